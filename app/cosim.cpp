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
#include "base/error.h"
#include "base/output_file.h"

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
  CLI::Option* vectors_opt = nullptr;
  CLI::Option* index_opt = nullptr;
};

nlohmann::json to_json(const CosimReport& r) {
  return {
      {"pipeline", r.pipeline},
      {"config", r.config_name},
      {"config_path", r.config_path},
      {"rtl", r.rtl_label},
      {"seed", r.options.seed},
      {"vectors", r.vectors},
      {"directed_vectors", r.directed},
      {"random_vectors", r.random},
      {"outputs", r.outputs},
      {"mismatches", r.mismatches},
      {"cycles", r.cycles},
      {"source_idle", r.options.source.str()},
      {"backpressure", r.options.sink.str()},
      {"throughput", r.throughput},
      {"latency", {{"min", r.latency_min}, {"max", r.latency_max}}},
      {"passed", r.passed},
      {"failure_kind", r.failure_kind},
      {"failure", r.failure},
  };
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  if (parts.empty()) parts.emplace_back();
  return parts;
}

std::string xml_escaped(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // XML 1.0 allows no control characters but tab and newlines.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') {
          out += '?';
        } else {
          out += c;
        }
    }
  }
  return out;
}

struct Run {
  CosimReport report;
  double seconds = 0;
};

// JUnit XML as CI systems read it: one testsuite per pipeline, one testcase per run, the
// first-failure report as the failure's text.
std::string junit_xml(const std::vector<Run>& runs) {
  std::size_t failures = 0;
  double seconds = 0;
  for (const Run& r : runs) {
    failures += r.report.passed ? 0 : 1;
    seconds += r.seconds;
  }
  std::string x = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<testsuites name=\"phongsim cosim\" tests=\"{}\" failures=\"{}\" time=\"{:.3f}\">\n",
      runs.size(), failures, seconds);
  for (std::size_t i = 0; i < runs.size();) {
    std::size_t j = i;
    std::size_t suite_failures = 0;
    double suite_seconds = 0;
    while (j < runs.size() && runs[j].report.pipeline == runs[i].report.pipeline) {
      suite_failures += runs[j].report.passed ? 0 : 1;
      suite_seconds += runs[j].seconds;
      ++j;
    }
    x += fmt::format("  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" time=\"{:.3f}\">\n",
                     xml_escaped(runs[i].report.pipeline), j - i, suite_failures, suite_seconds);
    for (; i < j; ++i) {
      const CosimReport& r = runs[i].report;
      x += fmt::format(
          "    <testcase classname=\"{}.{}\" name=\"source {} sink {} seed {}\" time=\"{:.3f}\">\n",
          xml_escaped(r.pipeline), xml_escaped(r.config_name), xml_escaped(r.options.source.str()),
          xml_escaped(r.options.sink.str()), r.options.seed, runs[i].seconds);
      if (!r.passed) {
        x += fmt::format("      <failure type=\"{}\" message=\"{}\">{}</failure>\n",
                         xml_escaped(r.failure_kind), xml_escaped(r.summary()),
                         xml_escaped(r.failure));
      }
      x += fmt::format("      <system-out>{}</system-out>\n    </testcase>\n",
                       xml_escaped(r.summary()));
    }
    x += "  </testsuite>\n";
  }
  return x + "</testsuites>\n";
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
  if (!c.trace.empty() && c.target.simulator == "icarus") {
    throw Error("--trace is not available with --simulator icarus (use the Verilator build)");
  }
  if (total > 1 && (!c.json.empty() || !c.trace.empty() || *c.index_opt)) {
    throw Error(
        "--json, --trace and --vector-index take one run: give one --config and one "
        "pattern each for --source-idle and --backpressure");
  }
  // Every configuration and its RTL first, so bad input stops the command before any run.
  std::vector<Loaded> loaded;
  std::vector<Target> targets;
  for (const auto& config : configs) {
    Target t = c.target;
    t.config = config;
    loaded.push_back(load(t));
    targets.push_back(t);
  }
  std::optional<OutputFile> json_file;
  std::optional<OutputFile> trace_file;
  std::optional<OutputFile> junit_file;
  if (!c.json.empty()) json_file.emplace(c.json);
  if (!c.junit.empty()) junit_file.emplace(c.junit);
  CosimOptions o = c.options;
  if (!c.trace.empty()) {
    trace_file.emplace(c.trace);
    o.trace_path = trace_file->temp_path().string();
  }
  std::vector<Run> runs;
  for (std::size_t k = 0; k < loaded.size(); ++k) {
    const Loaded& l = loaded[k];
    o.random_vectors = *c.vectors_opt ? c.vectors : l.pipeline->default_vectors;
    if (*c.index_opt) {
      o.only_index = c.vector_index;
      o.random_vectors = 0;  // --vector-index replaces --vectors; keep the repro line exact
    }
    const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
    const CosimSubject subject = subject_of(l, targets[k], stimulus);
    for (const StallPattern& source : source_patterns) {
      for (const StallPattern& sink : sink_patterns) {
        o.source = source;
        o.sink = sink;
        const auto start = std::chrono::steady_clock::now();
        Run r{cosim(subject, o), 0};
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (trace_file) {
          trace_file->commit();
          r.report.trace_written = c.trace;
          std::string& f = r.report.failure;
          if (const auto at = f.find(o.trace_path); at != std::string::npos) {
            f.replace(at, o.trace_path.size(), c.trace);
          }
        }
        if (!r.report.passed) fmt::print("{}", r.report.failure);
        fmt::print("{}\n", r.report.summary());
        std::fflush(stdout);
        if (trace_file && r.report.passed) {
          fmt::print("waveform (first {} cycles): {}\n", o.trace_window, c.trace);
        }
        runs.push_back(std::move(r));
      }
    }
  }
  if (json_file) {
    fmt::print(json_file->get(), "{}\n", to_json(runs.front().report).dump(2));
    json_file->commit();
  }
  if (junit_file) {
    std::fputs(junit_xml(runs).c_str(), junit_file->get());
    junit_file->commit();
  }
  std::size_t failed = 0;
  for (const Run& r : runs) failed += r.report.passed ? 0 : 1;
  if (runs.size() > 1) {
    fmt::print("{} of {} runs passed\n", runs.size() - failed, runs.size());
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
                           "run only this vector (as numbered in a failure report)", kMaxVectors);
  cmd->add_flag("!--no-directed", c->options.directed, "skip the directed corners");
  cmd->add_option("--trace", c->trace,
                  "write an FST waveform: the window before the first failure, or the first "
                  "cycles of a passing run");
  add_count(*cmd, "--trace-window", c->options.trace_window, "waveform length in cycles",
            kMaxCycles);
  add_count(*cmd, "--timeout", c->options.timeout,
            "cycles without a handshake that count as deadlock (0: 100000)", kMaxCycles);
  cmd->add_option("--jobs", c->options.jobs,
                  "workers (threads) sharing a run's shards; the results do not depend on it")
      ->check(CLI::Range(1U, 256U))
      ->capture_default_str();
  cmd->add_option("--json", c->json, "write a JSON summary (one run)");
  cmd->add_option("--junit", c->junit,
                  "write JUnit XML: one testcase per configuration x stall pattern run");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
