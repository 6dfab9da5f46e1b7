#include "sim/cosim/waveform.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "base/error.h"

// GTKWave's FST implementation, compiled here as Verilator compiles it into its runtime
// (verilated_fst_c.cpp): the reader part is what this file uses.
#define FST_CONFIG_INCLUDE "fst_config.h"
#include "gtkwave/fastlz.c"  // NOLINT
#include "gtkwave/fstapi.c"  // NOLINT
#include "gtkwave/lz4.c"     // NOLINT

namespace phongsim {

WaveFormat wave_format(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".fst") return WaveFormat::fst;
  if (ext == ".vcd") return WaveFormat::vcd;
  throw Error(fmt::format(
      "--trace {}: a waveform is .fst (compact, GTKWave) or .vcd (any viewer); name the file so",
      path.string()));
}

void fst_to_vcd(const std::filesystem::path& fst, std::FILE* vcd) {
  void* ctx = fstReaderOpen(fst.c_str());
  if (ctx == nullptr) throw Error(fmt::format("cannot read the waveform {}", fst.string()));
  fstReaderProcessHier(ctx, vcd);
  fstReaderSetFacProcessMaskAll(ctx);
  fstReaderIterBlocks(ctx, nullptr, nullptr, vcd);
  fstReaderClose(ctx);
}

}  // namespace phongsim
