// Input contracts: the input domain on which a pipeline's accuracy claims hold (each spec doc's
// "Input contract" section), as named clauses and a check of one vector against them. The
// registry gives each configuration its contract (PipelineInfo::contract); co-simulation and
// eval count the vectors inside and outside it. Bit-exactness is checked on every vector either
// way: a vector out of contract is one on which the model and the RTL still agree, but the
// pipeline's accuracy figures do not apply.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace phongsim {

// How many vectors a run met inside and outside the contract, and, per clause, how many broke
// that clause first (clauses are checked in order; a vector counts once).
struct ContractCounts {
  std::uint64_t in = 0;
  std::vector<std::uint64_t> by_clause;  // indexed like InputContract::clauses()

  [[nodiscard]] std::uint64_t out() const;
  void add(const ContractCounts& other);
};

class InputContract {
 public:
  static constexpr int kIn = -1;

  // The first clause `in` (one vector, raw values in the model's inputs() order) breaks, as an
  // index into clauses(), or kIn. Vectors arrive in stream order from the model's reset state,
  // so a pipeline whose words depend on the ones before them (kb: a span's event words on its
  // header) keeps that state in the function object: a copy of an InputContract is a checker
  // with its own state, and a fresh copy of the registry's starts from reset.
  using Check = std::function<int(std::span<const std::int64_t> in)>;

  InputContract() = default;  // none: nothing is counted
  InputContract(std::vector<std::string> clauses, Check check)
      : clauses_(std::move(clauses)), check_(std::move(check)) {}

  [[nodiscard]] bool defined() const { return static_cast<bool>(check_); }
  [[nodiscard]] const std::vector<std::string>& clauses() const { return clauses_; }
  [[nodiscard]] int check(std::span<const std::int64_t> in) { return check_(in); }

  // Checks `vectors` (back to back, `width` values each) in order, adding them to `counts`.
  void count(std::span<const std::int64_t> vectors, std::size_t width, ContractCounts& counts);

  // "12 in contract, 3 out of contract (a in [0, 1]: 1; |V| = 1: 2)": clauses nobody broke are
  // left out.
  [[nodiscard]] std::string summary(const ContractCounts& counts) const;

 private:
  std::vector<std::string> clauses_;
  Check check_;
};

}  // namespace phongsim
