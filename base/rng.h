// Counter-based random numbers: every (seed, stream, index) starts an independent generator, so
// vector i of a run can be regenerated on its own and every failure reproduces from
// (configuration, seed, vector index).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace phongsim {

// Some static functions below also take GCC vectors (FieldRandom::fill). They are inline, so GCC's
// note that a vector argument's calling convention differs between instruction sets is moot.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream, std::uint64_t index)
      : state_(start(seed, stream, index)) {}

  // A plain splitmix64 sequence from `state` (the float references' test meshes use it).
  static Rng from_state(std::uint64_t state) { return Rng(state); }
  // The state from_state() continues this sequence from.
  [[nodiscard]] std::uint64_t state() const { return state_; }
  // Skips `count` values of next().
  void discard(std::uint64_t count) { state_ += count * kGamma; }

  // splitmix64 (Steele, Lea, Flood 2014).
  std::uint64_t next() { return finalize(state_ += kGamma); }

  // The next out.size() values of next(), each computed on its own (the k-th is a function of
  // the state plus k steps): no chain of dependent steps.
  void fill(std::span<std::uint64_t> out) {
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = output(state_, k);
    state_ += out.size() * kGamma;
  }

  // The same without an object, for loops over many generators that the compiler vectorizes:
  // the state Rng(seed, stream, index) starts from, and output k of fill() from a state. The
  // static functions below take std::uint64_t or a GCC vector of them (one generator per lane).
  static std::uint64_t start(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
    return mix(seed ^ mix(stream + 0x51ed2701f3a5c7b9ULL) ^ mix(~index));
  }
  template <class U>
  static U output(U state, std::uint64_t k) {
    return finalize(state + (k + 1) * kGamma);
  }

  // Uniform in [0, n) for n >= 1 (multiply-shift; the bias is below 2^-64 * n).
  std::uint64_t below(std::uint64_t n) { return scaled(next(), n); }
  // below(n) from an output of next() (or fill()).
  static std::uint64_t scaled(std::uint64_t z, std::uint64_t n) {
    return static_cast<std::uint64_t>((static_cast<unsigned __int128>(z) * n) >> 64);
  }
  // scaled() from 32-bit halves instead of a 128-bit product: a loop of it vectorizes.
  template <class U>
  static U scaled_halves(U z, std::uint64_t n) {
    constexpr std::uint64_t kLow = 0xffffffffU;
    const U zl = z & kLow, zh = z >> 32;
    const std::uint64_t nl = n & kLow, nh = n >> 32;
    const U ll = zl * nl, lh = zl * nh, hl = zh * nl;
    const U mid = (ll >> 32) + (lh & kLow) + (hl & kLow);
    return zh * nh + (lh >> 32) + (hl >> 32) + (mid >> 32);
  }

  // scaled() for n < 2^32: two 32 x 32-bit products (one vector instruction each).
  template <class U>
  static U scaled_narrow(U z, std::uint64_t n) {
    return ((z >> 32) * n + (((z & 0xffffffffU) * n) >> 32)) >> 32;
  }

  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  // Uniform in [-1, 1).
  double symmetric() { return 2 * uniform() - 1; }

  bool chance(double p) { return uniform() < p; }
  bool coin() { return (next() >> 63) != 0; }

 private:
  static std::uint64_t mix(std::uint64_t x) { return finalize(x + kGamma); }
  explicit Rng(std::uint64_t raw_state) : state_(raw_state) {}
  static constexpr std::uint64_t kGamma = 0x9e3779b97f4a7c15ULL;
  template <class U>
  static U finalize(U z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  std::uint64_t state_;
};
#pragma GCC diagnostic pop

// Stream identifiers, so stimulus and the two stall patterns never share random numbers.
enum RngStream : std::uint64_t { kStimulusStream = 1, kSourceStream = 2, kSinkStream = 3 };

}  // namespace phongsim
