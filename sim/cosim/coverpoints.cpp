#include "sim/cosim/coverpoints.h"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "base/error.h"
#include "base/file_util.h"
#include "base/output_file.h"

namespace phongsim {
namespace fs = std::filesystem;

std::size_t Coverpoints::declare(std::string name) {
  if (std::find(names_.begin(), names_.end(), name) != names_.end()) {
    throw Error(fmt::format("coverpoint {} declared twice", name));
  }
  names_.push_back(std::move(name));
  counts_.push_back(0);
  reasons_.emplace_back();
  return names_.size() - 1;
}

void Coverpoints::waive(const std::string& name, std::string reason) {
  const auto at = std::find(names_.begin(), names_.end(), name);
  if (at != names_.end())
    reasons_[static_cast<std::size_t>(at - names_.begin())] = std::move(reason);
}

void Coverpoints::waived_hit(std::size_t index) const {
  throw Error(
      fmt::format("coverpoint {} is waived ({}) but was hit", names_[index], reasons_[index]));
}

std::size_t Coverpoints::size() const {
  return static_cast<std::size_t>(std::count(reasons_.begin(), reasons_.end(), std::string()));
}

std::vector<std::string> Coverpoints::waivers() const {
  std::vector<std::string> w;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (!reasons_[i].empty()) w.push_back(names_[i] + ": " + reasons_[i]);
  }
  return w;
}

Coverpoints::Sides Coverpoints::declare_sides(const std::string& name, fx::Format from,
                                              fx::Format to, fx::Round round) {
  Sides s;
  if (fx::resize_side(from.min_raw(), from, to, round) < 0) s.low = declare(name + ".low");
  s.inside = declare(name + ".inside");
  if (fx::resize_side(from.max_raw(), from, to, round) > 0) s.high = declare(name + ".high");
  return s;
}

void Coverpoints::hit_side(const Sides& s, int side) {
  const std::size_t at = side < 0 ? s.low : side > 0 ? s.high : s.inside;
  if (at == kNone) {
    throw Error(fmt::format("coverpoint: a requantization saturated {} where it cannot",
                            side < 0 ? "low" : "high"));
  }
  hit(at);
}

bool Coverpoints::hit(const std::string& name, std::uint64_t n) {
  const auto at = std::find(names_.begin(), names_.end(), name);
  if (at == names_.end()) return false;
  hit(static_cast<std::size_t>(at - names_.begin()), n);
  return true;
}

std::size_t Coverpoints::hit_points() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < names_.size(); ++i) n += counts_[i] > 0 && reasons_[i].empty();
  return n;
}

std::vector<std::string> Coverpoints::holes() const {
  std::vector<std::string> h;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (counts_[i] == 0 && reasons_[i].empty()) h.push_back(names_[i]);
  }
  return h;
}

void Coverpoints::merge(const Coverpoints& other) {
  for (std::size_t i = 0; i < other.names_.size(); ++i) {
    const auto at = std::find(names_.begin(), names_.end(), other.names_[i]);
    if (at == names_.end()) {
      names_.push_back(other.names_[i]);
      counts_.push_back(other.counts_[i]);
      reasons_.push_back(other.reasons_[i]);
    } else if (other.reasons_[i].empty()) {
      counts_[static_cast<std::size_t>(at - names_.begin())] += other.counts_[i];
    }
  }
}

Coverpoints Coverpoints::prefixed(const std::string& prefix) const {
  Coverpoints p = *this;
  for (std::string& n : p.names_) n = prefix + n;
  return p;
}

void Coverpoints::write(const fs::path& file) const {
  OutputFile out(file);
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (reasons_[i].empty()) fmt::print(out.get(), "{} {}\n", counts_[i], names_[i]);
  }
  out.commit();
}

