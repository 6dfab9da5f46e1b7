// Stimulus for co-simulation: directed corner vectors first, then seeded random vectors. Vector
// `index` is a pure function of (seed, index), so any failing vector can be regenerated alone.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "base/rng.h"
#include "model/fixed.h"
#include "model/pipeline.h"

namespace phongsim {

// Values worth hitting in any format: both range ends and their neighbours, zero, one LSB either
// side of zero, and +-1.0 and 1/2 where representable. Sorted, no duplicates.
[[nodiscard]] std::vector<std::int64_t> corner_values(fx::Format fmt);

// Field-by-field random raw values: each field usually uniform over its format's whole range,
// sometimes (1 in 8) one of its corner_values(), so range ends and exact ones keep showing up in
// random runs. Field i takes the Rng's outputs 2i and 2i + 1 (below(8) == 0 picks a corner; the
// second picks the corner or the value), whichever it becomes. The default random stimulus, also
// available to pipelines that mix it with their own. Not thread-safe (scratch): one per thread.
class FieldRandom {
 public:
  explicit FieldRandom(const std::vector<Field>& fields);
  void operator()(Rng& rng, std::span<std::int64_t> in) const;
  void operator()(std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in) const {
    Rng rng(seed, kStimulusStream, index);
    (*this)(rng, in);
  }
  // Vectors first .. first + count - 1 of `seed` back to back in `out`: the values of `count`
  // calls of the above, made a block of vectors at a time so that the loops over a block
  // vectorize (fx::on_kernel_isa). Thread-safe (no scratch).
  // `skip` > 0: fields from the Rng's outputs skip + 2i and skip + 2i + 1, i.e. the above on an
  // Rng that has drawn `skip` numbers first (a pipeline that mixes this stimulus with its own).
  void fill(std::uint64_t seed, std::uint64_t first, std::size_t count, std::span<std::int64_t> out,
            std::uint64_t skip = 0) const;
  // The same for chosen generators: for each k, the vector of the Rng that starts in state
  // starts[k] (Rng::start's value) into row rows[k] of `out` (a pipeline that fills only some of
  // a block's vectors from this stimulus).
  void fill_rows(std::span<const std::uint64_t> starts, std::span<const std::uint32_t> rows,
                 std::span<std::int64_t> out, std::uint64_t skip = 0) const;

 private:
  struct Draw {
    std::int64_t lo = 0;                           // min_raw()
    std::uint64_t span = 0;                        // max_raw() - min_raw() + 1 (<= 2^63)
    std::size_t corners_at = 0, corner_count = 0;  // into corners_
  };
  std::vector<Draw> draws_;
  std::vector<std::int64_t> corners_;  // each field's, padded to kCornerSlots
  static constexpr std::size_t kCornerSlots = 16;
  mutable std::vector<std::uint64_t> z_;  // the Rng's outputs for one vector

  // fill()'s and fill_rows()'s work on up to kBlock generators: vector v from state[v] into row
  // row(v) of `out`.
  static constexpr std::size_t kBlock = 64;
  template <bool kPermute, class Row>
  void fill_block(const std::uint64_t* state, std::size_t m, Row row, std::int64_t* out,
                  std::uint64_t skip) const;
};

class Stimulus {
 public:
  // Fills random input vector `index` (raw values in the model's inputs() order); a pure function
  // of (seed, index). Most draw from Rng(seed, kStimulusStream, index); pipelines whose inputs
  // come in groups (a span's words) derive the group from the index.
  using RandomFn =
      std::function<void(std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in)>;

  // Random vectors first .. first + count - 1 back to back in `out`: the same as `count` calls of
  // a RandomFn, made a block at a time where that is faster.
  using RandomBlockFn = std::function<void(std::uint64_t seed, std::uint64_t first,
                                           std::size_t count, std::span<std::int64_t> out)>;

  // `directed` holds complete input vectors (raw values in the model's inputs() order).
  // Random vectors come from `random` when given, otherwise from FieldRandom; `block`, when
  // given, makes the same vectors as `random` for vectors() (tests/lyon_test.cpp checks it).
  Stimulus(const PipelineModel& model, std::vector<std::vector<std::int64_t>> directed,
           RandomFn random = {}, RandomBlockFn block = {});

  [[nodiscard]] std::uint64_t directed_count() const { return directed_.size(); }

  // Vector `index`: directed_[index] below directed_count(), otherwise random from (seed, index).
  // Not thread-safe (a RandomFn may cache): a thread uses its own copy.
  void vector(std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in) const;
  // Vectors first .. first + count - 1 back to back in `in`: what `count` vector() calls give.
  // The default random stimulus (FieldRandom) makes them a block at a time.
  void vectors(std::uint64_t seed, std::uint64_t first, std::size_t count,
               std::span<std::int64_t> in) const;

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
  RandomBlockFn block_;
  std::optional<FieldRandom> fields_;  // the random stimulus when no RandomFn is given
  GroupFn groups_;
};

}  // namespace phongsim
