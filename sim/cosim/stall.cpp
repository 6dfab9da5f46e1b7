#include "sim/cosim/stall.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>

#include "base/error.h"

namespace phongsim {
namespace {

template <class T>
bool parse_number(std::string_view text, T& value) {
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return !text.empty() && ec == std::errc{} && ptr == end;
}

}  // namespace

StallPattern StallPattern::parse(std::string_view spec) {
  const auto bad = [&](std::string_view why) {
    return Error(
        fmt::format("stall pattern '{}': {} (expected none, periodic:BITS, random:P or "
                    "long[:STALL[:RUN]])",
                    spec, why));
  };
  StallPattern p;
  const auto colon = spec.find(':');
  const std::string_view kind = spec.substr(0, colon);
  const std::string_view rest = colon == std::string_view::npos ? "" : spec.substr(colon + 1);

  if (kind == "none" && colon == std::string_view::npos) return p;
  if (kind == "periodic") {
    if (rest.empty() || rest.find_first_not_of("01") != std::string_view::npos) {
      throw bad("BITS must be a non-empty string of 0 and 1");
    }
    if (rest.find('1') == std::string_view::npos) throw bad("BITS must contain at least one 1");
    if (rest.size() > kMaxPeriodicBits) {
      throw bad(fmt::format("BITS has {} bits, at most {}", rest.size(), kMaxPeriodicBits));
    }
    p.kind_ = Kind::periodic;
    p.bits_ = rest;
    return p;
  }
  if (kind == "random") {
    if (!parse_number(rest, p.probability_) || !(p.probability_ >= 0.0) ||
        !(p.probability_ <= kMaxStallProbability)) {
      throw bad(fmt::format("P must be a number in [0, {}]", kMaxStallProbability));
    }
    p.kind_ = Kind::random;
    return p;
  }
  if (kind == "long") {
    p.kind_ = Kind::long_stall;
    p.stall_ = 100;
    p.run_ = 400;
    if (colon != std::string_view::npos) {
      const auto colon2 = rest.find(':');
      if (!parse_number(rest.substr(0, colon2), p.stall_) || p.stall_ == 0 ||
          p.stall_ > kMaxLongCycles) {
        throw bad(fmt::format("STALL must be an integer in 1..{}", kMaxLongCycles));
      }
      if (colon2 != std::string_view::npos && (!parse_number(rest.substr(colon2 + 1), p.run_) ||
                                               p.run_ == 0 || p.run_ > kMaxLongCycles)) {
        throw bad(fmt::format("RUN must be an integer in 1..{}", kMaxLongCycles));
      }
    }
    return p;
  }
  throw bad("unknown pattern");
}

std::string StallPattern::str() const {
  switch (kind_) {
    case Kind::none:
      return "none";
    case Kind::periodic:
      return "periodic:" + bits_;
    case Kind::random:
      return fmt::format("random:{}", probability_);
    case Kind::long_stall:
      return fmt::format("long:{}:{}", stall_, run_);
  }
  return "?";
}

std::uint64_t StallPattern::longest_stall() const {
  switch (kind_) {
    case Kind::periodic: {  // longest run of 0s, wrapping around the end
      const std::string twice = bits_ + bits_;
      std::uint64_t longest = 0;
      std::uint64_t run = 0;
      for (const char b : twice) {
        run = b == '0' ? run + 1 : 0;
        longest = std::max(longest, run);
      }
      return longest;
    }
    case Kind::long_stall:
      return stall_;
    case Kind::none:
    case Kind::random:
      return 0;
  }
  return 0;
}

bool StallPattern::active(std::uint64_t cycle, Rng& rng) const {
  switch (kind_) {
    case Kind::none:
      return true;
    case Kind::periodic:
      return bits_[cycle % bits_.size()] == '1';
    case Kind::random:
      return !rng.chance(probability_);
    case Kind::long_stall:
      return cycle % (run_ + stall_) < run_;
  }
  return true;
}

}  // namespace phongsim
