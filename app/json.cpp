#include "app/json.h"

#include "app/cli.h"

namespace phongsim::cli {

nlohmann::ordered_json json_document(std::string_view command) {
  return {{"schema", kJsonSchema}, {"command", command}};
}

nlohmann::ordered_json contract_json(const std::vector<std::string>& clauses,
                                     const ContractCounts& counts) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < clauses.size(); ++i) {
    a.push_back({{"clause", clauses[i]},
                 {"out_of_contract", i < counts.by_clause.size() ? counts.by_clause[i] : 0}});
  }
  return a;
}

nlohmann::ordered_json rtl_json(const RtlIdentity& rtl) {
  const auto hashed = [](const std::vector<SourceHash>& files) {
    nlohmann::ordered_json a = nlohmann::ordered_json::array();
    for (const SourceHash& f : files)
      a.push_back({{"path", f.path.string()}, {"sha256", f.sha256}});
    return a;
  };
  const auto optional = [](bool known, nlohmann::ordered_json value) {
    return known ? std::move(value) : nlohmann::ordered_json(nullptr);
  };
  const bool verilator = rtl.simulator == "verilator";
  nlohmann::ordered_json dirs = nlohmann::ordered_json::array();
  for (const auto& d : rtl.include_dirs) dirs.push_back(d.string());
  nlohmann::ordered_json params = nlohmann::ordered_json::object();
  for (const RtlParam& p : rtl.params) params[p.name] = p.value;
  return {{"top", rtl.top},
          {"source", rtl.source},
          {"simulator", rtl.simulator},
          {"key", optional(verilator, rtl.sources.key)},
          {"plugin", optional(verilator, rtl.plugin.string())},
          {"files", hashed(rtl.sources.files)},
          {"includes", optional(verilator, hashed(rtl.sources.includes))},
          {"include_dirs", dirs},
          {"defines", rtl.defines},
          {"parameters", params},
          {"flags", optional(verilator, rtl.sources.flags)}};
}

JsonOutput::JsonOutput(const std::string& path) {
  if (!path.empty()) file_.emplace(path);
}

void JsonOutput::write(const nlohmann::ordered_json& document) {
  if (!file_) return;
  std::fputs((document.dump(2) + "\n").c_str(), file_->get());
  file_->commit();
}

}  // namespace phongsim::cli
