// Named width configuration: one TOML file in configs/<pipeline>/<name>.toml is the single source
// of a pipeline's formats and modes for both the model (read here) and the RTL (rtl_parameters():
// one mechanical rule, which Verilation, lint and synthesis all use).
//
//   pipeline = "lirp"                 # which pipeline the file configures
//   description = "..."               # one line for listings and reports
//   [format]  p = "S1.10"             # signal formats  -> -GPFmt=<fx_pkg format word>
//   [mode]    out_round = "half_even" # named modes     -> -GOutRound=<encoding>
//   [param]   k = 2                   # plain integers  -> -GK=2
//   [setup]   policy = "d2_only"      # software-side choices (stimulus, setup); no RTL effect
//
// The pipeline's model asks for the keys it needs; any key it did not ask for is reported as
// unknown by check_all_used(), so a typo cannot silently fall back to a default.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "model/fixed.h"

namespace phongsim {

// One parameter of the pipeline's top module.
// A format as the RTL's *Fmt parameters carry it (fx_pkg::fx_fmt): signed·65536 + int·256 +
// frac.
[[nodiscard]] constexpr std::int64_t format_word(fx::Format f) {
  return (f.is_signed ? 65536 : 0) + f.int_bits * 256 + f.frac_bits;
}

struct RtlParam {
  std::string name;  // UpperCamelCase: [mode] out_round -> OutRound, [format] p -> PFmt
  std::int64_t value;
  // Where it comes from, in words (phongsim contract): "[format] p = S1.10 (format word: ...)",
  // "[mode] out_round = half_even (encoding 2)", "[param] k = 2".
  std::string meaning;
  // The RTL sees name and value only: two parameters that set the same value are equal.
  bool operator==(const RtlParam& o) const { return name == o.name && value == o.value; }
};

class Config {
 public:
  // Reads and syntax-checks a file; throws Error("<file>: ...") naming the problem (and line).
  static Config load(const std::filesystem::path& path);
  // Same from text; `origin` stands in for the file name in messages and gives the config name.
  static Config parse(std::string_view text, const std::string& origin);

  [[nodiscard]] const std::string& name() const { return name_; }  // file stem, e.g. "default"
  [[nodiscard]] const std::string& origin() const { return origin_; }
  [[nodiscard]] const std::string& pipeline() const { return pipeline_; }
  [[nodiscard]] const std::string& description() const { return description_; }

  // Typed accessors; each throws Error naming file, table, key and line when the key is missing
  // or its value is not valid.
  [[nodiscard]] fx::Format format(const std::string& key) const;
  [[nodiscard]] fx::Round round(const std::string& key) const;
  [[nodiscard]] fx::Overflow overflow(const std::string& key) const;
  [[nodiscard]] std::int64_t param(const std::string& key, std::int64_t lo, std::int64_t hi) const;
  // [setup] values: one of `allowed`, or an integer in [lo, hi].
  [[nodiscard]] std::string setup(const std::string& key,
                                  std::initializer_list<std::string_view> allowed) const;
  [[nodiscard]] std::int64_t setup_integer(const std::string& key, std::int64_t lo,
                                           std::int64_t hi) const;

  // The top module's parameters, in a fixed order ([format], [mode], [param]; keys sorted):
  //   [format] p = "S1.10"           ->  PFmt = fx_pkg format word (signed*65536 + int*256 + frac)
  //   [mode]   out_round = "half_up" ->  OutRound = the fx_pkg encoding of the mode
  //   [param]  k = 2                 ->  K = 2
  // [setup] keys have no RTL effect. Validation (widths, required keys) is the model's job; this
  // throws Error only for what it cannot translate. Marks no key as used.
  [[nodiscard]] std::vector<RtlParam> rtl_parameters() const;

  // Throws Error for the first key in the file that no accessor asked for.
  void check_all_used() const;

  // Throws Error("<origin>: <message>") - for pipeline models that reject a combination of values.
  [[noreturn]] void fail(const std::string& message) const;

 private:
  struct Entry {
    std::string text;  // value as written (string values unquoted)
    std::int64_t integer = 0;
    bool is_integer = false;
    int line = 0;
  };
  const Entry& entry(const std::string& table, const std::string& key) const;
  std::int64_t integer(const std::string& table, const std::string& key, std::int64_t lo,
                       std::int64_t hi) const;

  std::string origin_;
  std::string name_;
  std::string pipeline_;
  std::string description_;
  std::map<std::string, std::map<std::string, Entry>> tables_;  // "format" -> key -> entry
  mutable std::set<std::string> used_;                          // "table.key"
};

}  // namespace phongsim
