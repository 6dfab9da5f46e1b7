#include "sim/pipelines/quad_analysis.h"

#include <algorithm>
#include <cmath>

#include "model/quad.h"
#include "model/quad_setup.h"
#include "sim/pipelines/quad_stimulus.h"

namespace phongsim {
namespace {

struct Walked {
  std::vector<std::int64_t> pixels;  // x, y, r, g, b per covered pixel
  std::vector<std::int64_t> acc;     // the three accumulators per covered pixel
};

// Walks `tri` with `colour` through `m` and calls visit(walked, pixel, channel, r(s, t)) for every
// covered pixel and channel, r evaluated directly at the pixel's centre (eqs. 4.1, 4.3).
template <class Visit>
void walk_with_direct(const QuadModel& m, const quad::SubpixelTri& tri,
                      const std::array<quad::Coeffs, 3>& colour, Visit visit) {
  Walked w;
  (void)m.walk(quad_program(tri, colour, m.formats()), w.pixels, &w.acc);
  const auto v = quad::to_pixels(tri);
  for (std::size_t i = 0; i < w.pixels.size() / 5; ++i) {
    const quad::St st = quad::st_at(v[0], v[1], v[2],
                                    {static_cast<double>(w.pixels[5 * i]) + 0.5,
                                     static_cast<double>(w.pixels[5 * i + 1]) + 0.5});
    for (int ch = 0; ch < 3; ++ch) visit(w, i, ch, quad::eval_st(colour[ch], st));
  }
}

}  // namespace

double quad_drift(int size, int guard_bits, fx::Format out, int triangles, std::uint64_t seed) {
  QuadFormats f;
  f.acc = fx::Format{true, 2, out.frac_bits + guard_bits};
  f.out = out;
  f.sub_bits = 4;
  const QuadModel m(f);
  const double lsb = std::ldexp(1.0, -out.frac_bits);
  const auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
  double worst = 0;
  for (int n = 0; n < triangles; ++n) {
    Rng rng(seed, kStimulusStream, static_cast<std::uint64_t>(n));
    const double x = rng.uniform() * (2048 - size);
    const double y = rng.uniform() * (2048 - size);
    std::array<quad::Vertex2, 3> v;
    for (auto& p : v) p = {x + rng.uniform() * size, y + rng.uniform() * size};
    const quad::SubpixelTri tri = quad::quantize(v[0], v[1], v[2], f.sub_bits);
    if (quad::orientation(tri) == 0) continue;
    std::array<quad::Coeffs, 3> colour;
    for (auto& c : colour) c = random_colour(rng, QuadMode::quadratic);
    walk_with_direct(m, tri, colour, [&](const Walked& w, std::size_t i, int ch, double exact) {
      const double got = clamp01(fx::to_real(w.acc[3 * i + ch], f.acc));
      worst = std::max(worst, std::abs(got - clamp01(exact)) / lsb);
    });
  }
  return worst;
}

QuadOutputError quad_output_error(const QuadFormats& f, QuadMode mode, int triangles,
                                  std::uint64_t seed) {
  const QuadModel m(f);
  const double lsb = std::ldexp(1.0, -f.out.frac_bits);
  const double top = fx::to_real(f.out.max_raw(), f.out);
  QuadOutputError e;
  double sum = 0;
  for (int n = 0; n < triangles; ++n) {
    Rng rng(seed, kStimulusStream, static_cast<std::uint64_t>(n));
    const quad::SubpixelTri tri = random_triangle(rng, f.sub_bits);
    std::array<quad::Coeffs, 3> colour;
    for (auto& c : colour) c = random_colour(rng, mode);
    walk_with_direct(m, tri, colour, [&](const Walked& w, std::size_t i, int ch, double exact) {
      // Clamped to what the output can hold: 0.8 tops out at 255/256, not 1.
      const double d =
          std::abs(fx::to_real(w.pixels[5 * i + 2 + ch], f.out) - std::clamp(exact, 0.0, top)) /
          lsb;
      e.max = std::max(e.max, d);
      sum += d;
      ++e.pixels;
    });
  }
  e.mean = e.pixels == 0 ? 0 : sum / static_cast<double>(e.pixels);
  return e;
}

}  // namespace phongsim
