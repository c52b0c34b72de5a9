// The OpenAPI description of the REST API (docs/openapi.json, compiled in).
#pragma once

#include <string>

namespace dem::server {
const std::string& openapi_json();
}
