#include "model/shade_kb.h"

#include <fmt/format.h>

#include <algorithm>

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
  taken_ = {};
  spans_.clear();
  i_ = 0;
}

ShadeKbModel::Route ShadeKbModel::route() const {
  if (left_[0] == 0 && left_[1] == 0 && left_[2] == 0) return {};
  const unsigned first = left_[0] != 0 ? 0 : left_[1] != 0 ? 1 : 2;
  return {false, 1U << first};
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
    (void)engines_[static_cast<std::size_t>(c)].eval(word, pixels_[static_cast<std::size_t>(c)]);
  }
  // Join: one pixel when every channel has one; x = x0 + i (wrapping at 2048), y the span's.
  std::size_t emitted = pixels_[0].size() - taken_[0];
  for (std::size_t c = 1; c < kChannels; ++c) {
    emitted = std::min(emitted, pixels_[c].size() - taken_[c]);
  }
  emitted /= 2;
  const std::int64_t coord_mask = (std::int64_t{1} << kCoordBits) - 1;
  const std::int64_t* ch[kChannels];
  for (std::size_t c = 0; c < kChannels; ++c) ch[c] = pixels_[c].data() + taken_[c];
  const std::size_t at = out.size();
  out.resize(at + 5 * emitted);
  std::int64_t* o = out.data() + at;
  // The span in locals (stores to `out` may alias the members as far as the compiler knows).
  const auto next_span = [this] {
    if (spans_.empty()) throw Error("shade_kb model: a pixel without a span");  // cannot happen
    return spans_.front();
  };
  Span span = emitted != 0 ? next_span() : Span{};
  std::int64_t i = i_;
  for (std::size_t k = 0; k < 2 * emitted; k += 2, o += 5) {
    o[0] = (span.x + i) & coord_mask;
    o[1] = span.y;
    for (std::size_t c = 0; c < kChannels; ++c) o[2 + c] = ch[c][k];
    if (ch[0][k + 1] != 0) {  // the span's last pixel
      spans_.pop_front();
      i = 0;
      if (k + 2 < 2 * emitted) span = next_span();
    } else {
      i = (i + 1) & coord_mask;
    }
  }
  i_ = i;
  // What the join took leaves the queues: all of it, or a prefix once it is long (a channel
  // runs ahead while the others wait for their event words).
  for (std::size_t c = 0; c < kChannels; ++c) {
    std::vector<std::int64_t>& p = pixels_[c];
    taken_[c] += 2 * emitted;
    if (taken_[c] == p.size()) {
      p.clear();
      taken_[c] = 0;
    } else if (taken_[c] >= 4096) {
      p.erase(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(taken_[c]));
      taken_[c] = 0;
    }
  }
  return emitted;
}

}  // namespace phongsim
