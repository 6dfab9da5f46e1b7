#include "sim/cosim/stimulus.h"

#include <algorithm>

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

std::int64_t random_raw(Rng& rng, fx::Format fmt, std::span<const std::int64_t> corners) {
  if (rng.below(8) == 0) {
    return corners[rng.below(corners.size())];
  }
  const auto span = static_cast<std::uint64_t>(fmt.max_raw() - fmt.min_raw()) + 1;  // <= 2^63
  return fmt.min_raw() + static_cast<std::int64_t>(rng.below(span));
}

FieldRandom::FieldRandom(const std::vector<Field>& fields) {
  for (const auto& f : fields) {
    formats_.push_back(f.fmt);
    corners_.push_back(corner_values(f.fmt));
  }
}

void FieldRandom::operator()(Rng& rng, std::span<std::int64_t> in) const {
  for (std::size_t i = 0; i < formats_.size(); ++i)
    in[i] = random_raw(rng, formats_[i], corners_[i]);
}

Stimulus::Stimulus(const PipelineModel& model, std::vector<std::vector<std::int64_t>> directed,
                   RandomFn random)
    : directed_(std::move(directed)), random_(std::move(random)) {
  if (!random_) random_ = FieldRandom(model.inputs());
}

void Stimulus::vector(std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in) const {
  if (index < directed_.size()) {
    std::copy(directed_[index].begin(), directed_[index].end(), in.begin());
    return;
  }
  random_(seed, index, in);
}

}  // namespace phongsim
