// The REST API under /api/ (docs/api.md, server/openapi.json): one function from a request to its
// response. The WebSocket upgrade and the static files are the HTTP session's.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <boost/beast/http.hpp>

#include "server/http_util.hpp"
#include "server/job_manager.hpp"
#include "server/study_manager.hpp"

namespace dem::server {

struct ApiContext {
  JobManager& jobs;
  StudyManager& studies;
  const std::string& openapi;          // the OpenAPI description served at /api/openapi.json
  const std::filesystem::path& cases;  // the bundled cases
};

// `target` with /api/v1/ read as /api/ (the versioned path; /api/ is its alias, kept for the viewer).
void drop_api_version(Target& target);

// The request under /api/ (its version dropped).
http::message_generator handle_api(const Request& req, const Target& target, ApiContext& ctx);

// The methods the API resource at these segments ("api", ...; the version dropped) answers, as in
// its Allow header; nullptr when there is no resource there. The OpenAPI description's test walks it.
const char* allowed_methods(const std::vector<std::string>& segments);

// A name of a file in a job's outputs: letters, digits, '.', '_', '-', not starting with '.'.
bool is_artifact_name(const std::string& name);

}  // namespace dem::server
