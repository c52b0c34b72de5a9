// The value of a header that is a list of elements with parameters (RFC 9110 5.6.1, 5.6.6), as
// Accept-Encoding ("gzip;q=0.8, identity") and Prefer (RFC 7240: "respond-async, wait=10") are:
// split on commas outside quoted strings, whitespace around the parts dropped, names in lower case.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <boost/beast/http.hpp>

#include "server/http_util.hpp"

namespace dem::server {

struct HeaderElement {
  std::string name;                                         // lower case ("gzip", "respond-async", "wait")
  std::string value;                                        // after '=' (unquoted), empty when none
  std::vector<std::pair<std::string, std::string>> params;  // after ';': name (lower case), value (unquoted)

  // The value of the parameter `name` (lower case), if given.
  std::optional<std::string> param(std::string_view name) const;
};

// The elements of a list; empty elements (",,") are skipped, and so is an element that is not a
// token (a stray quote, a '=' without a name): a malformed part of a hint is ignored, never an error.
std::vector<HeaderElement> parse_header_list(std::string_view value);

// Every line of `field` in the request as one list (RFC 9110 5.3: lines of a list header are one).
std::vector<HeaderElement> header_list(const Request& req, http::field field);

}  // namespace dem::server
