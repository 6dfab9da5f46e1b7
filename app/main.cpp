// phongsim command line: wires the subcommands (app/<command>.cpp) into one CLI.
// Exit status: 0 success; 1 verification failure (mismatch, deadlock, handshake violation, lint
// finding); 2 bad input or usage (one line on stderr, no output files written).
#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "base/error.h"

int main(int argc, char** argv) {
  using namespace phongsim::cli;
  CLI::App app{
      "phongsim: co-simulates fixed-point pixel-shading RTL against its bit-accurate "
      "C++ model.\nExit status: 0 ok, 1 verification failure, 2 bad input."};
  app.require_subcommand(1);
  Action action;
  add_cosim(app, action);
  add_eval(app, action);
  add_build_rtl(app, action);
  add_lint(app, action);
  add_synth(app, action);
  add_bench(app, action);
  add_sweep(app, action);
  add_render(app, action);
  add_vectors(app, action);
  add_analyze(app, action);
  add_list(app, action);
  add_contract(app, action);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "phongsim: error: {} (see phongsim --help)\n", e.what());
    return 2;
  }
  try {
    return action();
  } catch (const std::exception& e) {
    fmt::print(stderr, "phongsim: error: {}\n", e.what());
    return 2;
  }
}
