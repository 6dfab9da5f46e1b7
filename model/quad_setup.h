// Setup for the quadratic colour interpolator (model/quad.h): from a triangle's subpixel
// vertices and its colour coefficients (eq. 4.1's C0..C5 per channel, ref/quad_float.h) to the
// walker's program words. Its own rounding is part of the specification (docs/quad.md), so model
// and RTL start from identical words.
#pragma once

#include <array>

#include "model/quad.h"
#include "ref/quad_float.h"

namespace phongsim {

enum class QuadMode { quadratic, linear };

// The screen the walker clips to (pixels), at most 2048 x 2048.
struct QuadScreen {
  int width = 2048;
  int height = 2048;
};

// The program for `tri` (vertices within [0, 2048] in both coordinates; Error otherwise) with
// channel colours `colour` (C0..C5 over the triangle's own vertex order). Degenerate triangles
// and triangles covering no pixel centre give a program with no rows.
[[nodiscard]] QuadProgram quad_program(const quad::SubpixelTri& tri,
                                       const std::array<quad::Coeffs, 3>& colour,
                                       const QuadFormats& formats, QuadScreen screen = {});

// Guard bits (accumulator fraction bits below the output LSB) that bound the accumulated
// rounding of the six channel words by half an output LSB over a box of w x h pixels:
// the smallest G with 1 + (w-1)² + (w-1)(h-1) + (h-1)² <= 2^G (docs/quad.md).
[[nodiscard]] int quad_guard_bits_needed(int w, int h);

}  // namespace phongsim
