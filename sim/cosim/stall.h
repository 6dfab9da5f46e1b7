// Source-idle and sink-backpressure patterns for the co-simulation harness. One grammar serves
// both sides; "active" means the source offers its next transaction / the sink is ready.
//
//   none            always active (no stalls)
//   periodic:BITS   cycle c uses BITS[c mod len]: '1' active, '0' stalled (e.g. 1110, 0001);
//                   at most kMaxPeriodicBits bits
//   random:P        stalled with probability P (0 <= P <= kMaxStallProbability) each cycle
//   long[:S[:R]]    R active cycles, then S stalled cycles, repeating (default S=100, R=400);
//                   S and R in 1..kMaxLongCycles
// The bounds keep every pattern's stalls short enough that a run ends: a stall is never longer
// than a million cycles, a random one is a hundred cycles long on average at most.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/rng.h"

namespace phongsim {

inline constexpr std::size_t kMaxPeriodicBits = 4096;
inline constexpr double kMaxStallProbability = 0.99;
inline constexpr std::uint64_t kMaxLongCycles = 1'000'000;

class StallPattern {
 public:
  StallPattern() = default;  // none

  // Throws Error naming the spec when it does not follow the grammar above.
  static StallPattern parse(std::string_view spec);

  [[nodiscard]] std::string str() const;
  [[nodiscard]] bool never_stalls() const { return kind_ == Kind::none; }

  // Longest run of stalled cycles the pattern can make by construction (0 for random, whose
  // runs are unbounded but vanishingly unlikely to be long).
  [[nodiscard]] std::uint64_t longest_stall() const;

  // Whether the side is active in `cycle`. Random patterns draw from `rng`; call once per cycle,
  // in cycle order, so a run is reproducible.
  [[nodiscard]] bool active(std::uint64_t cycle, Rng& rng) const;

 private:
  enum class Kind { none, periodic, random, long_stall };
  Kind kind_ = Kind::none;
  std::string bits_;
  double probability_ = 0.0;
  std::uint64_t stall_ = 0;
  std::uint64_t run_ = 0;
};

}  // namespace phongsim
