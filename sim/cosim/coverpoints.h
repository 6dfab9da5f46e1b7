// Functional coverpoints (docs/verification.md, "Functional coverpoints"): named events a
// pipeline's registry entry declares for one configuration and counts on the model side, one
// input vector at a time (PipelineInfo::coverpoints), plus the stall-pattern classes a
// co-simulation ran under. `phongsim cosim --coverage DIR` counts them over the vectors of its
// runs and merges them, like the RTL's line and toggle counts, with earlier runs' in
// DIR/coverpoints.txt; the holes (points never hit) are listed by name.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "model/fixed.h"
#include "model/pipeline.h"
#include "sim/cosim/coverage.h"
#include "sim/cosim/stall.h"
#include "sim/cosim/stimulus.h"

namespace phongsim {

// Named counters in declaration order.
class Coverpoints {
 public:
  // Declares `name` and returns its index; declaring a name twice is an error (Error).
  std::size_t declare(std::string name);
  // A requantization point's outcomes (fx::resize_side): `name.low` (saturating low),
  // `name.inside` (no overflow), `name.high` (saturating high), each declared only when a value
  // of `from` can reach it (rounded per `round` into `to`): an unsigned value never saturates
  // low, a value whose format fits never saturates. Undeclared outcomes are kNone.
  static constexpr std::size_t kNone = SIZE_MAX;
  struct Sides {
    std::size_t low = kNone, inside = kNone, high = kNone;
  };
  Sides declare_sides(const std::string& name, fx::Format from, fx::Format to, fx::Round round);
  // Waives declared point `name` (no effect when it is not declared): an outcome the stimulus
  // cannot reach, with the reason. A waived point counts in neither hit_points() nor size();
  // hitting it is an Error (the reason was wrong).
  void waive(const std::string& name, std::string reason);
  void hit(std::size_t index, std::uint64_t n = 1) {
    if (!reasons_.at(index).empty()) waived_hit(index);
    counts_[index] += n;
  }
  // Counts outcome `side` (-1, 0, +1); Error when it was not declared (it cannot happen).
  void hit_side(const Sides& s, int side);
  // Counts `name` when it was declared; false when it was not.
  bool hit(const std::string& name, std::uint64_t n = 1);

  // Points not waived, their hits and holes (points never counted, in declaration order).
  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] std::size_t hit_points() const;
  [[nodiscard]] std::vector<std::string> holes() const;
  // Every declared point, waived ones included, and its count.
  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  [[nodiscard]] const std::vector<std::uint64_t>& counts() const { return counts_; }
  // The waived points as "NAME: REASON".
  [[nodiscard]] std::vector<std::string> waivers() const;

  // Adds `other`'s counts point by point (by name), declaring the points this set lacks.
  void merge(const Coverpoints& other);
  // Every name prefixed with `prefix` ("lirp/default:").
  [[nodiscard]] Coverpoints prefixed(const std::string& prefix) const;

  // A text file of "COUNT NAME" lines, waived points left out (written atomically); read() of a
  // missing file is an empty set, of a malformed one an Error naming file and line.
  void write(const std::filesystem::path& file) const;
  [[nodiscard]] static Coverpoints read(const std::filesystem::path& file);

 private:
  [[noreturn]] void waived_hit(std::size_t index) const;

  std::vector<std::string> names_;
  std::vector<std::uint64_t> counts_;
  std::vector<std::string> reasons_;  // why a point is waived; "" when it is not
};

// A pipeline's coverpoints for one configuration: the points, declared with count 0, and how one
// input vector counts into them. `sample` gets each vector of a run in stimulus order (raw values
// in the model's inputs() order) with a model that started in its reset state and has seen the
// run's earlier vectors (it evaluates the vector itself: stateful models advance). A sampler may
// keep state between vectors (a span program's words); use a fresh one per run.
struct CoverpointSampler {
  Coverpoints points;
  // The RTL line points the waived coverpoints make unreachable (an fx_resize saturation arm of
  // the instance computing a requantization that cannot saturate): left out of the line figures.
  std::vector<LineWaiver> line_waivers;
  std::function<void(PipelineModel& model, std::span<const std::int64_t> in, Coverpoints& points)>
      sample;
};

// The output stage kb's engine and quad's channels share (fx_clamp01 of the accumulator, then
// fx_rq to the output format): the clamp's outcomes `clamp.low`, `clamp.high` (declared only
// when `acc` has integer bits: else it never exceeds 1) and `clamp.none`, and the
// requantization's `value.high` (declared only when `out` cannot hold the clamped maximum) and
// `value.inside`; the arms a clamped value cannot reach (low always, high when `out` holds 1)
// go into `sampler`'s line waivers, the rq's saturation lines of instance `u_value`.
class Clamp01Output {
 public:
  Clamp01Output(CoverpointSampler& sampler, fx::Format acc, fx::Format out, fx::Round round);
  // Counts one accumulator value's clamp and requantization.
  void hit(Coverpoints& points, std::int64_t acc_raw) const;

 private:
  fx::Format acc_, out_;
  fx::Round round_;
  std::size_t clamp_ = 0, value_high_ = Coverpoints::kNone, value_inside_ = 0;
};

// The vectors a co-simulation runs (Stimulus::vector: the directed ones when `directed`, then
// `random` from `seed`; only `only_index` when given) counted into `sampler.points` through a
// copy of `model` reset first.
void count_coverpoints(CoverpointSampler& sampler, const PipelineModel& model,
                       const Stimulus& stimulus, std::uint64_t seed, bool directed,
                       std::uint64_t random, std::optional<std::uint64_t> only_index);

// The stall-pattern classes: `stall.source.<kind>` and `stall.sink.<kind>` for every kind of
// StallPattern (none, periodic, random, long), declared in `points`; stall_class_hit() counts the
// two a run with (`source`, `sink`) falls into where its patterns acted: the source withheld an
// input (`source_idle` cycles) or an output waited for the sink (`sink_stalled` cycles); `none`
// counts always.
void declare_stall_classes(Coverpoints& points);
void stall_class_hit(Coverpoints& points, const StallPattern& source, const StallPattern& sink,
                     std::uint64_t source_idle, std::uint64_t sink_stalled);

}  // namespace phongsim
