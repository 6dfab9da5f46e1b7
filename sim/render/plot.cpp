#include "sim/render/plot.h"

#include <fmt/format.h>

#include "base/error.h"
#include "base/output_file.h"
#include "base/paths.h"
#include "base/process.h"
#include "base/text.h"

namespace phongsim {

namespace {

// What a failed run of the script said, as one line: its own "plot.py: ..." line (it reports
// every problem it can catch that way), else the interpreter's last line naming an error (a
// Python that cannot start), else its last line.
std::string complaint(std::string_view output, const std::vector<std::string>& argv, int code) {
  std::string_view own, error, last;
  while (!output.empty()) {
    const auto nl = output.find('\n');
    const std::string_view line = trim(output.substr(0, nl));
    output = nl == std::string_view::npos ? std::string_view{} : output.substr(nl + 1);
    if (line.empty()) continue;
    last = line;
    if (line.starts_with("plot.py: ")) own = line;
    if (line.find("Error") != std::string_view::npos) error = line;
  }
  if (!own.empty()) return std::string(own);
  return fmt::format("{} {} failed (exit status {}){}{}", argv[0], argv[1], code,
                     error.empty() && last.empty() ? "" : ": ", error.empty() ? last : error);
}

}  // namespace

void plot_figure(std::string_view figure, const std::vector<std::string>& args,
                 const std::filesystem::path& out) {
  OutputFile png(out);  // checks the destination now; removes the temporary file on failure
  plot_figure(figure, args, png);
  png.commit();
}

void plot_figure(std::string_view figure, const std::vector<std::string>& args, OutputFile& out) {
  std::vector<std::string> argv{python_program(), (data_root() / "scripts" / "plot.py").string(),
                                std::string(figure)};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), {"--out", out.temp_path().string()});
  const ProcessResult r = run_process(argv);
  if (r.exit_code != 0) {
    throw Error(fmt::format("cannot write {}: {}", out.path().string(),
                            complaint(r.out, argv, r.exit_code)));
  }
}

}  // namespace phongsim
