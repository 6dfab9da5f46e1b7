// Waveform formats. The Verilated plugins trace to FST (the runtime they share is built with
// VerilatedFstC); a VCD is the same waveform converted by the FST reader of GTKWave's fstapi,
// which Verilator ships (the conversion GTKWave's fst2vcd does).
#pragma once

#include <cstdio>
#include <filesystem>

namespace phongsim {

enum class WaveFormat { fst, vcd };

// The format a waveform path asks for by its extension (.fst or .vcd, any case); Error naming
// the path otherwise.
[[nodiscard]] WaveFormat wave_format(const std::filesystem::path& path);

// Writes the FST file `fst` to `vcd` as a Value Change Dump. Error when it cannot be read.
void fst_to_vcd(const std::filesystem::path& fst, std::FILE* vcd);

}  // namespace phongsim
