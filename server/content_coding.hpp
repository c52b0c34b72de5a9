// Which content coding an answer gets (RFC 9110 12.5.3, Accept-Encoding): gzip when the client
// accepts it, else none (identity).
#pragma once

#include <vector>

#include "server/header_list.hpp"

namespace dem::server {

// True when the Accept-Encoding elements accept gzip ("gzip" or its alias "x-gzip", else "*") with a
// q above 0 and not below identity's, when identity is named. No header, an empty one, "identity",
// "gzip;q=0" or a q that cannot be read: false (identity is what every client reads).
bool accepts_gzip(const std::vector<HeaderElement>& accept_encoding);

}  // namespace dem::server
