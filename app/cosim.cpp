// phongsim cosim: model and Verilated RTL on directed + seeded random vectors, compared bit by
// bit under stall patterns (docs/cosim.md). Several configurations and comma-separated stall
// patterns make a matrix: one run per configuration x source pattern x sink pattern, each a
// testcase of the --junit report.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <optional>
#include <sstream>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"
#include "base/output_file.h"
#include "base/temporaries.h"
#include "sim/cosim/coverage.h"
#include "sim/cosim/coverpoints.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/cosim/waveform.h"

namespace phongsim::cli {
namespace {

struct CosimCli {
  Target target;
  CosimOptions options;
  std::uint64_t vectors = 0;
  std::uint64_t vector_index = 0;
  std::string source = "none";
  std::string sink = "none";
  std::string trace;
  std::string json;
  std::string junit;
  std::string coverage;
  std::string waivers;  // --waivers FILE: the user's waivers (with --coverage)
  bool no_toggle = false;
  CLI::Option* vectors_opt = nullptr;
  CLI::Option* index_opt = nullptr;
};

nlohmann::ordered_json to_json(const FieldValue& v) {
  return {{"field", v.name}, {"format", v.format}, {"raw", v.raw}, {"real", v.real}};
}

// The line points a waiver left out, each with its reason and, for the user's, the waiver
// ("waivers.txt:3"; null for a configuration's).
nlohmann::ordered_json waived_json(const std::vector<WaivedPoint>& waived) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const WaivedPoint& w : waived) {
    a.push_back({{"file", w.file},
                 {"lines", w.lines},
                 {"instance", w.instance},
                 {"reason", w.reason},
                 {"waiver", w.waiver.empty() ? nlohmann::ordered_json(nullptr)
                                             : nlohmann::ordered_json(w.waiver)}});
  }
  return a;
}

// The coverage points and signals of the target's design (probe_design): one DUT of the
// coverage plugin the runs will use, built now if it is not yet (as rtl_of would).
DesignProbe probe_of(const Loaded& l, const Target& t) {
  RtlDesign design = design_of(l, t);
  if (t.x_init == "random") design.x_init = XInit::random;
  design.coverage = true;
  design.coverage_toggle = t.coverage_toggle;
  RtlPlugin plugin;
  DesignProbe p = probe_design([&](const std::string& prefix) {
    return rtl_duts(design, *l.model, t.no_build ? RtlBuild::never : RtlBuild::if_missing, stderr,
                    &plugin, static_cast<std::uint32_t>(t.x_init_seed()), prefix)();
  });
  p.moved = moved_sources(plugin, design);
  p.points = relocated(p.points, p.moved);
  return p;
}

// The report's lines on what the user's waivers left out: one per waiver, its points by file
// and lines, and its reason.
void print_user_waivers(std::FILE* text, const CoverageSummary& s) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const WaivedPoint*>> by;
  for (const WaivedPoint& w : s.waived) {
    if (w.waiver.empty()) continue;
    if (!by.contains(w.waiver)) order.push_back(w.waiver);
    by[w.waiver].push_back(&w);
  }
  for (const std::string& origin : order) {
    const auto& points = by[origin];
    std::vector<std::string> where;
    for (const WaivedPoint* p : points) {
      std::string f = p->file.substr(p->file.rfind('/') + 1);
      where.push_back(fmt::format("{}:{} in {}", f, p->lines, p->instance));
    }
    fmt::print(text, "waived by {} ({} line point{}: {}): {}\n", origin, points.size(),
               points.size() == 1 ? "" : "s", fmt::join(where, ", "), points.front()->reason);
  }
}

// The design's signals without toggle points; null when they were not checked (no toggle data).
nlohmann::ordered_json not_toggled_json(const CoverageSummary& s) {
  if (!s.signals_checked) return nullptr;
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const UncountedSignal& u : s.not_toggled) {
    a.push_back({{"signal", u.path}, {"bits", u.bits}, {"why", u.why}});
  }
  return a;
}

