// A client's preferences (RFC 7240, the Prefer header). The server runs every job on its own
// threads after answering, so `respond-async` is always met: its submissions say so with
// Preference-Applied. `wait=N` (how long the client would wait for a synchronous answer) and the
// rest are ignored, as RFC 7240 2 lets a server do.
#pragma once

#include "server/http_util.hpp"

namespace dem::server {

// True when the request's Prefer lines name respond-async (any case, with or without a value or
// parameters, among other preferences).
bool prefers_respond_async(const Request& req);

// Adds Preference-Applied: respond-async to the answer of a request that preferred it.
void apply_respond_async(const Request& req, http::response<http::string_body>& res);

}  // namespace dem::server
