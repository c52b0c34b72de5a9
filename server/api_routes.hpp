// The REST API under /api/ (docs/api.md, server/openapi.json): one function from a request to its
// response. The WebSocket upgrade and the static files are the HTTP session's.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

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

http::message_generator handle_api(const Request& req, const Target& target, ApiContext& ctx);

// A name of a file in a job's outputs: letters, digits, '.', '_', '-', not starting with '.'.
bool is_artifact_name(const std::string& name);

}  // namespace dem::server
