#include "sim/cosim/eval.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "base/error.h"
#include "base/output_file.h"
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

// All input vectors of the file, flattened in model inputs() order.
std::vector<std::int64_t> read_vectors(const std::filesystem::path& path,
                                       const std::vector<Field>& fields, bool real) {
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("{}: cannot read input vectors", path.string()));
  std::vector<std::int64_t> values;
  std::vector<std::size_t> column_of_field;  // field i is in column column_of_field[i]
  std::size_t columns = 0;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const auto content = trim(line);
    if (content.empty() || content.front() == '#') continue;
    const auto cells = split_csv(content);
    const std::string where_line = fmt::format("{}:{}", path.string(), line_no);
    if (columns == 0) {  // header
      columns = cells.size();
      for (const auto& c : cells) {
        if (std::none_of(fields.begin(), fields.end(),
                         [&](const Field& f) { return f.name == c; })) {
          throw Error(fmt::format("{}: unknown column '{}'", where_line, c));
        }
      }
      for (const auto& f : fields) {
        const auto it = std::find(cells.begin(), cells.end(), f.name);
        if (it == cells.end())
          throw Error(fmt::format("{}: missing column '{}'", where_line, f.name));
        if (std::find(it + 1, cells.end(), f.name) != cells.end()) {
          throw Error(fmt::format("{}: column '{}' appears twice", where_line, f.name));
        }
        column_of_field.push_back(static_cast<std::size_t>(it - cells.begin()));
      }
      continue;
    }
    if (cells.size() != columns) {
      throw Error(fmt::format("{}: {} values, but the header has {} columns", where_line,
                              cells.size(), columns));
    }
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const auto where = fmt::format("{}: column '{}'", where_line, fields[i].name);
      const auto cell = cells[column_of_field[i]];
      values.push_back(real ? parse_real(cell, fields[i], where)
                            : parse_raw(cell, fields[i], where));
    }
  }
  if (columns == 0) throw Error(fmt::format("{}: no header row", path.string()));
  return values;
}

}  // namespace

std::size_t eval_csv(PipelineModel& model, const DutFactory& make_dut,
                     const std::filesystem::path& in, const std::filesystem::path& out, bool real) {
  const auto& ins = model.inputs();
  const auto& outs = model.outputs();
  const std::vector<std::int64_t> vectors = read_vectors(in, ins, real);
  const std::size_t count = vectors.size() / ins.size();
  OutputFile file(out);

  std::vector<std::int64_t> results;
  if (!make_dut) {
    model.reset();
    (void)model.eval_batch(std::span(vectors).first(count * ins.size()), results);
  } else {
    DutPtr dut = make_dut();
    const HarnessResult r = stream_vectors(*dut, ins.size(), outs.size(), vectors,
                                           [&](std::span<const std::int64_t> o) {
                                             results.insert(results.end(), o.begin(), o.end());
                                           });
    if (r.reason != StopReason::finished) throw Error("RTL evaluation failed: " + r.message);
  }

  std::string text;
  for (std::size_t i = 0; i < outs.size(); ++i) text += (i ? "," : "") + outs[i].name;
  text += "\n";
  for (std::size_t row = 0; row < results.size() / outs.size(); ++row) {
    for (std::size_t i = 0; i < outs.size(); ++i) {
      const std::int64_t raw = results[row * outs.size() + i];
      if (i > 0) text += ",";
      text += real ? fmt::format("{}", fx::to_real(raw, outs[i].fmt)) : std::to_string(raw);
    }
    text += "\n";
  }
  std::fputs(text.c_str(), file.get());
  file.commit();
  return results.size() / outs.size();
}

}  // namespace phongsim
