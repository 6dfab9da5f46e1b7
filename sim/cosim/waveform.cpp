#include "sim/cosim/waveform.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>

#include "base/error.h"
#include "base/temporaries.h"

// GTKWave's FST implementation, compiled here as Verilator compiles it into its runtime
// (verilated_fst_c.cpp), under names of its own (a Verilated testbench linking this library has
// Verilator's copy too).
#include "sim/cosim/fst_private_names.h"
#define FST_CONFIG_INCLUDE "fst_config.h"
#include "gtkwave/fastlz.c"  // NOLINT
#include "gtkwave/fstapi.c"  // NOLINT
#include "gtkwave/lz4.c"     // NOLINT

namespace phongsim {

WaveFormat wave_format(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".fst") return WaveFormat::fst;
  if (ext == ".vcd") return WaveFormat::vcd;
  throw Error(fmt::format(
      "--trace {}: a waveform is .fst (compact, GTKWave) or .vcd (any viewer); name the file so",
      path.string()));
}

void fst_to_vcd(const std::filesystem::path& fst, std::FILE* vcd) {
  void* ctx = fstReaderOpen(fst.c_str());
  if (ctx == nullptr) throw Error(fmt::format("cannot read the waveform {}", fst.string()));
  fstReaderProcessHier(ctx, vcd);
  fstReaderSetFacProcessMaskAll(ctx);
  fstReaderIterBlocks(ctx, nullptr, nullptr, vcd);
  fstReaderClose(ctx);
}

std::vector<WaveSignal> waveform_signals(const std::filesystem::path& fst) {
  void* in = fstReaderOpen(fst.c_str());
  if (in == nullptr) throw Error(fmt::format("cannot read the waveform {}", fst.string()));
  // fstapi's names of its variable types (as fst2vcd writes them), FST_VT_VCD_EVENT on.
  static const char* const kTypes[] = {
      "event",   "integer",  "parameter", "real",   "real_parameter", "reg",     "supply0",
      "supply1", "time",     "tri",       "triand", "trior",          "trireg",  "tri0",
      "tri1",    "wand",     "wire",      "wor",    "port",           "sparray", "realtime",
      "string",  "bit",      "logic",     "int",    "shortint",       "longint", "byte",
      "enum",    "shortreal"};
  std::vector<WaveSignal> out;
  std::vector<std::string> scope;
  while (const fstHier* h = fstReaderIterateHier(in)) {
    if (h->htyp == FST_HT_SCOPE) {
      scope.emplace_back(h->u.scope.name);
    } else if (h->htyp == FST_HT_UPSCOPE && !scope.empty()) {
      scope.pop_back();
    } else if (h->htyp == FST_HT_VAR) {
      std::string path;
      for (const std::string& sc : scope) path += (path.empty() ? "" : ".") + sc;
      const std::string name = h->u.var.name;
      const unsigned t = h->u.var.typ;
      out.push_back({path, name.substr(0, name.find(' ')), h->u.var.length,
                     t < std::size(kTypes) ? kTypes[t] : fmt::format("type {}", t),
                     h->u.var.direction != FST_VD_IMPLICIT});
    }
  }
  fstReaderClose(in);
  return out;
}

namespace {

// The annotation's values, time by time (a later set at the same time replaces an earlier one),
// merged into the copied value changes in time order.
struct Changes {
  std::map<std::uint64_t, std::map<fstHandle, std::string>> at;
  void set(std::uint64_t time, fstHandle h, std::string value) { at[time][h] = std::move(value); }
};

std::string bits(std::uint64_t value, std::uint32_t width) {
  std::string s(width, '0');
  for (std::uint32_t i = 0; i < width && i < 64; ++i) {
    if ((value >> i) & 1U) s[width - 1 - i] = '1';
  }
  return s;
}

struct Copy {
  void* out = nullptr;
  std::unordered_map<fstHandle, fstHandle> handle;  // reader's -> writer's
  Changes* notes = nullptr;
  std::map<std::uint64_t, std::map<fstHandle, std::string>>::iterator next;
  bool timed = false;
  std::uint64_t now = 0;

