// phongsim sweep: bit-width exploration — run|plan|point|merge a sweep file, or search for the
// narrowest configuration within an error budget (docs/exploration.md).
#include <fmt/format.h>
#include <unistd.h>

#include <cmath>

#include "app/commands.h"
#include "base/error.h"
#include "base/file_util.h"
#include "base/output_file.h"
#include "base/paths.h"
#include "sim/explore/search.h"
#include "sim/explore/sweep.h"

namespace phongsim::cli {
namespace {

namespace fs = std::filesystem;

struct SweepCli {
  std::string action, file, out = "sweep-out", sweep, write;
  std::size_t index = 0;
  bool verify = true;
};

std::function<void(std::size_t, std::size_t)> sweep_progress() {
  if (isatty(STDERR_FILENO) == 0) return [](std::size_t, std::size_t) {};
  return [](std::size_t done, std::size_t total) {
    fmt::print(stderr, "\r\033[K  sweep: point {}/{}", done, total);
    if (done == total) fmt::print(stderr, "\r\033[K");
  };
}

int run_sweep_action(const std::string& action, const std::string& file, const std::string& out,
                     const std::string& sweep_file, std::size_t index, const std::string& write,
                     bool verify) {
  if (action == "point") {  // one job of a plan: evaluate a point's configuration
    const SweepSpec spec = load_sweep(sweep_file);
    OutputFile check(out);  // unwritable: fail before the work
    const PointResult r = evaluate_point(spec, file, index, stderr);
    write_point_result(r, out);
    fmt::print("point {}: max error {:.4g} LSB{}\n", index, r.error.max_lsb,
               r.synthesized ? fmt::format(", {} cells", r.synth.cells) : "");
    return 0;
  }
  if (action == "search") {
    const SearchSpec spec = load_search(file);
    const SearchResult r =
        search_min_width(spec, [](std::string_view s) { fmt::print("  {}\n", s); });
    const Config base = Config::load(spec.base);
    const fs::path dest = write.empty()
                              ? data_root() / "configs" / base.pipeline() / (spec.name + ".toml")
                              : fs::path(write);
    fmt::print("found after {} evaluations: {} fraction bits fewer, max error {:.4g} LSB{}\n",
               r.evaluations, r.bits_saved, r.error.max_lsb,
               std::isnan(r.colour_correctness)
                   ? ""
                   : fmt::format(", colour correctness {:.5f}", r.colour_correctness));
    for (const auto& [sig, f] : r.formats) fmt::print("  {} = {}\n", sig, f);
    OutputFile found(dest);  // unwritable: fail before Verilating
    std::fputs(r.toml.c_str(), found.get());
    if (verify) {
      // Verilate the found point and co-simulate it before it lands at `dest`.
      const fs::path dir = fs::temp_directory_path() / fmt::format("phongsim-search-{}", getpid());
      fs::create_directories(dir);
      const std::shared_ptr<void> cleanup(nullptr, [dir](void*) {
        std::error_code ec;
        fs::remove_all(dir, ec);
      });
      const fs::path candidate = dir / dest.filename();
      {
        OutputFile c(candidate);
        std::fputs(r.toml.c_str(), c.get());
        c.commit();
      }
      Target t;
      t.config = candidate.string();
      const Loaded l = load(t);
      CosimOptions o;
      o.random_vectors = spec.verify_vectors;
      o.source = StallPattern::parse("random:0.2");
      o.sink = StallPattern::parse("random:0.5");
      const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
      const CosimReport rep = cosim(subject_of(l, t, stimulus), o);
      if (!rep.passed) {
        fmt::print("{}", rep.failure);
        throw Error(fmt::format("the found configuration fails co-simulation; not written to {}",
                                dest.string()));
      }
      fmt::print("verified: {}\n", rep.summary());
    }
    found.commit();
    fmt::print("wrote {}\n", dest.string());
    return 0;
  }
  const SweepSpec spec = load_sweep(file);
  if (action == "plan") {
    const auto points = plan_sweep(spec, out);
    fmt::print(
        "{} points: {}/points/*.toml; run {}/jobs.txt (e.g. parallel < jobs.txt, or a "
        "Slurm array: scripts/slurm-sweep.sh), or make -j -C {}; then phongsim sweep "
        "merge {} --out {}\n",
        points.size(), out, out, out, file, out);
    return 0;
  }
  if (action == "merge") {
    const auto results = merge_sweep(spec, out);
    fmt::print("{} points merged: {}/sweep.csv, {}/summary.md{}\n", results.size(), out, out,
               spec.synth.generic || spec.synth.ice40 ? fmt::format(", {}/pareto.png", out) : "");
    return 0;
  }
  if (action == "run") {
    const auto results = run_sweep(spec, out, sweep_progress(), stderr);
    fmt::print("{}\n{} points: {}/sweep.csv, {}/summary.md\n",
               read_file(fs::path(out) / "summary.md"), results.size(), out, out);
    return 0;
  }
  throw Error(fmt::format("unknown sweep action '{}' (run, plan, point, merge, search)", action));
}

}  // namespace

void add_sweep(CLI::App& app, Action& action) {
  auto c = std::make_shared<SweepCli>();
  auto* cmd = app.add_subcommand(
      "sweep",
      "Bit-width exploration: run|plan|point|merge a sweep file, or search for the "
      "narrowest configuration within an error budget (docs/exploration.md)");
  cmd->add_option("action", c->action, "run, plan, point, merge or search")->required();
  cmd->add_option("file", c->file,
                  "the sweep file (point: the point's configuration; search: the search "
                  "file)")
      ->required();
  cmd->add_option("--out", c->out, "output directory (point: the result JSON)")
      ->capture_default_str();
  cmd->add_option("--sweep", c->sweep, "point: the sweep file it belongs to");
  cmd->add_option("--index", c->index, "point: its index");
  cmd->add_option("--write", c->write,
                  "search: where the found configuration goes (default "
                  "configs/<pipeline>/<search name>.toml)");
  cmd->add_flag("!--no-verify", c->verify,
                "search: skip Verilating and co-simulating the found configuration");
  cmd->callback([c, &action]() {
    action = [c]() {
      if (c->action == "point" && c->sweep.empty()) throw Error("sweep point needs --sweep");
      return run_sweep_action(c->action, c->file, c->out, c->sweep, c->index, c->write, c->verify);
    };
  });
}

}  // namespace phongsim::cli
