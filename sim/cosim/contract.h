// Input contracts: the input domain on which a pipeline's accuracy claims hold (each spec doc's
// "Input contract" section), as named clauses and a check of one vector against them (run over
// a batch of vectors per call). The registry gives each configuration its contract
// (PipelineInfo::contract); co-simulation and eval count the vectors inside and outside it.
// Bit-exactness is checked on every vector either way: a vector out of contract is one on which
// the model and the RTL still agree, but the pipeline's accuracy figures do not apply.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "model/plan.h"

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

  // Checks vectors (back to back, `width` values each, as many as `clauses` has room for) in
  // stream order from the model's reset state, writing for each the first clause it breaks, as
  // an index into clauses(), or kIn. A pipeline whose words depend on the ones before them (kb:
  // a span's event words on its header) keeps that state in the function object: a copy of an
  // InputContract is a checker with its own state, and a fresh copy of the registry's starts
  // from reset. One call per batch: a co-simulation checks every vector, and a call per vector
  // through std::function cost about as much as LIRP's clauses themselves.
  using Check = std::function<void(std::span<const std::int64_t> vectors, std::size_t width,
                                   std::span<std::int16_t> clauses)>;

  InputContract() = default;  // none: nothing is counted
  // From a check of one vector (returning a clause index or kIn), run over a batch in one loop.
  template <class CheckOne>
  requires std::is_invocable_r_v<int, CheckOne&, std::span<const std::int64_t>> InputContract(
      std::vector<std::string> clauses, CheckOne check)
      : clauses_(std::move(clauses)),
        check_([one = std::move(check)](std::span<const std::int64_t> vectors, std::size_t width,
                                        std::span<std::int16_t> out) mutable {
          for (std::size_t i = 0; i < out.size(); ++i) {
            out[i] = static_cast<std::int16_t>(one(vectors.subspan(i * width, width)));
          }
        }) {}

  // From a check of a batch (a pipeline whose one-vector check does not vectorize as it stands:
  // LIRP's, which transposes its block of vectors first).
  InputContract(std::vector<std::string> clauses, Check batch)
      : clauses_(std::move(clauses)), check_(std::move(batch)) {}

  [[nodiscard]] bool defined() const { return static_cast<bool>(check_); }
  [[nodiscard]] const std::vector<std::string>& clauses() const { return clauses_; }
  // One vector: the first clause it breaks, or kIn.
  [[nodiscard]] int check(std::span<const std::int64_t> in) {
    std::int16_t c = 0;
    check_(in, in.size(), std::span(&c, 1));
    return c;
  }
  // clauses.size() vectors of `width` values from `vectors`, in order.
  void check(std::span<const std::int64_t> vectors, std::size_t width,
             std::span<std::int16_t> clauses) {
    check_(vectors, width, clauses);
  }

  // Checks `vectors` (back to back, `width` values each) in order, adding them to `counts`.
  void count(std::span<const std::int64_t> vectors, std::size_t width, ContractCounts& counts);

  // "12 in contract, 3 out of contract (a in [0, 1]: 1; |V| = 1: 2)": clauses nobody broke are
  // left out.
  [[nodiscard]] std::string summary(const ContractCounts& counts) const;

 private:
  std::vector<std::string> clauses_;
  Check check_;
};

// A batch check's vectors a block at a time, field by field (structure of arrays, so that the
// clauses' loop over a block's vectors vectorizes): body(v, m, clauses) with v[c][k] field c of
// the block's vector k as T, m <= kFieldBlock vectors and their m clauses. Call it inside
// fx::on_kernel_isa, whose flatten inlines it for the kernel's instruction set.
inline constexpr std::size_t kFieldBlock = fx::kBlock;
template <class T, std::size_t kFields, class Body>
void for_each_field_block(std::span<const std::int64_t> vectors, std::span<std::int16_t> clauses,
                          Body&& body) {
  alignas(64) std::int64_t raw[kFields][kFieldBlock];
  for (std::size_t b = 0; b < clauses.size(); b += kFieldBlock) {
    const std::size_t m = std::min(kFieldBlock, clauses.size() - b);
    fx::to_fields(vectors.data() + b * kFields, kFields, m, raw);
    if constexpr (std::is_same_v<T, std::int64_t>) {
      body(raw, m, clauses.data() + b);
    } else {
      alignas(64) T converted[kFields][kFieldBlock];
      for (std::size_t c = 0; c < kFields; ++c) {
        for (std::size_t k = 0; k < m; ++k) converted[c][k] = static_cast<T>(raw[c][k]);
      }
      body(converted, m, clauses.data() + b);
    }
  }
}

}  // namespace phongsim
