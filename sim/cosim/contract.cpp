#include "sim/cosim/contract.h"

#include <fmt/format.h>

#include <numeric>

namespace phongsim {

std::uint64_t ContractCounts::out() const {
  return std::accumulate(by_clause.begin(), by_clause.end(), std::uint64_t{0});
}

void ContractCounts::add(const ContractCounts& other) {
  in += other.in;
  if (by_clause.size() < other.by_clause.size()) by_clause.resize(other.by_clause.size());
  for (std::size_t i = 0; i < other.by_clause.size(); ++i) by_clause[i] += other.by_clause[i];
}

void InputContract::count(std::span<const std::int64_t> vectors, std::size_t width,
                          ContractCounts& counts) {
  if (!check_ || width == 0) return;
  counts.by_clause.resize(clauses_.size());
  std::vector<std::int16_t> clauses(vectors.size() / width);
  check_(vectors, width, clauses);
  for (const std::int16_t c : clauses) {
    if (c == kIn) {
      ++counts.in;
    } else {
      ++counts.by_clause[static_cast<std::size_t>(c)];
    }
  }
}

std::string InputContract::summary(const ContractCounts& counts) const {
  std::string s = fmt::format("{} in contract, {} out of contract", counts.in, counts.out());
  std::string broken;
  for (std::size_t i = 0; i < counts.by_clause.size() && i < clauses_.size(); ++i) {
    if (counts.by_clause[i] == 0) continue;
    broken += fmt::format("{}{}: {}", broken.empty() ? "" : "; ", clauses_[i], counts.by_clause[i]);
  }
  if (!broken.empty()) s += " (" + broken + ")";
  return s;
}

}  // namespace phongsim
