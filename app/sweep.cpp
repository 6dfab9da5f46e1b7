// phongsim sweep: bit-width exploration — run|plan|point|merge a sweep file, or search for the
// narrowest configuration within an error budget (docs/exploration.md). Each action is a
// subcommand of its own (its own --help).
#include <fmt/format.h>

#include <algorithm>
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
#include "base/text.h"
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
  Target rtl;  // the user's RTL (--rtl, -f, -F, -I, -D, --top): synthesized and verified per point
  std::uint64_t verify_vectors = 20000;
};

// The user's RTL for every point: synthesized instead of phongsim's and co-simulated (under
// random stalls) with the point's configuration. None without --rtl or -f.
std::optional<SweepRtl> sweep_rtl(const SweepFiles& c) {
  const RtlSources sources = c.rtl.checked_sources();
  if (!c.rtl.user_rtl()) {
    if (!c.rtl.top.empty()) throw Error("--top names the top of your RTL: give it (--rtl or -f)");
    return std::nullopt;
  }
  SweepRtl r;
  r.sources = sources;
  r.top = c.rtl.top;
  // The jobs of a plan run anywhere: absolute paths, the lists read into one --rtl.
  r.options = " --rtl";
  for (const fs::path& f : sources.files) r.options += " " + shell_quoted(fs::absolute(f).string());
  for (const fs::path& d : sources.include_dirs) {
    r.options += " " + shell_quoted("+incdir+" + fs::absolute(d).string());
  }
  for (const std::string& d : sources.defines) r.options += " " + shell_quoted("+define+" + d);
  if (!r.top.empty()) r.options += " --top " + shell_quoted(r.top);
  r.options += fmt::format(" --verify-vectors {}", c.verify_vectors);
  // The design's identity in every point's result (merge refuses a mix): its top, defines and
  // the content of its files, include folders' too, whatever the point's parameters.
  ContentHash id;
  const auto add_file = [&](const fs::path& f) { id.add(f.filename().string() + file_hash(f)); };
  const auto add_folder = [&](const fs::path& d) {  // an include folder: its headers too
    std::vector<fs::path> in;
    for (const auto& e : fs::directory_iterator(d)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".sv" || ext == ".v" || ext == ".svh" || ext == ".vh")) {
        in.push_back(e.path());
      }
    }
    std::sort(in.begin(), in.end());
    for (const fs::path& f : in) add_file(f);
  };
  for (const fs::path& f : rtl_files(sources.files)) add_file(f);
  for (const fs::path& d : sources.include_dirs) add_folder(d);
  for (const std::string& d : sources.defines) id.add("define " + d);
  const std::string identity = fmt::format(
      "{} from --rtl ({})", r.top.empty() ? "the built-in top" : r.top, id.hex().substr(0, 16));
  const Target rtl = c.rtl;
  const std::uint64_t vectors = quick_cap(c.verify_vectors, kQuickVectors);
  r.verify = [rtl, vectors, identity](const fs::path& config) {
    Target t = rtl;
    t.config = config.string();
    const Loaded l = load(t);
    CosimOptions o;
    o.random_vectors = vectors;
    o.source = StallPattern::parse("random:0.2");
    o.sink = StallPattern::parse("random:0.5");
    const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
    const CosimReport rep = cosim(subject_of(l, t, stimulus), o);
    if (!rep.passed) fmt::print(stderr, "{}", rep.failure);
    return SweepRtl::Verdict{rep.passed, rep.summary(), identity,
                             rep.measured ? static_cast<int>(rep.latency_max) : -1};
  };
  return r;
}

// Exit status of a sweep with the user's RTL: 1 when a point's co-simulation failed.
int sweep_status(const std::vector<PointResult>& results) {
  const std::string failed = failed_points(results);
  if (failed.empty()) return 0;
  fmt::print(stderr, "FAIL: {}\n", failed);
  return 1;
}

int run_plan(const SweepFiles& c) {
  const SweepSpec spec = load_sweep_quick(c.file);
  const std::optional<SweepRtl> rtl = sweep_rtl(c);
  const auto points = plan_sweep(spec, c.out, rtl ? &*rtl : nullptr);
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
  return sweep_status(results);
}

