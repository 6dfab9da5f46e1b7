#include "app/json.h"

namespace phongsim::cli {

nlohmann::ordered_json json_document(std::string_view command) {
  return {{"schema", kJsonSchema}, {"command", command}};
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
