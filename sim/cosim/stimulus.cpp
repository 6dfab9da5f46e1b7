#include "sim/cosim/stimulus.h"

#include <algorithm>
#include <cstring>

#include "base/error.h"
#include "model/plan.h"

namespace phongsim {

std::vector<std::int64_t> corner_values(fx::Format fmt) {
  const std::int64_t lo = fmt.min_raw();
  const std::int64_t hi = fmt.max_raw();
  std::vector<std::int64_t> v{lo, lo + 1, hi - 1, hi, 0, 1, -1};
  if (fmt.int_bits >= 1) {  // +-1.0 and its neighbours
    const std::int64_t one = std::int64_t{1} << fmt.frac_bits;
    v.insert(v.end(), {one - 1, one, one + 1, -one, -one + 1});
  }
  if (fmt.frac_bits >= 1) v.push_back(std::int64_t{1} << (fmt.frac_bits - 1));  // 1/2
  std::erase_if(v, [&](std::int64_t x) { return x < lo || x > hi; });
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

FieldRandom::FieldRandom(const std::vector<Field>& fields) : z_(2 * fields.size()) {
  for (const auto& f : fields) {
    const std::vector<std::int64_t> c = corner_values(f.fmt);
    if (c.size() > kCornerSlots)
      throw Error("FieldRandom: more corner values than fill() permutes");
    draws_.push_back({f.fmt.min_raw(),
                      static_cast<std::uint64_t>(f.fmt.max_raw() - f.fmt.min_raw()) + 1,
                      corners_.size(), c.size()});
    corners_.insert(corners_.end(), c.begin(), c.end());
    corners_.resize(corners_.size() + kCornerSlots - c.size());  // fill_block's permute loads 16
  }
}

// The Rng's outputs drawn at once (independent of each other), then each field's choice made
// without a branch (corner or uniform: a random 1-in-8 branch mispredicts).
void FieldRandom::operator()(Rng& rng, std::span<std::int64_t> in) const {
  rng.fill(z_);
  for (std::size_t i = 0; i < draws_.size(); ++i) {
    const Draw& d = draws_[i];
    const std::uint64_t z = z_[2 * i + 1];
    const std::int64_t corner = corners_[d.corners_at + Rng::scaled(z, d.corner_count)];
    const std::int64_t uniform = d.lo + static_cast<std::int64_t>(Rng::scaled(z, d.span));
    in[i] = Rng::scaled(z_[2 * i], 8) == 0 ? corner : uniform;
  }
}

// Vectors of the generators for fill_block's permute path, one per lane. Every function on them
// is inlined into a kernel (fx::on_kernel_isa's flatten), so none passes one in a call: the
// warning that their calling convention differs between instruction sets does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
using Lanes = std::uint64_t __attribute__((vector_size(64)));
using SignedLanes = std::int64_t __attribute__((vector_size(64)));

// operator() for a block of vectors field by field, each loop over the block's generators.
// Inline: fill() and fill_rows() call it on the kernel instruction set (fx::on_kernel_isa).
// kPermute (AVX-512 only): the loop eight generators at a time as GCC vectors, each field's
// corners (at most 16) in two registers, picked by one two-register permute (vpermt2q) per
// eight generators; otherwise a table load per value, which the compiler turns into a gather
// emulated one value at a time (LIRP's stimulus: about 20 % faster with the permute on AVX-512,
// 13-27 % slower on baseline and AVX2, where the permute is emulated too; docs/performance.md).
template <bool kPermute, class Row>
[[gnu::always_inline]] inline void FieldRandom::fill_block(const std::uint64_t* state,
                                                           std::size_t m, Row row,
                                                           std::int64_t* out,
                                                           std::uint64_t skip) const {
  constexpr std::uint64_t kNarrow = std::uint64_t{1} << 32;
  constexpr std::size_t kLanes = sizeof(Lanes) / sizeof(std::uint64_t);
  static_assert(kBlock % kLanes == 0);
  static_assert(kCornerSlots == 2 * kLanes);
  // The permute path's generators padded to whole vectors (the padding's values are never stored).
  alignas(64) std::uint64_t padded[kBlock];
  if constexpr (kPermute) {
    std::copy(state, state + m, padded);
    std::fill(padded + m, padded + kBlock, 0);
  }
  alignas(64) std::int64_t value[kBlock];
  // Locals: stores to `out` may alias the members as far as the compiler knows.
  const std::size_t n = draws_.size();
  const Draw* const draws = draws_.data();
  const std::int64_t* const corners = corners_.data();
  for (std::size_t i = 0; i < n; ++i) {
    const Draw d = draws[i];
    // The loop for a field's span: fields narrower than 32 bits scale with half the products.
    const auto draw = [&](auto narrow) {
      const auto scale = [&](auto z) {
        if constexpr (narrow)
          return Rng::scaled_narrow(z, d.span);
        else
          return Rng::scaled_halves(z, d.span);
      };
      if constexpr (kPermute) {
        SignedLanes low, high;
        std::memcpy(&low, corners + d.corners_at, sizeof low);
        std::memcpy(&high, corners + d.corners_at + kLanes, sizeof high);
        for (std::size_t v = 0; v < m; v += kLanes) {
          Lanes s;
          std::memcpy(&s, padded + v, sizeof s);
          const Lanes pick = Rng::output(s, skip + 2 * i);
          const Lanes z = Rng::output(s, skip + 2 * i + 1);
          const auto at = reinterpret_cast<SignedLanes>(Rng::scaled_narrow(z, d.corner_count));
          const SignedLanes corner = __builtin_shuffle(low, high, at);
          const SignedLanes uniform = d.lo + reinterpret_cast<SignedLanes>(scale(z));
          const SignedLanes chosen = (pick >> 61) == 0 ? corner : uniform;
          std::memcpy(value + v, &chosen, sizeof chosen);
        }
      } else {
        for (std::size_t v = 0; v < m; ++v) {
          const std::uint64_t pick = Rng::output(state[v], skip + 2 * i);
          const std::uint64_t z = Rng::output(state[v], skip + 2 * i + 1);
          const std::int64_t corner = corners[d.corners_at + Rng::scaled_narrow(z, d.corner_count)];
          const std::int64_t uniform = d.lo + static_cast<std::int64_t>(scale(z));
          value[v] = pick >> 61 == 0 ? corner : uniform;  // scaled(pick, 8) == 0
        }
      }
    };
    if (d.span < kNarrow) {
      draw(std::true_type{});
    } else {
      draw(std::false_type{});
    }
    for (std::size_t v = 0; v < m; ++v) out[row(v) * n + i] = value[v];
  }
}

void FieldRandom::fill(std::uint64_t seed, std::uint64_t first, std::size_t count,
                       std::span<std::int64_t> out, std::uint64_t skip) const {
  const bool permute = fx::kernel_isa() == fx::Isa::avx512;
  fx::on_kernel_isa([&] {
    alignas(64) std::uint64_t state[kBlock];
    for (std::size_t b = 0; b < count; b += kBlock) {
      const std::size_t m = std::min(kBlock, count - b);
      for (std::size_t v = 0; v < m; ++v) {
        state[v] = Rng::start(seed, kStimulusStream, first + b + v);
      }
      const auto row = [b](std::size_t v) { return b + v; };
      if (permute) {
        fill_block<true>(state, m, row, out.data(), skip);
      } else {
        fill_block<false>(state, m, row, out.data(), skip);
      }
    }
  });
}

void FieldRandom::fill_rows(std::span<const std::uint64_t> starts,
                            std::span<const std::uint32_t> rows, std::span<std::int64_t> out,
                            std::uint64_t skip) const {
  // No permute path: Lyon's stimulus, the one user, measured 4-10 % slower with it.
  fx::on_kernel_isa([&] {
    const std::uint32_t* const r = rows.data();
    for (std::size_t b = 0; b < starts.size(); b += kBlock) {
      const std::size_t m = std::min(kBlock, starts.size() - b);
      const auto row = [r, b](std::size_t v) { return std::size_t{r[b + v]}; };
      fill_block<false>(starts.data() + b, m, row, out.data(), skip);
    }
  });
}

Stimulus::Stimulus(const PipelineModel& model, std::vector<std::vector<std::int64_t>> directed,
                   RandomFn random, RandomBlockFn block)
    : directed_(std::move(directed)), random_(std::move(random)), block_(std::move(block)) {
  if (!random_) fields_.emplace(model.inputs());
}

void Stimulus::vector(std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in) const {
  if (index < directed_.size()) {
    std::copy(directed_[index].begin(), directed_[index].end(), in.begin());
  } else if (fields_) {
    (*fields_)(seed, index, in);
  } else {
    random_(seed, index, in);
  }
}

void Stimulus::vectors(std::uint64_t seed, std::uint64_t first, std::size_t count,
                       std::span<std::int64_t> in) const {
  const std::size_t n_in = count == 0 ? 0 : in.size() / count;
  std::size_t k = 0;
  for (; k < count && first + k < directed_.size(); ++k) {  // directed, then random
    vector(seed, first + k, in.subspan(k * n_in, n_in));
  }
  if (fields_) {
    fields_->fill(seed, first + k, count - k, in.subspan(k * n_in));
    return;
  }
  if (block_) {
    block_(seed, first + k, count - k, in.subspan(k * n_in));
    return;
  }
  for (; k < count; ++k) random_(seed, first + k, in.subspan(k * n_in, n_in));
}

}  // namespace phongsim
