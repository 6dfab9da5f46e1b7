#include "app/json.h"

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

JsonOutput::JsonOutput(const std::string& path) {
  if (!path.empty()) file_.emplace(path);
}

void JsonOutput::write(const nlohmann::ordered_json& document) {
  if (!file_) return;
  std::fputs((document.dump(2) + "\n").c_str(), file_->get());
  file_->commit();
}

}  // namespace phongsim::cli
