#include "model/shade_kb.h"

#include <fmt/format.h>

#include "base/error.h"

namespace phongsim {

ShadeKbModel::ShadeKbModel(const KbFormats& formats, bool stages)
    : engines_{KbModel(formats, stages), KbModel(formats, stages), KbModel(formats, stages)} {
  const fx::Format coord{false, kCoordBits, 0};
  const fx::Format count{false, formats.event_bits, 0};
  inputs_ = {{"n", fx::Format{false, KbFormats::kIndexBits, 0}}, {"x0", coord}, {"y0", coord}};
  for (const char* field : {"count", "f", "d1", "d2"}) {
    for (const char* ch : {"r", "g", "b"}) {
      inputs_.push_back({fmt::format("{}_{}", field, ch),
                         std::string_view(field) == "count" ? count : formats.acc});
    }
  }
  inputs_.push_back({"reload", fx::Format{false, 1, 0}});
  outputs_ = {
      {"x", coord}, {"y", coord}, {"r", formats.out}, {"g", formats.out}, {"b", formats.out}};
}

void ShadeKbModel::reset() {
  for (KbModel& e : engines_) e.reset();
  left_ = {};
  for (auto& p : pixels_) p.clear();
  spans_.clear();
  i_ = 0;
}

ShadeKbModel::Route ShadeKbModel::route() const {
  if (left_[0] == 0 && left_[1] == 0 && left_[2] == 0) return {};
  const unsigned first = left_[0] != 0 ? 0 : left_[1] != 0 ? 1 : 2;
  return {false, 1U << first};
}

std::array<std::int64_t, 6> ShadeKbModel::channel_word(std::span<const std::int64_t> in, int ch) {
  const auto c = static_cast<std::size_t>(ch);
  return {in[kN], in[kCount + c], in[kF + c], in[kD1 + c], in[kD2 + c], in[kReload]};
}

std::size_t ShadeKbModel::eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  // Demux: the word to its channels (and a header's x0, y to the span queue).
  const Route r = route();
  if (r.header) {
    spans_.push_back({in[kX], in[kY]});
    for (std::size_t c = 0; c < kChannels; ++c) left_[c] = in[kCount + c];
  } else {
    for (std::size_t c = 0; c < kChannels; ++c) {
      if ((r.targets >> c & 1U) != 0) --left_[c];
    }
  }
  // The engines: each emits its pixels as soon as the RTL's could.
  for (int c = 0; c < kChannels; ++c) {
    if ((r.targets >> c & 1U) == 0) continue;
    const auto word = channel_word(in, c);
    scratch_.clear();
    (void)engines_[static_cast<std::size_t>(c)].eval(word, scratch_);
    for (std::size_t k = 0; k + 1 < scratch_.size(); k += 2) {
      pixels_[static_cast<std::size_t>(c)].push_back({scratch_[k], scratch_[k + 1] != 0});
    }
  }
  // Join: one pixel when every channel has one; x = x0 + i (wrapping at 2048), y the span's.
  std::size_t emitted = 0;
  const std::int64_t coord_mask = (std::int64_t{1} << kCoordBits) - 1;
  while (!pixels_[0].empty() && !pixels_[1].empty() && !pixels_[2].empty()) {
    if (spans_.empty()) throw Error("shade_kb model: a pixel without a span");  // cannot happen
    const Span& s = spans_.front();
    out.insert(out.end(), {(s.x + i_) & coord_mask, s.y, pixels_[0].front().value,
                           pixels_[1].front().value, pixels_[2].front().value});
    const bool last = pixels_[0].front().last;
    for (auto& p : pixels_) p.pop_front();
    if (last) {
      spans_.pop_front();
      i_ = 0;
    } else {
      i_ = (i_ + 1) & coord_mask;
    }
    ++emitted;
  }
  return emitted;
}

}  // namespace phongsim
