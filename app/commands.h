// The phongsim subcommands, one file each (app/<command>.cpp). Each adds its subcommand to the
// app and, when the command line selects it, sets `action` to what it runs.
#pragma once

#include <CLI/CLI.hpp>

#include "app/cli.h"

namespace phongsim::cli {

void add_cosim(CLI::App& app, Action& action);
void add_eval(CLI::App& app, Action& action);
void add_vectors(CLI::App& app, Action& action);
void add_build_rtl(CLI::App& app, Action& action);
void add_lint(CLI::App& app, Action& action);
void add_synth(CLI::App& app, Action& action);
void add_bench(CLI::App& app, Action& action);
void add_analyze(CLI::App& app, Action& action);
void add_list(CLI::App& app, Action& action);
void add_contract(CLI::App& app, Action& action);
void add_render(CLI::App& app, Action& action);
void add_sweep(CLI::App& app, Action& action);
void add_study(CLI::App& app, Action& action);

}  // namespace phongsim::cli
