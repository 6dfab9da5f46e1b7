// phongsim sweep: bit-width exploration — run|plan|point|merge a sweep file, or search for the
// narrowest configuration within an error budget (docs/exploration.md). Each action is a
// subcommand of its own (its own --help).
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"
#include "base/file_util.h"
#include "base/output_file.h"
#include "base/paths.h"
#include "base/temporaries.h"
#include "sim/explore/search.h"
#include "sim/explore/sweep.h"

namespace phongsim::cli {
namespace {

namespace fs = std::filesystem;

// PHONGSIM_QUICK: fewer samples and no synthesis (docs/cosim.md).
SweepSpec load_sweep_quick(const std::string& file) {
  SweepSpec spec = load_sweep(file);
  if (quick_mode()) {
    spec.samples = std::min<std::uint64_t>(spec.samples, 500);
    spec.scene_size = std::min(spec.scene_size, 16);
    spec.synth = SynthOptions{false, false};
    if (spec.area == "lut4") spec.area = "cells";
  }
  return spec;
}

std::function<void(std::size_t, std::size_t)> sweep_progress() {
  const Progress line = progress_line();
  return [line](std::size_t done, std::size_t total) { line("sweep: points", done, total); };
}

struct SweepFiles {
  std::string file;
  std::string out = "sweep-out";
};

int run_plan(const SweepFiles& c) {
  const SweepSpec spec = load_sweep_quick(c.file);
  const auto points = plan_sweep(spec, c.out);
  fmt::print(
      "{} points: {}/points/*.toml; run {}/jobs.txt (e.g. parallel < jobs.txt, or a "
      "Slurm array: scripts/slurm-sweep.sh), or make -j -C {}; then phongsim sweep "
      "merge {} --out {}\n",
      points.size(), c.out, c.out, c.out, c.file, c.out);
  return 0;
}

int run_merge(const SweepFiles& c) {
  const SweepSpec spec = load_sweep_quick(c.file);
  const auto results = merge_sweep(spec, c.out);
  fmt::print("{} points merged: {}/sweep.csv, {}/summary.md{}\n", results.size(), c.out, c.out,
             spec.synth.generic || spec.synth.ice40 ? fmt::format(", {}/pareto.png", c.out) : "");
  return 0;
}

int run_run(const SweepFiles& c) {
  const SweepSpec spec = load_sweep_quick(c.file);
  const auto results = run_sweep(spec, c.out, sweep_progress(), stderr);
  fmt::print("{}\n{} points: {}/sweep.csv, {}/summary.md\n",
             read_file(fs::path(c.out) / "summary.md"), results.size(), c.out, c.out);
  return 0;
}

struct PointCli {
  std::string config, sweep, out;
  std::uint64_t index = 0;
};

int run_point(const PointCli& c) {
  check_distinct({{"--out", c.out}, {"--sweep", c.sweep}, {"CONFIG", c.config}});
  const SweepSpec spec = load_sweep_quick(c.sweep);
  OutputFile out(c.out);  // unwritable: fail before the work
  const PointResult r = evaluate_point(spec, c.config, c.index, stderr);
  std::fputs(point_result_json(r).c_str(), out.get());
  out.commit();
  fmt::print("point {}: max error {:.4g} LSB{}\n", c.index, r.error.max_lsb,
             r.synthesized && r.synth.cells >= 0 ? fmt::format(", {} cells", r.synth.cells) : "");
  return 0;
}

struct SearchCli {
  std::string file, out, json, junit;
  bool verify = true;
};

int run_search(const SearchCli& c) {
  SearchSpec spec = load_search(c.file);
  spec.verify_vectors = quick_cap(spec.verify_vectors, kQuickVectors);
  const Config base = Config::load(spec.base);
  const fs::path dest = c.out.empty()
                            ? data_root() / "configs" / base.pipeline() / (spec.name + ".toml")
                            : fs::path(c.out);
  if (!c.junit.empty() && !c.verify)
    throw Error("--junit reports the verification: not with --no-verify");
  check_distinct({{"--out", dest},
                  {"--json", c.json},
                  {"--junit", c.junit},
                  {"SEARCH", c.file},
                  {"base", spec.base}});
  JsonOutput json(c.json);
  std::optional<OutputFile> junit_file;
  if (!c.junit.empty()) junit_file.emplace(c.junit);
  if (junit_file && junit_file->is_stdout()) throw Error("--junit -: give --junit a file");
  OutputFile found(dest);  // unwritable: fail before the search
  std::FILE* const text = found.is_stdout() ? stderr : json.text();
  const Progress progress = progress_line();
  const SearchResult r = search_min_width(
      spec, [text](std::string_view s) { fmt::print(text, "  {}\n", s); },
      [&](std::size_t n) { progress("search: evaluations", n, 0); });
  progress("search: evaluations", 1, 1);
  fmt::print(text, "found after {} evaluations: {} fraction bits fewer, max error {:.4g} LSB{}\n",
             r.evaluations, r.bits_saved, r.error.max_lsb,
             std::isnan(r.colour_correctness)
                 ? ""
                 : fmt::format(", colour correctness {:.5f}", r.colour_correctness));
  for (const auto& [sig, f] : r.formats) fmt::print(text, "  {} = {}\n", sig, f);
  std::fputs(r.toml.c_str(), found.get());
  nlohmann::ordered_json j = json_document("sweep search");
  j["search"] = c.file;
  j["name"] = spec.name;
  j["base"] = spec.base.string();
  j["pipeline"] = base.pipeline();
  j["evaluations"] = r.evaluations;
  j["bits_saved"] = r.bits_saved;
  j["formats"] = nlohmann::ordered_json::object();
  for (const auto& [sig, f] : r.formats) j["formats"][sig] = f;
  j["max_error_lsb"] = r.error.max_lsb;
  j["mean_error_lsb"] = r.error.mean_lsb;
  j["colour_correctness"] = json_number(r.colour_correctness);
  j["verified"] = nullptr;
  if (c.verify) {
    // Verilate the found point and co-simulate it before it lands at `dest`.
    const TempDir dir("search");
    const fs::path candidate =
        dir.path() / (dest.filename() == "-" ? fs::path(spec.name + ".toml") : dest.filename());
    {
      OutputFile f(candidate);
      std::fputs(r.toml.c_str(), f.get());
      f.commit();
    }
    Target t;
    t.config = candidate.string();
    const Loaded l = load(t);
    CosimOptions o;
    o.random_vectors = spec.verify_vectors;
    o.source = StallPattern::parse("random:0.2");
    o.sink = StallPattern::parse("random:0.5");
    o.progress = [&](std::uint64_t done, std::uint64_t all) {
      progress("search: verifying", done, all);
    };
    const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
    const auto start = std::chrono::steady_clock::now();
    const CosimReport rep = cosim(subject_of(l, t, stimulus), o);
    progress("search: verifying", 1, 1);
    if (junit_file) {  // written whether the verification passes or not
      const CosimRun run{
          rep, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
      std::fputs(junit_xml(std::span(&run, 1)).c_str(), junit_file->get());
      junit_file->commit();
    }
    if (!rep.passed) {
      fmt::print(text, "{}", rep.failure);
      throw Error(fmt::format("the found configuration fails co-simulation; not written to {}",
                              dest.string()));
    }
    fmt::print(text, "verified: {}\n", rep.summary());
    j["verified"] = {{"passed", rep.passed},
                     {"vectors", rep.vectors},
                     {"outputs", rep.outputs},
                     {"cycles", rep.cycles},
                     {"summary", rep.summary()}};
  }
  j["written"] = dest.string();
  found.commit();
  json.write(j);
  fmt::print(text, "wrote {}\n", dest.string());
  return 0;
}

}  // namespace

void add_sweep(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "sweep",
      "Bit-width exploration: run|plan|point|merge a sweep file, or search for the "
      "narrowest configuration within an error budget (docs/exploration.md); phongsim sweep "
      "ACTION --help for each");
  cmd->require_subcommand(1);