  void time(std::uint64_t t) {
    if (!timed || t != now) {
      fstWriterEmitTimeChange(out, t);
      timed = true;
      now = t;
    }
  }
  // The annotation's changes up to time t (inclusive) go first.
  void flush(std::uint64_t t) {
    for (; next != notes->at.end() && next->first <= t; ++next) {
      time(next->first);
      for (const auto& [h, v] : next->second) fstWriterEmitValueChange(out, h, v.data());
    }
  }
};

void copy_change(void* user, std::uint64_t time, fstHandle fac, const unsigned char* value) {
  auto& c = *static_cast<Copy*>(user);
  c.flush(time);
  c.time(time);
  fstWriterEmitValueChange(c.out, c.handle.at(fac), value);
}

void copy_varlen(void* user, std::uint64_t time, fstHandle fac, const unsigned char* value,
                 std::uint32_t len) {
  auto& c = *static_cast<Copy*>(user);
  c.flush(time);
  c.time(time);
  fstWriterEmitVariableLengthValueChange(c.out, c.handle.at(fac), value, len);
}

struct Sightings {
  std::uint64_t from = 0, to = 0;
  struct Watch {
    std::size_t stage = 0;
    std::size_t signal = 0;    // which of the stage's signals
    std::string want;          // the stage's bits
    std::uint32_t lowest = 0;  // where they are in the signal (from its least significant bit)
  };
  std::unordered_map<fstHandle, std::vector<Watch>> watch;
  std::unordered_map<fstHandle, std::pair<std::uint64_t, std::string>> current;  // since, value
  std::vector<StageSighting>* out = nullptr;

