// phongsim command line: wires the subcommands (app/<command>.cpp) into one CLI.
// Exit status: 0 success; 1 verification failure (mismatch, deadlock, handshake violation, lint
// finding); 2 bad input or usage (one line on stderr, no output files written); 128 + N when
// signal N ended it (130 SIGINT, 143 SIGTERM), its temporary files removed.
#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include <malloc.h>
#include <new>
#include <string_view>

#include "app/cli.h"
#include "app/commands.h"
#include "base/error.h"
#include "base/process.h"
#include "base/temporaries.h"
#include "model/plan.h"
#include "sim/cosim/rtl_plugin.h"

namespace phongsim {
extern const char* const kRevision;  // generated at build time (cmake/Revision.cmake)
}

namespace {

// The first line a tool prints for its version, or why there is none.
std::string tool_version(const std::vector<std::string>& argv) {
  const phongsim::ProcessResult r = phongsim::run_process(argv);
  if (r.exit_code != 0) return "not found";
  const std::string_view out = r.out;
  return std::string(out.substr(0, out.find('\n')));
}

std::string names_of(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return names;
}

// What is wrong with the command words of argv: an unknown command or action, a missing action,
// an unknown option before any command; "" when CLI11 can take it from here.
std::string command_problem(CLI::App& app, int argc, char** argv) {
  const CLI::App* at = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string_view word = argv[i];
    const bool help = word == "-h" || word == "--help" || word == "--help-all";
    if (help) return "";
    const bool groups = !at->get_subcommands([](const CLI::App*) { return true; }).empty();
    if (!groups) return "";  // a command's own arguments: CLI11 checks them
    if (word.starts_with("-")) {
      if (at == &app && word != "--version") {
        return fmt::format("unknown option '{}' before the command (see phongsim --help)", word);
      }
      if (at != &app) {
        return fmt::format("{} needs an action ({}; see phongsim {} --help)", at->get_name(),
                           names_of(*at), at->get_name());
      }
      return "";
    }
    const CLI::App* next = nullptr;
    for (const CLI::App* sub : at->get_subcommands([](const CLI::App*) { return true; })) {
      if (sub->get_name() == word) next = sub;
    }
    if (next == nullptr) {
      if (at == &app) {
        return fmt::format("unknown command '{}' (commands: {}; see phongsim --help)", word,
                           names_of(app));
      }
      return fmt::format("unknown {} action '{}' (actions: {}; see phongsim {} --help)",
                         at->get_name(), word, names_of(*at), at->get_name());
    }
    at = next;
  }
  if (at != &app && !at->get_subcommands([](const CLI::App*) { return true; }).empty()) {
    return fmt::format("{} needs an action ({}; see phongsim {} --help)", at->get_name(),
                       names_of(*at), at->get_name());
  }
  return "";
}

int print_version() {
  fmt::print("phongsim {} ({})\n  {}\n  {}\n", PHONGSIM_VERSION, phongsim::kRevision,
             tool_version({"verilator", "--version"}), tool_version({"yosys", "-V"}));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace phongsim::cli;
  phongsim::install_signal_cleanup();
  // Freed buffers stay with the process for the next to reuse: every co-simulation shard,
  // sweep point and bench run allocates its batch buffers afresh, and with glibc's defaults
  // they went back to the kernel and were page-faulted in again each time (most of a small
  // co-simulation's time; docs/performance.md).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  CLI::App app{
      "phongsim: co-simulates fixed-point pixel-shading RTL against its bit-accurate "
      "C++ model.\nExit status: 0 ok, 1 verification failure, 2 bad input; 130/143 when "
      "interrupted (SIGINT/SIGTERM)."};
  app.require_subcommand(1);
  bool version = false;
  app.add_flag("--version", version,
               "print phongsim's version and git revision, and the Verilator and Yosys it runs");
  Action action;
  add_cosim(app, action);
  add_eval(app, action);
  add_build_rtl(app, action);
  add_lint(app, action);
  add_synth(app, action);
  add_bench(app, action);
  add_sweep(app, action);
  add_render(app, action);
  add_study(app, action);
  add_vectors(app, action);
  add_analyze(app, action);
  add_list(app, action);
  add_contract(app, action);
  add_common_options(app);  // plain --help, and --progress on every command

  phongsim::cli::set_invocation(argc > 0 ? argv[0] : "phongsim");
  try {
    install_tool_progress();
    // Housekeeping first: temporaries of phongsim processes that were killed outright.
    phongsim::sweep_stale_temporaries(
        {phongsim::rtl_cache_dir(), phongsim::rtl_cache_dir() / "synth"});
    if (argc == 2 && std::string_view(argv[1]) == "--version") return print_version();
    // A bad $PHONGSIM_ISA is refused now, not in the first worker thread that runs a kernel.
    (void)phongsim::fx::kernel_isa();
    // Words that are no options name a command (and its action, for sweep): say which one is
    // not known, rather than CLI11's "A subcommand is required".
    if (const std::string problem = command_problem(app, argc, argv); !problem.empty()) {
      fmt::print(stderr, "phongsim: error: {}\n", problem);
      return 2;
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "phongsim: error: {}\n", e.what());
    return 2;
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (version) return print_version();
    fmt::print(stderr, "phongsim: error: {} (see phongsim --help)\n", e.what());
    return 2;
  }
  // An empty value names nothing: `--json ''` would otherwise quietly write no file.
  for (const CLI::App* cmd = &app; cmd != nullptr;) {
    for (const CLI::Option* opt : cmd->get_options()) {
      for (const std::string& value : opt->results()) {
        if (value.empty() && opt->get_expected_min() > 0) {
          fmt::print(stderr, "phongsim: error: {} is given an empty value (see phongsim --help)\n",
                     opt->get_name());
          return 2;
        }
      }
    }
    const auto subs = cmd->get_subcommands();
    cmd = subs.empty() ? nullptr : subs.front();
  }
  try {
    return action();
  } catch (const phongsim::DesignFailure& e) {
    fmt::print(stderr, "phongsim: FAIL: {}\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr,
               "phongsim: error: out of memory (the request needs more memory than this "
               "process may use: ask for fewer vectors, samples or pixels)\n");
    return 2;
  } catch (const std::length_error& e) {
    fmt::print(stderr, "phongsim: error: out of memory (a buffer would exceed its limit: {})\n",
               e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "phongsim: error: {}\n", e.what());
    return 2;
  }
}
