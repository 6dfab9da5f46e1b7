// Stimulus for co-simulation: directed corner vectors first, then seeded random vectors. Vector
// `index` is a pure function of (seed, index), so any failing vector can be regenerated alone.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "model/fixed.h"
#include "model/pipeline.h"
#include "sim/rng.h"

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
  // `directed` holds complete input vectors (raw values in the model's inputs() order).
  Stimulus(const PipelineModel& model, std::vector<std::vector<std::int64_t>> directed);

  [[nodiscard]] std::uint64_t directed_count() const { return directed_.size(); }

  // Vector `index`: directed_[index] below directed_count(), otherwise random from (seed, index).
  void vector(std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in) const;

 private:
  std::vector<fx::Format> formats_;
  std::vector<std::vector<std::int64_t>> corners_;  // corner_values() per input field
  std::vector<std::vector<std::int64_t>> directed_;
};

}  // namespace phongsim