  const auto add_files = [&](const char* name, const char* what, int (*run)(const SweepFiles&)) {
    auto c = std::make_shared<SweepFiles>();
    auto* sub = cmd->add_subcommand(name, what);
    sub->add_option("file", c->file, "the sweep file")->required();
    sub->add_option("--out", c->out, "the sweep's directory (docs/exploration.md)")
        ->capture_default_str();
    sub->callback([c, run, &action]() { action = [c, run]() { return run(*c); }; });
  };
  add_files("run", "plan, evaluate every point here, merge: DIR/sweep.csv, summary.md, pareto.*",
            run_run);
  add_files("plan",
            "write DIR/points/NNNN.toml, DIR/jobs.txt (one command per point) and DIR/Makefile, "
            "for parallel, make or Slurm",
            run_plan);
  add_files("merge",
            "collect DIR/results/*.json into DIR/sweep.csv, summary.md, pareto.csv, pareto.png",
            run_merge);

  auto point = std::make_shared<PointCli>();
  auto* p = cmd->add_subcommand("point", "evaluate one planned point (one line of jobs.txt)");
  p->add_option("config", point->config, "the point's configuration (DIR/points/NNNN.toml)")
      ->required();
  p->add_option("--sweep", point->sweep, "the sweep file it belongs to")->required();
  add_count(*p, "--index", point->index, "the point's index", kMaxSweepPoints - 1)->required();
  p->add_option("--out", point->out, "the result JSON (DIR/results/NNNN.json)")->required();
  p->callback([point, &action]() { action = [point]() { return run_point(*point); }; });

  auto search = std::make_shared<SearchCli>();
  auto* s = cmd->add_subcommand(
      "search", "narrowest fraction bits of a base's signals within an error budget");
  s->add_option("file", search->file, "the search file (docs/exploration.md)")->required();
  s->add_option("--out,--write", search->out,
                "where the found configuration goes (default configs/<pipeline>/<search "
                "name>.toml; - is standard output; --write: the same, its older name)");
  s->add_option("--json", search->json,
                "also write the result as JSON (docs/json.md; - is standard output)");
  s->add_option("--junit", search->junit,
                "write the verification's co-simulation as JUnit XML (as cosim --junit)");
  s->add_flag("!--no-verify", search->verify,
              "skip Verilating and co-simulating the found configuration");
  s->callback([search, &action]() { action = [search]() { return run_search(*search); }; });
}

}  // namespace phongsim::cli
