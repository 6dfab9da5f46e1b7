#include "sim/pipelines/quad_stimulus.h"

#include <algorithm>
#include <cmath>

namespace phongsim {

QuadMode quad_mode(const Config& cfg) {
  return cfg.setup("mode", {"quadratic", "linear"}) == "linear" ? QuadMode::linear
                                                                : QuadMode::quadratic;
}

quad::SubpixelTri random_triangle(Rng& rng, int sub_bits) {
  const double max_side = rng.below(128) == 0 ? 1024.0 : 64.0;
  const double w = std::exp(rng.uniform() * std::log(max_side));
  const double h = rng.below(4) == 0 ? std::exp(rng.uniform() * std::log(max_side)) : w;
  const double x = rng.uniform() * (2048 - w);
  const double y = rng.uniform() * (2048 - h);
  std::array<quad::Vertex2, 3> v;
  for (auto& p : v) p = {x + rng.uniform() * w, y + rng.uniform() * h};
  if (rng.below(32) == 0) v[2] = {(v[0].x + v[1].x) / 2, (v[0].y + v[1].y) / 2};  // collinear
  quad::SubpixelTri tri = quad::quantize(v[0], v[1], v[2], sub_bits);
  if (rng.below(2) == 0) tri = quad::reversed(tri);
  return tri;
}

quad::Coeffs random_colour(Rng& rng, QuadMode mode) {
  const auto sample = [&rng]() {
    return rng.below(8) == 0 ? 1.4 * rng.uniform() - 0.2 : rng.uniform();
  };
  if (mode == QuadMode::linear) return quad::linear_coefficients(sample(), sample(), sample());
  quad::Samples r;
  for (auto& x : r) x = sample();
  return quad::coefficients(r);
}

Stimulus make_quad_stimulus(const PipelineModel& model, QuadMode mode) {
  const auto& qm = dynamic_cast<const QuadModel&>(model);
  const QuadFormats f = qm.formats();
  const int s = f.sub_bits;
  const auto tri = [s](double x0, double y0, double x1, double y1, double x2, double y2) {
    return quad::quantize({x0, y0}, {x1, y1}, {x2, y2}, s);
  };
  const auto flat = [](double v) { return quad::linear_coefficients(v, v, v); };
  std::vector<std::vector<std::int64_t>> directed;
  const auto add = [&](const quad::SubpixelTri& t, const std::array<quad::Coeffs, 3>& colour) {
    directed.push_back(QuadModel::words(quad_program(t, colour, f)));
  };
  const std::array<quad::Coeffs, 3> grey{flat(0.5), flat(0.25), flat(0.75)};
  const std::array<quad::Coeffs, 3> ramp{quad::linear_coefficients(0, 1, 0.5),
                                         quad::linear_coefficients(1, 0, 0.5),
                                         quad::coefficients({0, 1, 0, 1, 0, 1})};
  const std::array<quad::Coeffs, 3> outside{flat(-0.3), flat(1.3), flat(1.0)};  // clamp corners
  // One pixel; vertices on pixel centres (top-left ties on every edge); both windings.
  add(tri(10.2, 10.2, 10.9, 10.3, 10.4, 10.9), grey);
  add(tri(20.5, 20.5, 30.5, 20.5, 20.5, 30.5), ramp);
  add(tri(20.5, 20.5, 20.5, 30.5, 30.5, 20.5), ramp);
  add(tri(40.5, 40.5, 50.5, 50.5, 40.5, 50.5), ramp);
  // A 1024 x 1024 right triangle, a sliver, a degenerate triangle, the screen's far corner.
  add(tri(0, 0, 1024, 0, 0, 1024), ramp);
  add(tri(100, 100, 900, 103, 100, 101), ramp);
  add(tri(5, 5, 10, 10, 15, 15), grey);
  add(tri(2040, 2040, 2048, 2047, 2043, 2048), outside);
  add(tri(60, 60, 70, 62, 61, 75), outside);

  // Random: three quarters through the setup, one quarter arbitrary words over a small box.
  const FieldRandom bits(model.inputs());
  auto random = [f, mode, bits](std::uint64_t seed, std::uint64_t index,
                                std::span<std::int64_t> in) {
    Rng rng(seed, kStimulusStream, index);
    if (rng.below(4) == 0) {
      bits(rng, in);
      in[0] = static_cast<std::int64_t>(rng.below(2016));  // box up to 32 x 32 pixels
      in[1] = static_cast<std::int64_t>(rng.below(2016));
      in[2] = in[0] + static_cast<std::int64_t>(rng.below(32));
      in[3] = in[1] + static_cast<std::int64_t>(rng.below(32));
      return;
    }
    const quad::SubpixelTri t = random_triangle(rng, f.sub_bits);
    std::array<quad::Coeffs, 3> colour;
    for (auto& c : colour) c = random_colour(rng, mode);
    const auto w = QuadModel::words(quad_program(t, colour, f));
    std::copy(w.begin(), w.end(), in.begin());
  };
  return Stimulus(model, std::move(directed), random);
}

}  // namespace phongsim
