// Stimulus for co-simulation: directed corner vectors first, then seeded random vectors. Vector
// `index` is a pure function of (seed, index), so any failing vector can be regenerated alone.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "base/rng.h"
#include "model/fixed.h"
#include "model/pipeline.h"

namespace phongsim {

// Values worth hitting in any format: both range ends and their neighbours, zero, one LSB either
// side of zero, and +-1.0 and 1/2 where representable. Sorted, no duplicates.
[[nodiscard]] std::vector<std::int64_t> corner_values(fx::Format fmt);

// A random raw value of `fmt`: usually uniform over the whole range, sometimes (1 in 8) one of
// `corners` (corner_values(fmt)), so range ends and exact ones keep showing up in random runs.
[[nodiscard]] std::int64_t random_raw(Rng& rng, fx::Format fmt,
                                      std::span<const std::int64_t> corners);

class Stimulus {
 public:
  // Fills random input vector `index` (raw values in the model's inputs() order); a pure function
  // of (seed, index). Most draw from Rng(seed, kStimulusStream, index); pipelines whose inputs
  // come in groups (a span's words) derive the group from the index.
  using RandomFn =
      std::function<void(std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in)>;

  // `directed` holds complete input vectors (raw values in the model's inputs() order).
  // Random vectors come from `random` when given, otherwise field by field from random_raw().
  Stimulus(const PipelineModel& model, std::vector<std::vector<std::int64_t>> directed,
           RandomFn random = {});

  [[nodiscard]] std::uint64_t directed_count() const { return directed_.size(); }

  // Vector `index`: directed_[index] below directed_count(), otherwise random from (seed, index).
  // Not thread-safe (a RandomFn may cache): a thread uses its own copy.
  void vector(std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in) const;

  // Where a co-simulation may be split (sim/cosim/cosim.h: shards). For vectors that depend on
  // the ones before them (a span program's words), `starts` gives the first index >= i at which
  // an independent group of vectors begins; the model and the RTL are back in their reset state
  // there. Without it, only pipelines with independent vectors are split.
  using GroupFn = std::function<std::uint64_t(std::uint64_t index)>;
  void set_groups(GroupFn starts) { groups_ = std::move(starts); }
  [[nodiscard]] bool has_groups() const { return static_cast<bool>(groups_); }
  [[nodiscard]] std::uint64_t group_start(std::uint64_t index) const {
    return groups_ ? groups_(index) : index;
  }

 private:
  std::vector<std::vector<std::int64_t>> directed_;
  RandomFn random_;
  GroupFn groups_;
};

// Field-by-field random values (random_raw with corner bias) for the given formats: the default
// random stimulus, also available to pipelines that mix it with their own.
class FieldRandom {
 public:
  explicit FieldRandom(const std::vector<Field>& fields);
  void operator()(Rng& rng, std::span<std::int64_t> in) const;
  void operator()(std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in) const {
    Rng rng(seed, kStimulusStream, index);
    (*this)(rng, in);
  }

 private:
  std::vector<fx::Format> formats_;
  std::vector<std::vector<std::int64_t>> corners_;
};

}  // namespace phongsim