nlohmann::ordered_json to_json(const CosimFailure& f, const std::string& report) {
  nlohmann::ordered_json inputs = nlohmann::ordered_json::array();
  for (const FieldValue& v : f.inputs) inputs.push_back(to_json(v));
  nlohmann::ordered_json outputs = nlohmann::ordered_json::array();
  for (const FieldComparison& c : f.outputs) {
    outputs.push_back(
        {{"field", c.name},
         {"format", c.format},
         {"expected", c.expected ? to_json(*c.expected) : nlohmann::ordered_json(nullptr)},
         {"got", c.got ? to_json(*c.got) : nlohmann::ordered_json(nullptr)},
         {"differs", c.differs}});
  }
  nlohmann::ordered_json stages = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < f.stages.size(); ++i) {
    nlohmann::ordered_json v = to_json(f.stages[i]);
    if (i < f.sightings.size()) {  // the design's signals of the stage's name
      nlohmann::ordered_json signals = nlohmann::ordered_json::array();
      for (const StageSighting::Signal& g : f.sightings[i].signals) {
        signals.push_back({{"path", g.path}, {"held", g.held}});
      }
      v["signals"] = signals;
    }
    stages.push_back(std::move(v));
  }
  const auto optional = [](const std::optional<std::uint64_t>& v) {
    return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
  };
  return {{"kind", f.kind},
          {"cycle", f.cycle},
          {"vector_index", optional(f.vector)},
          {"output_index", optional(f.output)},
          {"outputs_of_vector", f.vector && f.output ? nlohmann::ordered_json(f.outputs_of_vector)
                                                     : nlohmann::ordered_json(nullptr)},
          {"inputs", inputs},
          {"outputs", outputs},
          {"stages", stages},
          {"first_differing_stage", f.first_differing_stage.empty()
                                        ? nlohmann::ordered_json(nullptr)
                                        : nlohmann::ordered_json(f.first_differing_stage)},
          {"contract", f.contract.empty() ? nlohmann::ordered_json(nullptr)
                                          : nlohmann::ordered_json(f.contract)},
          {"message", f.message},
          {"in_measurement_run", f.in_measurement_run},
          {"report", report}};
}

nlohmann::ordered_json to_json(const CosimRun& run, const Target& t) {
  const CosimReport& r = run.report;
  return {
      {"pipeline", r.pipeline},
      {"config", r.config_name},
      {"config_path", r.config_path},
      {"rtl", rtl_json(run.rtl)},
      {"x_init", t.x_init_mode()},
      {"x_seed", t.x_init_seed() != 0 ? nlohmann::ordered_json(t.x_init_seed())
                                      : nlohmann::ordered_json(nullptr)},
      {"seed", r.options.seed},
      {"vectors", r.vectors},
      {"directed_vectors", r.directed},
      {"random_vectors", r.random},
      {"in_contract",
       r.contract ? nlohmann::ordered_json(r.contract->in) : nlohmann::ordered_json(nullptr)},
      {"out_of_contract",
       r.contract ? nlohmann::ordered_json(r.contract->out()) : nlohmann::ordered_json(nullptr)},
      {"contract_clauses", r.contract ? contract_json(r.contract_clauses, *r.contract)
                                      : nlohmann::ordered_json(nullptr)},
      {"outputs", r.outputs},
      {"mismatches", r.mismatches},
      {"cycles", r.cycles},
      {"duts", r.duts},
      {"longest_since_reset", {{"vectors", r.longest_vectors}, {"outputs", r.longest_outputs}}},
      {"reset_every", r.options.reset_every != 0 ? nlohmann::ordered_json(r.options.reset_every)
                                                 : nlohmann::ordered_json(nullptr)},
      {"drain_cycles", r.drain_cycles},
      {"source_idle", r.options.source.str()},
      {"backpressure", r.options.sink.str()},
      {"throughput",
       r.measured ? nlohmann::ordered_json(r.throughput) : nlohmann::ordered_json(nullptr)},
      {"latency", r.measured
                      ? nlohmann::ordered_json{{"min", r.latency_min}, {"max", r.latency_max}}
                      : nlohmann::ordered_json(nullptr)},
      {"passed", r.passed},
      {"seconds", run.seconds},
      {"trace", r.trace_written.empty() ? nlohmann::ordered_json(nullptr)
                                        : nlohmann::ordered_json(r.trace_written)},
      {"failure",
       r.failure_detail ? to_json(*r.failure_detail, r.failure) : nlohmann::ordered_json(nullptr)},
  };
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  if (parts.empty()) parts.emplace_back();
  return parts;
}

