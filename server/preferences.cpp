#include "server/preferences.hpp"

#include <algorithm>

#include "server/header_list.hpp"

namespace dem::server {

bool prefers_respond_async(const Request& req) {
  const std::vector<HeaderElement> preferences = header_list(req, http::field::prefer);
  return std::any_of(preferences.begin(), preferences.end(),
                     [](const HeaderElement& p) { return p.name == "respond-async"; });
}

void apply_respond_async(const Request& req, http::response<http::string_body>& res) {
  if (prefers_respond_async(req)) res.set(http::field::preference_applied, "respond-async");
}

}  // namespace dem::server