int run_run(const SweepFiles& c) {
  const SweepSpec spec = load_sweep_quick(c.file);
  const std::optional<SweepRtl> rtl = sweep_rtl(c);
  const auto results = run_sweep(spec, c.out, sweep_progress(), stderr, rtl ? &*rtl : nullptr);
  fmt::print("{}\n{} points: {}/sweep.csv, {}/summary.md\n",
             read_file(fs::path(c.out) / "summary.md"), results.size(), c.out, c.out);
  return sweep_status(results);
}

struct PointCli {
  std::string config, sweep, out;
  std::uint64_t index = 0;
  SweepFiles rtl;  // its --rtl words and --verify-vectors (sweep_rtl)
};

int run_point(const PointCli& c) {
  check_distinct({{"--out", c.out}, {"--sweep", c.sweep}, {"CONFIG", c.config}});
  const SweepSpec spec = load_sweep_quick(c.sweep);
  OutputFile out(c.out);  // unwritable: fail before the work
  const std::optional<SweepRtl> rtl = sweep_rtl(c.rtl);
  const PointResult r = evaluate_point(spec, c.config, c.index, stderr, rtl ? &*rtl : nullptr);
  std::fputs(point_result_json(r).c_str(), out.get());
  out.commit();
  fmt::print("point {}: max error {:.4g} LSB{}{}\n", c.index, r.error.max_lsb,
             r.synthesized && r.synth.cells >= 0 ? fmt::format(", {} cells", r.synth.cells) : "",
             r.verified ? fmt::format("; {}", r.verification) : "");
  return r.verified.value_or(true) ? 0 : 1;
}

struct SearchCli {
  std::string file, out, json, junit;
  bool verify = true;
  Target rtl;  // the user's RTL (--rtl, -f, -F, -I, -D, --top): what the verification runs
};

int run_search(const SearchCli& c) {
  SearchSpec spec = load_search(c.file);
  spec.verify_vectors = quick_cap(spec.verify_vectors, kQuickVectors);
  const Config base = Config::load(spec.base);
  // Never into the source tree or an installed prefix: the current folder unless --out says.
  const fs::path dest = c.out.empty() ? fs::path(spec.name + ".toml") : fs::path(c.out);
  if (!c.junit.empty() && !c.verify)
    throw Error("--junit reports the verification: not with --no-verify");
  if (c.rtl.user_rtl() && !c.verify) {
    throw Error("--rtl is what the verification runs: not with --no-verify");
  }
  (void)c.rtl.checked_sources();  // -I or -D without RTL
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
    Target t = c.rtl;  // the user's RTL, or phongsim's
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
          rep, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), {}};
      std::fputs(junit_xml(std::span(&run, 1)).c_str(), junit_file->get());
      junit_file->commit();
    }
    if (!rep.passed) {
      fmt::print(text, "{}", rep.failure);
      throw DesignFailure(fmt::format(
          "the found configuration fails co-simulation; not written to {}", dest.string()));
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

// --rtl, -f, -F, -I, -D, --top and --verify-vectors of run, plan and point.
void add_rtl_options(CLI::App& cmd, SweepFiles& c) {
  c.rtl.add_source_options(cmd);
  add_count(cmd, "--verify-vectors", c.verify_vectors,
            "with your RTL: random vectors of each point's co-simulation (under random stalls)",
            kMaxVectors)
      ->capture_default_str();
}

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
    if (run != run_merge) add_rtl_options(*sub, *c);
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
  add_rtl_options(*p, point->rtl);
  p->callback([point, &action]() { action = [point]() { return run_point(*point); }; });

  auto search = std::make_shared<SearchCli>();
  auto* s = cmd->add_subcommand(
      "search", "narrowest fraction bits of a base's signals within an error budget");
  s->add_option("file", search->file, "the search file (docs/exploration.md)")->required();
  s->add_option("--out,--write", search->out,
                "where the found configuration goes (default: <search name>.toml in the current "
                "folder; - is standard output; --write: the same, its older name)")
      ->type_name("FILE");
  s->add_option("--json", search->json,
                "also write the result as JSON (docs/json.md; - is standard output)");
  s->add_option("--junit", search->junit,
                "write the verification's co-simulation as JUnit XML (as cosim --junit)");
  s->add_flag("!--no-verify", search->verify,
              "skip Verilating and co-simulating the found configuration");
  search->rtl.add_source_options(*s);
  s->callback([search, &action]() { action = [search]() { return run_search(*search); }; });
}

}  // namespace phongsim::cli