int run(CosimCli& c) {
  std::vector<std::string> configs = c.target.configs;
  if (configs.empty()) configs.emplace_back();  // the pipeline's default configuration
  const std::vector<std::string> sources = split_commas(c.source);
  const std::vector<std::string> sinks = split_commas(c.sink);
  std::vector<StallPattern> source_patterns, sink_patterns;
  for (const auto& s : sources) source_patterns.push_back(StallPattern::parse(s));
  for (const auto& s : sinks) sink_patterns.push_back(StallPattern::parse(s));
  const std::size_t total = configs.size() * sources.size() * sinks.size();
  c.target.check_x_init();
  if (*c.vectors_opt && c.vectors == 0 && !c.options.directed && !*c.index_opt) {
    throw Error(
        "nothing to check: --vectors 0 with --no-directed gives no vectors, and a run that "
        "checks nothing cannot pass");
  }
  if (!c.coverage.empty() && c.target.simulator == "icarus") {
    throw Error(
        "--coverage is Verilator's (line and toggle coverage): not with --simulator icarus");
  }
  if (c.no_toggle && c.coverage.empty()) {
    throw Error("--no-toggle-coverage goes with --coverage DIR");
  }
  if (!c.waivers.empty() && c.coverage.empty()) {
    throw Error("--waivers goes with --coverage DIR");
  }
  if (!c.coverage.empty() && !c.target.plugin.empty()) {
    throw Error("--coverage builds a plugin of its own: not with --rtl-plugin");
  }
  if (!c.trace.empty() && c.target.simulator == "icarus") {
    throw Error("--trace is not available with --simulator icarus (use the Verilator build)");
  }
  if (total > 1 && (!c.trace.empty() || *c.index_opt)) {
    throw Error(
        "--trace and --vector-index take one run: give one --config and one pattern each for "
        "--source-idle and --backpressure");
  }
  const WaveFormat wave = c.trace.empty() ? WaveFormat::fst : wave_format(c.trace);
  const std::vector<std::pair<std::string, std::filesystem::path>> outputs{
      {"--json", c.json}, {"--junit", c.junit}, {"--trace", c.trace}};
  std::vector<std::pair<std::string, std::filesystem::path>> inputs = c.target.inputs();
  if (!c.waivers.empty()) inputs.emplace_back("--waivers", c.waivers);
  check_outputs(outputs, inputs);
  if (!c.coverage.empty()) {  // a folder of outputs: nothing read or written elsewhere in it
    for (const auto& [name, path] : outputs) {
      if (!path.empty() && path != "-" &&
          (same_destination(path, c.coverage) || inside(path, c.coverage))) {
        throw Error(fmt::format("{} {} lies in the --coverage folder {}, which phongsim fills",
                                name, path.string(), c.coverage));
      }
    }
    for (const auto& [name, path] : inputs) {
      if (!path.empty() && (same_destination(path, c.coverage) || inside(path, c.coverage))) {
        throw Error(
            fmt::format("{} {} lies in the --coverage folder {}: an output folder may "
                        "not hold what the command reads",
                        name, path.string(), c.coverage));
      }
    }
  }
  // Every configuration and its RTL first, so bad input stops the command before any run.
  CoverageInputs coverage_inputs;
  if (!c.waivers.empty()) coverage_inputs.user_waivers = read_waivers(c.waivers);
  std::vector<Loaded> loaded;
  std::vector<Target> targets;
  for (const auto& config : configs) {
    Target t = c.target;
    t.config = config;
    loaded.push_back(load(t));
    targets.push_back(t);
  }
  if (!c.coverage.empty()) {
    // Each design's coverage points and signals before any run: a stale waiver stops the
    // command here, and the signals Verilator counts no toggles of are listed after the runs.
    std::map<std::string, std::uint64_t> declared;
    for (std::size_t k = 0; k < loaded.size(); ++k) {
      Target t = targets[k];
      t.coverage_toggle = !c.no_toggle;
      DesignProbe p = probe_of(loaded[k], t);
      declared.merge(p.points);
      coverage_inputs.moved.merge(p.moved);
      if (!c.no_toggle) {
        for (WaveSignal& s : p.signals) coverage_inputs.signals.push_back(std::move(s));
      }
    }
    check_waivers(declared, coverage_inputs.user_waivers);
  }
  JsonOutput json(c.json);
  if (!c.coverage.empty()) {
    // One prefix per configuration: each plugin numbers its DUTs' files from 0.
    const std::string prefix = coverage_prefix(c.coverage);
    for (std::size_t k = 0; k < targets.size(); ++k) {
      targets[k].coverage_prefix = fmt::format("{}{}-", prefix, k);
      targets[k].coverage_toggle = !c.no_toggle;
    }
  }
  std::optional<OutputFile> trace_file;
  std::optional<OutputFile> junit_file;
  std::optional<TempDir> fst_dir;  // a VCD is converted from an FST written here
  if (!c.junit.empty()) junit_file.emplace(c.junit);
  std::FILE* const text = json.text();
  if (junit_file && junit_file->is_stdout()) {
    throw Error("--junit -: standard output carries the report; give --junit a file");
  }
  CosimOptions o = c.options;
  if (!c.trace.empty()) {
    trace_file.emplace(c.trace);
    if (wave == WaveFormat::vcd) {
      fst_dir.emplace("out");
      o.trace_path = (fst_dir->path() / "trace.fst").string();
    } else {
      o.trace_path = trace_file->temp_path().string();
    }
  }
  const Progress progress = progress_line();
  std::vector<CosimRun> runs;
  // With --coverage: this command's functional coverpoints, every configuration's prefixed
  // "<pipeline>/<config>:", and the stall-pattern classes of its runs.
  Coverpoints points;
  std::vector<LineWaiver>& line_waivers = coverage_inputs.line_waivers;
  if (!c.coverage.empty()) declare_stall_classes(points);
  for (std::size_t k = 0; k < loaded.size(); ++k) {
    const Loaded& l = loaded[k];
    o.random_vectors =
        quick_cap(*c.vectors_opt ? c.vectors : l.pipeline->default_vectors, kQuickVectors);
    if (*c.index_opt) {
      o.only_index = c.vector_index;
      o.random_vectors = 0;  // --vector-index replaces --vectors; keep the repro line exact
    }
    const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
    RtlIdentity identity;
    const CosimSubject subject = subject_of(l, targets[k], stimulus, &identity);
    if (!c.coverage.empty()) {
      CoverpointSampler sampler = l.pipeline->coverpoints(*l.model, l.cfg);
      count_coverpoints(sampler, *l.model, stimulus, o.seed, o.directed, o.random_vectors,
                        o.only_index);
      line_waivers.insert(line_waivers.end(), sampler.line_waivers.begin(),
                          sampler.line_waivers.end());
      points.merge(sampler.points.prefixed(fmt::format("{}/{}:", l.pipeline->name, l.cfg.name())));
    }
    for (const StallPattern& source : source_patterns) {
      for (const StallPattern& sink : sink_patterns) {
        o.source = source;
        o.sink = sink;
        const std::string what = fmt::format("cosim {}/{} (source {}, sink {})", l.pipeline->name,
                                             l.cfg.name(), source.str(), sink.str());
        o.progress = [&](std::uint64_t done, std::uint64_t all) { progress(what, done, all); };
        const auto start = std::chrono::steady_clock::now();
        CosimRun r{cosim(subject, o), 0, identity};
        progress(what, 1, 1);
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (trace_file) {
          if (wave == WaveFormat::vcd) fst_to_vcd(o.trace_path, trace_file->get());
          trace_file->commit();
          r.report.trace_written = c.trace;
          std::string& f = r.report.failure;
          if (const auto at = f.find(o.trace_path); at != std::string::npos) {
            f.replace(at, o.trace_path.size(), c.trace);
          }
        }
        if (!r.report.passed) fmt::print(text, "{}", r.report.failure);
        fmt::print(text, "{}\n", r.report.summary());
        std::fflush(text);
        if (trace_file && r.report.passed) {
          fmt::print(text, "waveform (first {} cycles): {}\n", o.trace_window, c.trace);
        }
        if (!c.coverage.empty()) {
          stall_class_hit(points, source, sink, r.report.source_idle_cycles,
                          r.report.sink_stall_cycles);
        }
        runs.push_back(std::move(r));
      }
    }
  }
  std::size_t failed = 0;
  for (const CosimRun& r : runs) failed += r.report.passed ? 0 : 1;
  std::optional<CoverageSummary> coverage;
  if (!c.coverage.empty()) {
    coverage = merge_coverage(c.coverage, coverage_inputs);
    const std::filesystem::path dir = c.coverage;
    const std::vector<UncountedSignal>& uncounted = coverage->not_toggled;
    const std::string toggles =
        !coverage->toggles_measured()
            ? "toggles not measured (--no-toggle-coverage)"
            : fmt::format("toggles {:.1f} % ({} of {}{})", coverage->toggle_percent(),
                          coverage->toggle_hit, coverage->toggle_points,
                          uncounted.empty()
                              ? ""
                              : fmt::format("; {} bits of {} signal{} not toggle-counted",
                                            coverage->not_toggled_bits(), uncounted.size(),
                                            uncounted.size() == 1 ? "" : "s"));
    fmt::print(text,
               "coverage ({} data file{} in {}): lines {:.1f} % ({} of {} points{}), {}; {}, {} "
               "(its Branches row is the lines figure, Functions the toggles)\n",
               coverage->files, coverage->files == 1 ? "" : "s", (dir / "data").string(),
               coverage->line_percent(), coverage->line_hit, coverage->line_points,
               coverage->line_waived == 0 ? "" : fmt::format(", {} waived", coverage->line_waived),
               toggles, (dir / "coverage.info").string(), (dir / "html" / "index.html").string());
    print_user_waivers(text, *coverage);
    // The signals the toggle figures leave out, by why (in the order first met).
    std::vector<std::string> whys;
    std::map<std::string, std::vector<const UncountedSignal*>> by_why;
    for (const UncountedSignal& u : uncounted) {
      if (!by_why.contains(u.why)) whys.push_back(u.why);
      by_why[u.why].push_back(&u);
    }
    for (const std::string& why : whys) {
      constexpr std::size_t kShown = 6;
      const auto& signals = by_why[why];
      std::uint64_t bits = 0;
      std::vector<std::string> shown;
      for (const UncountedSignal* u : signals) {
        bits += u->bits;
        if (shown.size() < kShown) shown.push_back(fmt::format("{} ({})", u->path, u->bits));
      }
      fmt::print(text, "not toggle-counted, {} ({} signal{}, {} bits): {}{}\n", why, signals.size(),
                 signals.size() == 1 ? "" : "s", bits, fmt::join(shown, ", "),
                 signals.size() <= kShown
                     ? ""
                     : fmt::format(" and {} more (--json lists them)", signals.size() - kShown));
    }
    // Earlier commands' counts in DIR first, so the file keeps their order.
    Coverpoints merged = Coverpoints::read(dir / "coverpoints.txt");
    merged.merge(points);
    merged.write(dir / "coverpoints.txt");
    points = merged;
    const std::vector<std::string> holes = points.holes();
    const std::size_t waived = points.waivers().size();
    fmt::print(
        text, "coverpoints: {} of {} hit ({:.1f} %); {}{}{}\n", points.hit_points(), points.size(),
        100.0 * static_cast<double>(points.hit_points()) /
            static_cast<double>(std::max<std::size_t>(points.size(), 1)),
        (dir / "coverpoints.txt").string(),
        waived == 0 ? "" : fmt::format("; {} waived (unreachable, --json lists why)", waived),
        holes.empty() ? "" : fmt::format("; never hit: {}", fmt::join(holes, ", ")));
  }
  if (json.wanted()) {
    nlohmann::ordered_json j = json_document("cosim");
    j["passed"] = failed == 0;
    j["runs_passed"] = runs.size() - failed;
    j["runs"] = nlohmann::ordered_json::array();
    for (const CosimRun& r : runs) j["runs"].push_back(to_json(r, c.target));
    j["coverage"] = nullptr;
    if (coverage) {
      const std::filesystem::path dir = c.coverage;
      j["coverage"] = {
          {"line_percent", coverage->line_percent()},
          {"toggle_percent", coverage->toggles_measured()
                                 ? nlohmann::ordered_json(coverage->toggle_percent())
                                 : nlohmann::ordered_json(nullptr)},
          {"lines",
           {{"hit", coverage->line_hit},
            {"total", coverage->line_points},
            {"waived", coverage->line_waived},
            {"waivers", waived_json(coverage->waived)}}},
          {"waiver_file",
           c.waivers.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(c.waivers)},
          {"toggles", coverage->toggles_measured()
                          ? nlohmann::ordered_json(
                                {{"hit", coverage->toggle_hit}, {"total", coverage->toggle_points}})
                          : nlohmann::ordered_json(nullptr)},
          {"not_toggle_counted", not_toggled_json(*coverage)},
          {"coverpoints",
           {{"hit", points.hit_points()},
            {"total", points.size()},
            {"holes", points.holes()},
            {"waivers", points.waivers()},
            {"file", (dir / "coverpoints.txt").string()}}},
          {"data_files", coverage->files},
          {"info", (dir / "coverage.info").string()},
          {"html", (dir / "html" / "index.html").string()}};
    }
    json.write(j);
  }
  if (junit_file) {
    std::fputs(junit_xml(runs).c_str(), junit_file->get());
    junit_file->commit();
  }
  if (runs.size() > 1) {
    fmt::print(text, "{} of {} runs passed\n", runs.size() - failed, runs.size());
  }
  return failed == 0 ? 0 : 1;
}

}  // namespace

