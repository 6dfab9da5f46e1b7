// Every built-in configuration as a gtest parameter: tests that run once per configuration in
// configs/ (TEST_P with ::testing::ValuesIn(ConfigItems())).
#pragma once

#include <filesystem>
#include <ostream>
#include <vector>

#include "sim/pipelines/registry.h"

namespace phongsim {

struct Item {
  const PipelineInfo* pipeline;
  std::filesystem::path config;
};

inline void PrintTo(const Item& it, std::ostream* os) { *os << it.config.string(); }

// configs/<pipeline>/*.toml of every registered pipeline, in registry order.
inline std::vector<Item> ConfigItems() {
  std::vector<Item> items;
  for (const PipelineInfo& p : pipelines()) {
    for (const auto& f : pipeline_configs(p)) items.push_back({&p, f});
  }
  return items;
}

}  // namespace phongsim
