#include "sim/cosim/eval.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "base/error.h"
#include "base/text.h"
#include "sim/cosim/harness.h"

namespace phongsim {
namespace {

std::int64_t parse_raw(std::string_view text, const Field& f, const std::string& where) {
  const bool negative = !text.empty() && text.front() == '-';
  std::string_view digits = negative ? text.substr(1) : text;
  int base = 10;
  if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
    digits.remove_prefix(2);
    base = 16;
  }
  std::uint64_t magnitude = 0;
  const auto* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, magnitude, base);
  if (digits.empty() || ec != std::errc{} || ptr != end || (negative && base == 16)) {
    throw Error(
        fmt::format("{}: '{}' is not an integer (use --real for real values)", where, text));
  }
  if (base == 16) {  // a bit pattern of the field's width
    if (f.fmt.width() < 64 && (magnitude >> f.fmt.width()) != 0) {
      throw Error(fmt::format("{}: {} has more than the {} bits of {}", where, text, f.fmt.width(),
                              f.fmt.str()));
    }
    return fx::from_bits(magnitude, f.fmt);
  }
  const auto value =
      negative ? -static_cast<__int128>(magnitude) : static_cast<__int128>(magnitude);
  if (value < f.fmt.min_raw() || value > f.fmt.max_raw()) {
    throw Error(fmt::format("{}: {} is outside {} (raw {}..{})", where, text, f.fmt.str(),
                            f.fmt.min_raw(), f.fmt.max_raw()));
  }
  return static_cast<std::int64_t>(value);
}

std::int64_t parse_real(std::string_view text, const Field& f, const std::string& where) {
  double x = 0;
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, x);
  if (text.empty() || ec != std::errc{} || ptr != end || !std::isfinite(x)) {
    throw Error(fmt::format("{}: '{}' is not a real number", where, text));
  }
  const double q = fx::round_scaled(x, f.fmt.frac_bits, fx::Round::half_even);
  if (!fx::raw_in_range(q, f.fmt)) {
    throw Error(fmt::format("{}: {} is outside the range of {} [{}, {}]", where, text, f.fmt.str(),
                            fx::to_real(f.fmt.min_raw(), f.fmt),
                            fx::to_real(f.fmt.max_raw(), f.fmt)));
  }
  return static_cast<std::int64_t>(q);
}

// The input vectors of a file, one at a time, in model inputs() order.
class VectorReader {
 public:
  VectorReader(const std::filesystem::path& path, const std::vector<Field>& fields, bool real)
      : path_(path), in_(path), fields_(fields), real_(real) {
    std::error_code ec;
    if (!in_ || std::filesystem::is_directory(path, ec)) {
      throw Error(fmt::format("{}: cannot read input vectors", path.string()));
    }
    if (!next_cells()) throw Error(fmt::format("{}: no header row", path.string()));
    const std::string where_line = fmt::format("{}:{}", path_.string(), line_no_);
    columns_ = cells_.size();
    for (const auto& c : cells_) {
      if (std::none_of(fields.begin(), fields.end(), [&](const Field& f) { return f.name == c; })) {
        throw Error(fmt::format("{}: unknown column '{}'", where_line, c));
      }
    }
    for (const auto& f : fields) {
      const auto it = std::find(cells_.begin(), cells_.end(), f.name);
      if (it == cells_.end())
        throw Error(fmt::format("{}: missing column '{}'", where_line, f.name));
      if (std::find(it + 1, cells_.end(), f.name) != cells_.end()) {
        throw Error(fmt::format("{}: column '{}' appears twice", where_line, f.name));
      }
      column_of_field_.push_back(static_cast<std::size_t>(it - cells_.begin()));
    }
  }