  void check(fstHandle h, std::uint64_t since, std::uint64_t until, const std::string& v) {
    if (since > to || until < from) return;  // held over [since, until): outside the window
    for (const Watch& w : watch.at(h)) {
      if (v.size() >= w.want.size() + w.lowest &&
          v.compare(v.size() - w.lowest - w.want.size(), w.want.size(), w.want) == 0) {
        (*out)[w.stage].signals[w.signal].held = true;
      }
    }
  }
};

void sighting(void* user, std::uint64_t time, fstHandle fac, const unsigned char* value) {
  auto& s = *static_cast<Sightings*>(user);
  if (!s.watch.contains(fac)) return;
  const auto it = s.current.find(fac);
  if (it != s.current.end()) s.check(fac, it->second.first, time, it->second.second);
  s.current[fac] = {time, reinterpret_cast<const char*>(value)};
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Whether a signal (its leaf name, `length` bits) is named after a stage `width` bits wide:
// the stage's name, its name with '.' as '_', or its last part after a '.', each optionally
// with a register suffix; and a vector stage's component (name_x, _y, _z) in a signal named
// after the vector, three components packed with x in the low bits. Returns the stage's lowest
// bit in the signal.
std::optional<std::uint32_t> named_after(const std::string& signal, std::uint32_t length,
                                         const std::string& stage, std::uint32_t width) {
  const std::string leaf = lower(signal.substr(0, signal.find_first_of(" [")));
  const auto is = [&](std::string name) {
    std::replace(name.begin(), name.end(), '.', '_');
    for (const char* suffix : {"", "_q", "_d", "_r", "_reg", "_ff"}) {
      if (leaf == name + suffix) return true;
    }
    return false;
  };
  const auto is_named = [&](const std::string& name) {
    const std::size_t dot = name.rfind('.');
    return is(name) || (dot != std::string::npos && is(name.substr(dot + 1)));
  };
  const std::string name = lower(stage);
  if (is_named(name) && length >= width) return 0;
  const std::size_t n = name.size();
  if (n > 2 && name[n - 2] == '_' &&
      (name[n - 1] == 'x' || name[n - 1] == 'y' || name[n - 1] == 'z') && length == 3 * width &&
      is_named(name.substr(0, n - 2))) {
    return static_cast<std::uint32_t>(name[n - 1] - 'x') * width;
  }
  return std::nullopt;
}

}  // namespace

std::vector<StageSighting> find_stages(const std::filesystem::path& fst,
                                       const std::vector<StageValue>& stages,
                                       std::uint64_t from_time, std::uint64_t to_time) {
  std::vector<StageSighting> out(stages.size());
  for (std::size_t i = 0; i < stages.size(); ++i) out[i].stage = stages[i].name;
  void* in = fstReaderOpen(fst.c_str());
  if (in == nullptr) throw Error(fmt::format("cannot read the waveform {}", fst.string()));
  Sightings s;
  s.from = from_time;
  s.to = to_time;
  s.out = &out;
  std::vector<std::string> scope;
  while (const fstHier* h = fstReaderIterateHier(in)) {
    if (h->htyp == FST_HT_SCOPE) {
      scope.emplace_back(h->u.scope.name);
    } else if (h->htyp == FST_HT_UPSCOPE && !scope.empty()) {
      scope.pop_back();
    } else if (h->htyp == FST_HT_VAR && !(scope.size() == 1 && scope[0] == "phongsim")) {
      const std::string name = h->u.var.name;
      for (std::size_t i = 0; i < stages.size(); ++i) {
        const auto width = static_cast<std::uint32_t>(stages[i].value.fmt.width());
        const auto lowest = named_after(name, h->u.var.length, stages[i].name, width);
        if (!lowest) continue;
        std::string path;
        for (const std::string& sc : scope) path += sc + ".";
        out[i].signals.push_back({path + name.substr(0, name.find(' ')), false});
        s.watch[h->u.var.handle].push_back(
            {i, out[i].signals.size() - 1,
             bits(static_cast<std::uint64_t>(stages[i].value.raw), width), *lowest});
      }
    }
  }
  if (!s.watch.empty()) {
    fstReaderClrFacProcessMaskAll(in);
    for (const auto& [h, w] : s.watch) fstReaderSetFacProcessMask(in, h);
    fstReaderIterBlocks(in, sighting, &s, nullptr);
    for (const auto& [h, c] : s.current) s.check(h, c.first, UINT64_MAX, c.second);
  }
  fstReaderClose(in);
  return out;
}

void annotate_waveform(const std::filesystem::path& fst, const WaveNotes& notes) {
  void* in = fstReaderOpen(fst.c_str());
  if (in == nullptr) throw Error(fmt::format("cannot read the waveform {}", fst.string()));
  const TempDir dir("out");
  const std::filesystem::path merged = dir.path() / "annotated.fst";
  void* out = fstWriterCreate(merged.c_str(), 1);
  if (out == nullptr) {
    fstReaderClose(in);
    throw Error(fmt::format("cannot write the waveform {}", merged.string()));
  }
  fstWriterSetTimescale(out, fstReaderGetTimescale(in));
  fstWriterSetTimezero(out, fstReaderGetTimezero(in));
  Copy c;
  c.out = out;
  int depth = 0;
  while (const fstHier* h = fstReaderIterateHier(in)) {
    switch (h->htyp) {
      case FST_HT_SCOPE:
        fstWriterSetScope(out, static_cast<fstScopeType>(h->u.scope.typ), h->u.scope.name,
                          h->u.scope.component);
        ++depth;
        break;
      case FST_HT_UPSCOPE:
        fstWriterSetUpscope(out);
        --depth;
        break;
      case FST_HT_VAR: {
        const fstHandle w = fstWriterCreateVar(
            out, static_cast<fstVarType>(h->u.var.typ), static_cast<fstVarDir>(h->u.var.direction),
            h->u.var.length, h->u.var.name, h->u.var.is_alias ? c.handle.at(h->u.var.handle) : 0);
        if (!h->u.var.is_alias) c.handle[h->u.var.handle] = w;
        break;
      }
      case FST_HT_ATTRBEGIN:
        // Source stems overload the name with a number; a viewer does without them.
        if (h->u.attr.typ == FST_AT_MISC &&
            (h->u.attr.subtype == FST_MT_SOURCESTEM || h->u.attr.subtype == FST_MT_SOURCEISTEM)) {
          break;
        }
        fstWriterSetAttrBegin(out, static_cast<fstAttrType>(h->u.attr.typ), h->u.attr.subtype,
                              h->u.attr.name, h->u.attr.arg);
        break;
      case FST_HT_ATTREND:
        fstWriterSetAttrEnd(out);
        break;
      default:
        break;
    }
  }
  for (; depth > 0; --depth) fstWriterSetUpscope(out);

  // The phongsim scope.
  fstWriterSetScope(out, FST_ST_VCD_MODULE, "phongsim", nullptr);
  const auto var = [&](const std::string& name, std::uint32_t width) {
    return fstWriterCreateVar(out, FST_VT_SV_LOGIC, FST_VD_IMPLICIT, width, name.c_str(), 0);
  };
  const fstHandle in_accept = var("in_accept", 1), in_vector = var("in_vector", 64);
  const fstHandle out_take = var("out_take", 1), out_vector = var("out_vector", 64),
                  out_index = var("out_index", 32), any = var("mismatch", 1);
  std::vector<fstHandle> expected, mismatch;
  std::vector<std::uint32_t> widths;
  for (const Field& f : notes.fields) {
    widths.push_back(static_cast<std::uint32_t>(f.fmt.width()));
    expected.push_back(var("expected_" + f.name, widths.back()));
    mismatch.push_back(var("mismatch_" + f.name, 1));
  }
  fstWriterSetUpscope(out);

  // Each cycle with a handshake sets its values at 2·cycle; the next cycle without one clears.
  Changes changes;
  const auto x = [](std::uint32_t w) { return std::string(w, 'x'); };
  const auto clear_inputs = [&](std::uint64_t t) {
    changes.set(t, in_accept, "0");
    changes.set(t, in_vector, x(64));
  };
  const auto clear_outputs = [&](std::uint64_t t) {
    changes.set(t, out_take, "0");
    changes.set(t, out_vector, x(64));
    changes.set(t, out_index, x(32));
    changes.set(t, any, "0");
    for (std::size_t i = 0; i < expected.size(); ++i) {
      changes.set(t, expected[i], x(widths[i]));
      changes.set(t, mismatch[i], "0");
    }
  };
  const std::uint64_t start = fstReaderGetStartTime(in);
  clear_inputs(start);
  clear_outputs(start);
  for (std::size_t k = 0; k < notes.accepts.size(); ++k) {
    const auto& a = notes.accepts[k];
    changes.set(2 * a.cycle, in_accept, "1");
    changes.set(2 * a.cycle, in_vector, bits(a.vector, 64));
    if (k + 1 == notes.accepts.size() || notes.accepts[k + 1].cycle != a.cycle + 1) {
      clear_inputs(2 * a.cycle + 2);
    }
  }
  for (std::size_t k = 0; k < notes.outputs.size(); ++k) {
    const auto& o = notes.outputs[k];
    const std::uint64_t t = 2 * o.cycle;
    clear_outputs(t);  // an unexpected output has no vector and no expected values
    changes.set(t, out_take, "1");
    bool differs = !o.owed;
    if (o.owed) {
      changes.set(t, out_vector, bits(o.vector, 64));
      changes.set(t, out_index, bits(o.index, 32));
      for (std::size_t i = 0; i < expected.size(); ++i) {
        changes.set(t, expected[i], bits(static_cast<std::uint64_t>(o.expected[i]), widths[i]));
        const bool d = o.expected[i] != o.got[i];
        changes.set(t, mismatch[i], d ? "1" : "0");
        differs = differs || d;
      }
    }
    changes.set(t, any, differs ? "1" : "0");
    if (k + 1 == notes.outputs.size() || notes.outputs[k + 1].cycle != o.cycle + 1) {
      clear_outputs(t + 2);
    }
  }

  c.notes = &changes;
  c.next = changes.at.begin();
  fstReaderSetFacProcessMaskAll(in);
  fstReaderIterBlocksSetNativeDoublesOnCallback(in, 1);
  fstReaderIterBlocks2(in, copy_change, copy_varlen, &c, nullptr);
  c.flush(UINT64_MAX);
  fstReaderClose(in);
  fstWriterClose(out);
  // Copied over the original (its inode stays: the caller's temporary keeps its lock).
  std::filesystem::copy_file(merged, fst, std::filesystem::copy_options::overwrite_existing);
}

}  // namespace phongsim