void add_cosim(CLI::App& app, Action& action) {
  auto c = std::make_shared<CosimCli>();
  auto* cmd = app.add_subcommand(
      "cosim", "Co-simulate model and Verilated RTL on directed + seeded random vectors");
  c->target.add_options(*cmd, true, true);
  c->target.add_simulator_option(*cmd);
  c->vectors_opt = add_count(*cmd, "--vectors", c->vectors,
                             "random vectors after the directed corners (default: the "
                             "pipeline's, about a million outputs)",
                             kMaxVectors);
  add_count(*cmd, "--seed", c->options.seed, "seed of stimulus and random stalls", UINT64_MAX);
  cmd->add_option("--source-idle", c->source,
                  "when the source offers input: none | periodic:BITS | random:P | "
                  "long[:STALL[:RUN]]; several, comma-separated, make one run each")
      ->capture_default_str();
  cmd->add_option("--backpressure", c->sink,
                  "when the sink is ready (same patterns; several, comma-separated, make one run "
                  "each)")
      ->capture_default_str();
  c->index_opt = add_count(*cmd, "--vector-index", c->vector_index,
                           "run only this vector (as numbered in a failure report)", kMaxVectors)
                     ->default_str("");  // no default: every vector
  cmd->add_flag("!--no-directed", c->options.directed, "skip the directed corners");
  cmd->add_option("--trace", c->trace,
                  "write a waveform, FST (FILE.fst) or VCD (FILE.vcd): the window before the "
                  "first failure, or the first cycles of a passing run");
  add_count(*cmd, "--trace-window", c->options.trace_window, "waveform length in cycles",
            kMaxTraceWindow, 1);
  add_count(*cmd, "--timeout", c->options.timeout,
            "cycles without a handshake that count as deadlock (0: 100000 plus the longest "
            "stall the patterns make)",
            kMaxTimeout);
  cmd->add_option("--jobs", c->options.jobs,
                  "workers (threads): the vectors go to N DUTs, each taking a contiguous 1/N of "
                  "the stream from reset (the verdict states the longest sequence since reset)")
      ->check(CLI::Range(1U, 256U).description(""))
      ->type_name("1..256")
      ->capture_default_str();
  add_count(*cmd, "--reset-every", c->options.reset_every,
            "a fresh DUT (from reset) every N vectors, at group starts; the workers share those "
            "runs and --jobs then changes nothing but the time (0: no resets but one per worker)",
            kMaxVectors);
  cmd->add_option("--json", c->json,
                  "write the results as JSON (docs/json.md: every run of the matrix); - is "
                  "standard output");
  cmd->add_option("--coverage", c->coverage,
                  "RTL line and toggle coverage: a coverage build of the plugin writes its counts "
                  "into DIR/data; every run's there so far is merged into DIR/coverage.info (lcov) "
                  "and DIR/html; functional coverpoints, counted on the model, into "
                  "DIR/coverpoints.txt (docs/verification.md)");
  cmd->add_option("--waivers", c->waivers,
                  "with --coverage: a waiver file, one a line: SOURCE[:LINE[-LAST]] [/REGEX/] "
                  "[@INSTANCE] REASON; the line points it names leave the line figures, listed "
                  "with the reason; a waiver that matches no point, or a waived point reached, is "
                  "an error (docs/cosim.md)");
  cmd->add_flag("--no-toggle-coverage", c->no_toggle,
                "with --coverage: line points only, no toggle points (a build several times "
                "smaller and faster to compile and run; the JSON's toggle figures are null)");
  cmd->add_option("--junit", c->junit,
                  "write JUnit XML: one testcase per configuration x stall pattern run");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
