#include "model/pipeline.h"

namespace phongsim {

std::size_t PipelineModel::eval_batch(std::span<const std::int64_t> in,
                                      std::vector<std::int64_t>& out,
                                      std::vector<std::uint32_t>* counts) {
  const std::size_t n_in = inputs_.size();
  std::size_t total = 0;
  for (std::size_t at = 0; at + n_in <= in.size(); at += n_in) {
    const std::size_t k = eval(in.subspan(at, n_in), out);
    if (counts != nullptr) counts->push_back(static_cast<std::uint32_t>(k));
    total += k;
  }
  return total;
}

}  // namespace phongsim