Coverpoints Coverpoints::read(const fs::path& file) {
  Coverpoints c;
  std::error_code ec;
  if (!fs::exists(file, ec)) return c;
  std::istringstream in(read_file(file, "coverpoint file"));
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const auto space = line.find(' ');
    std::uint64_t count = 0;
    const bool digits = space != 0 && space != std::string::npos && space + 1 < line.size() &&
                        std::all_of(line.begin(), line.begin() + static_cast<long>(space),
                                    [](char ch) { return ch >= '0' && ch <= '9'; });
    if (!digits) {
      throw Error(fmt::format("{}:{}: not a coverpoint line (COUNT NAME): {}", file.string(),
                              number, line));
    }
    try {
      count = std::stoull(line.substr(0, space));
    } catch (const std::exception&) {
      throw Error(fmt::format("{}:{}: count out of range", file.string(), number));
    }
    Coverpoints one;
    one.hit(one.declare(line.substr(space + 1)), count);
    c.merge(one);
  }
  return c;
}

void count_coverpoints(CoverpointSampler& sampler, const PipelineModel& model,
                       const Stimulus& stimulus, std::uint64_t seed, bool directed,
                       std::uint64_t random, std::optional<std::uint64_t> only_index) {
  const std::unique_ptr<PipelineModel> m = model.clone();
  m->reset();
  std::vector<std::int64_t> in(m->inputs().size());
  const auto one = [&](std::uint64_t index) {
    stimulus.vector(seed, index, in);
    sampler.sample(*m, in, sampler.points);
  };
  if (only_index) {
    one(*only_index);
    return;
  }
  const std::uint64_t first = directed ? 0 : stimulus.directed_count();
  const std::uint64_t end = stimulus.directed_count() + random;
  for (std::uint64_t i = first; i < end; ++i) one(i);
}

namespace {
constexpr const char* kStallKinds[] = {"none", "periodic", "random", "long"};

std::string kind(const StallPattern& p) {
  const std::string s = p.str();
  return s.substr(0, s.find(':'));
}
}  // namespace

void declare_stall_classes(Coverpoints& points) {
  for (const char* side : {"source", "sink"}) {
    for (const char* k : kStallKinds) points.declare(fmt::format("stall.{}.{}", side, k));
  }
}

void stall_class_hit(Coverpoints& points, const StallPattern& source, const StallPattern& sink,
                     std::uint64_t source_idle, std::uint64_t sink_stalled) {
  // A pattern that never acted (too few vectors, an always-active bit pattern) is not its class.
  if (source.never_stalls() || source_idle > 0) {
    points.hit("stall.source." + kind(source));
  }
  if (sink.never_stalls() || sink_stalled > 0) {
    points.hit("stall.sink." + kind(sink));
  }
}

Clamp01Output::Clamp01Output(CoverpointSampler& sampler, fx::Format acc, fx::Format out,
                             fx::Round round)
    : acc_(acc), out_(out), round_(round) {
  clamp_ = sampler.points.declare("clamp.low");
  if (acc.int_bits > 0) sampler.points.declare("clamp.high");
  sampler.points.declare("clamp.none");
  // 1 (or the largest accumulator value below it) saturates high unless the output holds it.
  const std::int64_t top = fx::clamp01_raw(acc.max_raw(), acc);
  if (fx::resize_side(top, acc, out, round) > 0) {
    value_high_ = sampler.points.declare("value.high");
  } else {
    sampler.line_waivers.push_back(fx_resize_saturation_waiver(
        R"(\.u_value\.)", "high",
        "value.high: the accumulator clamped to [0, 1] fits " + out.str()));
  }
  value_inside_ = sampler.points.declare("value.inside");
  sampler.line_waivers.push_back(fx_resize_saturation_waiver(
      R"(\.u_value\.)", "low", "value.low: the accumulator clamped to [0, 1] is never negative"));
}

void Clamp01Output::hit(Coverpoints& points, std::int64_t acc_raw) const {
  const std::int64_t one = std::int64_t{1} << acc_.frac_bits;
  const bool high = acc_.int_bits > 0 && acc_raw > one;
  points.hit(clamp_ + (acc_raw < 0 ? 0 : high ? 1 : acc_.int_bits > 0 ? 2 : 1));
  const std::int64_t clamped = fx::clamp01_raw(acc_raw, acc_);
  points.hit(fx::resize_side(clamped, acc_, out_, round_) > 0 ? value_high_ : value_inside_);
}

}  // namespace phongsim