  // Fills `v` with the next vector; false at the end of the file.
  bool next(std::span<std::int64_t> v) {
    if (!next_cells()) return false;
    const std::string where_line = fmt::format("{}:{}", path_.string(), line_no_);
    if (cells_.size() != columns_) {
      throw Error(fmt::format("{}: {} values, but the header has {} columns", where_line,
                              cells_.size(), columns_));
    }
    for (std::size_t i = 0; i < fields_.size(); ++i) {
      const auto where = fmt::format("{}: column '{}'", where_line, fields_[i].name);
      const auto cell = cells_[column_of_field_[i]];
      v[i] = real_ ? parse_real(cell, fields_[i], where) : parse_raw(cell, fields_[i], where);
    }
    return true;
  }

 private:
  // The next line with content, split into cells; false at the end of the file.
  bool next_cells() {
    while (std::getline(in_, line_)) {
      ++line_no_;
      const auto content = trim(line_);
      if (content.empty() || content.front() == '#') continue;
      cells_ = split_csv(content);
      return true;
    }
    if (in_.bad()) throw Error(fmt::format("{}: cannot read input vectors", path_.string()));
    return false;
  }

  std::filesystem::path path_;
  std::ifstream in_;
  const std::vector<Field>& fields_;
  bool real_;
  std::string line_;
  std::vector<std::string_view> cells_;       // views into line_
  std::vector<std::size_t> column_of_field_;  // field i is in column column_of_field_[i]
  std::size_t columns_ = 0;
  int line_no_ = 0;
};

}  // namespace

EvalResult eval_csv(PipelineModel& model, const DutFactory& make_dut,
                    const std::filesystem::path& in, std::FILE* out, bool real,
                    InputContract contract, StagesFn stages, std::FILE* stages_out) {
  const auto& ins = model.inputs();
  const auto& outs = model.outputs();
  VectorReader reader(in, ins, real);

  std::string header;
  for (std::size_t i = 0; i < outs.size(); ++i) header += (i ? "," : "") + outs[i].name;
  fmt::print(out, "{}\n", header);
  EvalResult result;
  std::size_t& rows = result.rows;
  // The stages come from a model of their own, which has seen the vectors before each one.
  std::unique_ptr<PipelineModel> stage_model;
  std::vector<std::int64_t> scratch;
  if (stages != nullptr && stages_out != nullptr) {
    stage_model = model.clone();
    stage_model->reset();
    fmt::print(stages_out, "vector,stage,format,raw,real\n");
  }
  const auto next = [&](std::span<std::int64_t> v) {
    if (!reader.next(v)) return false;
    if (stage_model) {
      for (const StageValue& s : stages(*stage_model, v)) {
        fmt::print(stages_out, "{},{},{},{},{}\n", result.vectors, s.name, s.value.fmt.str(),
                   s.value.raw, fx::to_real(s.value.raw, s.value.fmt));
      }
      scratch.clear();
      (void)stage_model->eval(v, scratch);
    }
    ++result.vectors;
    contract.count(v, v.size(), result.contract);
    return true;
  };
  std::string row;
  const auto write_row = [&](std::span<const std::int64_t> o) {
    row.clear();
    for (std::size_t i = 0; i < outs.size(); ++i) {
      if (i > 0) row += ",";
      row += real ? fmt::format("{}", fx::to_real(o[i], outs[i].fmt)) : std::to_string(o[i]);
    }
    row += "\n";
    std::fputs(row.c_str(), out);
    ++rows;
  };
  std::vector<std::int64_t> vector(ins.size());
  if (!make_dut) {
    model.reset();
    std::vector<std::int64_t> results;
    while (next(vector)) {
      results.clear();
      model.eval(vector, results);
      for (std::size_t at = 0; at < results.size(); at += outs.size()) {
        write_row(std::span(results).subspan(at, outs.size()));
      }
    }
  } else {
    DutPtr dut = make_dut();
    const HarnessResult r = stream_vectors(*dut, ins.size(), outs.size(), next, write_row);
    if (r.reason != StopReason::finished) throw Error("RTL evaluation failed: " + r.message);
  }
  return result;
}

}  // namespace phongsim
