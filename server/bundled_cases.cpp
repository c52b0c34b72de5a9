#include "server/bundled_cases.hpp"

#include <fstream>

#include <google/protobuf/util/json_util.h>

#include "server/api_routes.hpp"
#include "spec/referenced_files.hpp"
#include "spec/spec_loader.hpp"

namespace dem::server {
namespace fs = std::filesystem;
namespace {

// The README's first paragraph after its title: what the case is.
std::string description_of(const fs::path& readme) {
  std::ifstream in(readme);
  std::string line, text;
  bool title_seen = false;
  while (std::getline(in, line)) {
    if (!title_seen) {
      title_seen = line.rfind("# ", 0) == 0;
      continue;
    }
    if (line.empty()) {
      if (!text.empty()) break;
      continue;
    }
    text += (text.empty() ? "" : " ") + line;
  }
  return text;
}

}  // namespace

nlohmann::json list_cases(const fs::path& root) {
  nlohmann::json cases = nlohmann::json::array();
  std::error_code ec;
  std::vector<fs::path> folders;
  for (const fs::directory_entry& e : fs::directory_iterator(root, ec))
    if (e.is_directory() && fs::exists(e.path() / "spec.json") && is_artifact_name(e.path().filename().string()))
      folders.push_back(e.path());
  std::sort(folders.begin(), folders.end());
  for (const fs::path& folder : folders) {
    std::string title = folder.filename().string();
    try {
      const api::JobSpec spec = spec::read_json_file((folder / "spec.json").string());
      if (!spec.name().empty()) title = spec.name();
    } catch (const std::exception&) {
      continue;  // a broken bundled case is not offered
    }
    cases.push_back({{"name", folder.filename().string()},
                     {"title", title},
                     {"description", description_of(folder / "README.md")}});
  }
  return cases;
}

std::optional<std::string> case_spec(const fs::path& root, const std::string& name) {
  if (!is_artifact_name(name)) return std::nullopt;  // a plain folder name, never a path
  const fs::path folder = root / name;
  if (!fs::exists(folder / "spec.json")) return std::nullopt;
  api::JobSpec spec = spec::read_json_file((folder / "spec.json").string());
  spec::inline_files(spec, folder.string());
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  const auto status = google::protobuf::util::MessageToJsonString(spec, &json, options);
  if (!status.ok()) throw std::runtime_error("case " + name + ": " + status.ToString());
  return json;
}

}  // namespace dem::server
