// The bundled cases (cases/NAME/spec.json and README.md), offered to the viewer so a user can pick
// one, change its main parameters and submit it. Mesh files are inlined: what is sent is a spec the
// server accepts as it is.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace dem::server {

// [{"name", "title", "description"}] of every folder of `root` holding a spec.json, by name.
nlohmann::json list_cases(const std::filesystem::path& root);

// The case's spec as JSON (canonical protobuf JSON mapping, meshes inlined); empty when there is
// no such case. Throws spec::SpecError when the bundled spec itself is broken.
std::optional<std::string> case_spec(const std::filesystem::path& root, const std::string& name);

}  // namespace dem::server
