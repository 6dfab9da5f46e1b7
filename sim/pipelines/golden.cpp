#include "sim/pipelines/golden.h"

#include <fmt/format.h>

#include "base/error.h"

namespace phongsim {

GoldenModel::GoldenModel(Config cfg) : cfg_(std::move(cfg)) {
  pipeline_ = &find_pipeline(cfg_.pipeline());
  model_ = make_model(*pipeline_, cfg_);
}

GoldenModel::GoldenModel(const std::filesystem::path& config) : GoldenModel(Config::load(config)) {}

GoldenModel GoldenModel::from_toml(std::string_view text, const std::string& origin) {
  return GoldenModel(Config::parse(text, origin));
}

std::vector<std::int64_t> GoldenModel::eval(std::span<const std::int64_t> in) {
  if (in.size() != inputs().size()) {
    throw Error(fmt::format("{}: an input vector has {} values, not {}", cfg_.origin(), in.size(),
                            inputs().size()));
  }
  std::vector<std::int64_t> out;
  (void)model_->eval(in, out);
  return out;
}

std::vector<std::int64_t> GoldenModel::eval_batch(std::span<const std::int64_t> rows) {
  const std::size_t n = inputs().size();
  if (rows.size() % n != 0) {
    throw Error(
        fmt::format("{}: {} values are not whole vectors of {}", cfg_.origin(), rows.size(), n));
  }
  std::vector<std::int64_t> out;
  for (std::size_t i = 0; i < rows.size(); i += n) (void)model_->eval(rows.subspan(i, n), out);
  return out;
}

std::vector<StageValue> GoldenModel::stages(std::span<const std::int64_t> in) {
  if (in.size() != inputs().size()) {
    throw Error(fmt::format("{}: an input vector has {} values, not {}", cfg_.origin(), in.size(),
                            inputs().size()));
  }
  return pipeline_->stages(*model_, in);
}

Stimulus GoldenModel::stimulus() const { return pipeline_->make_stimulus(*model_, cfg_); }

RtlDesign GoldenModel::rtl_design(std::vector<std::filesystem::path> files, std::string top) const {
  return phongsim::rtl_design(*pipeline_, cfg_, std::move(files), std::move(top));
}

DutFactory GoldenModel::rtl(const RtlDesign& design, RtlBuild policy, std::FILE* log,
                            std::string* label) {
  RtlPlugin plugin;
  DutFactory f = rtl_duts(design, *model_, policy, log, &plugin);
  if (label != nullptr) *label = fmt::format("{} ({})", design.top, plugin.key);
  return f;
}

}  // namespace phongsim
