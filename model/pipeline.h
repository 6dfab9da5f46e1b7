// The golden-model side of a pipeline, as the co-simulation framework sees it: named fields
// with fixed-point formats, and a function from one input transaction to the output
// transactions it produces (one for LIRP; several for a triangle walker).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "model/fixed.h"

namespace phongsim {

// One field of a transaction. Its raw value travels as int64_t; on the RTL side it is `fmt`'s
// width of bits in the port the pipeline's adapter binds it to.
struct Field {
  std::string name;
  fx::Format fmt;
};

// One stage's value for one input, named as in the RTL and the pipeline's spec.
struct StageValue {
  std::string name;
  fx::Fixed value;
};

class PipelineModel {
 public:
  virtual ~PipelineModel() = default;

  [[nodiscard]] const std::vector<Field>& inputs() const { return inputs_; }
  [[nodiscard]] const std::vector<Field>& outputs() const { return outputs_; }

  // Evaluates one input transaction (raw values in inputs() order) and appends the raw values of
  // every output transaction it produces to `out`, in outputs() order. Returns how many outputs.
  virtual std::size_t eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) = 0;

  // The same for in.size() / inputs().size() transactions back to back: appends every output to
  // `out` exactly as that many eval() calls would and returns how many. `counts`, when given,
  // receives each transaction's number of outputs. Models with a compiled plan evaluate whole
  // blocks at once (structure of arrays inside); the default calls eval() per transaction.
  virtual std::size_t eval_batch(std::span<const std::int64_t> in, std::vector<std::int64_t>& out,
                                 std::vector<std::uint32_t>* counts = nullptr);

  // Back to the state after construction (for pipelines that keep state between transactions).
  virtual void reset() {}

  // An independent copy, state included (parallel co-simulation gives each worker its own).
  [[nodiscard]] virtual std::unique_ptr<PipelineModel> clone() const = 0;

 protected:
  std::vector<Field> inputs_;
  std::vector<Field> outputs_;
};

}  // namespace phongsim
