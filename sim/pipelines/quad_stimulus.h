// Stimulus for the quadratic colour interpolator: random triangles through the setup (every size
// from slivers and one-pixel triangles to 1024-pixel boxes, both windings, colours that leave
// [0, 1] now and then), arbitrary program words over small boxes, and directed corner cases.
#pragma once

#include "base/rng.h"
#include "model/quad.h"
#include "model/quad_setup.h"
#include "ref/quad_float.h"
#include "sim/cosim/stimulus.h"

namespace phongsim {

// [setup] mode: quadratic (six samples per channel) or linear (three vertex values).
[[nodiscard]] QuadMode quad_mode(const Config& cfg);

// A random triangle in subpixel units within the screen: box side log-uniform up to 64 pixels,
// one time in 128 up to 1024; one in 32 degenerate (collinear); random winding.
[[nodiscard]] quad::SubpixelTri random_triangle(Rng& rng, int sub_bits);

// Random colour coefficients for one channel: quadratic from six samples in [-0.2, 1.2] (mostly
// in [0, 1]), or linear from three.
[[nodiscard]] quad::Coeffs random_colour(Rng& rng, QuadMode mode);

[[nodiscard]] Stimulus make_quad_stimulus(const PipelineModel& model, QuadMode mode);

}  // namespace phongsim
