// The viewer's files (web/), served at / from a folder. Paths never leave the folder.
#pragma once

#include <filesystem>

#include "server/http_util.hpp"

namespace dem::server {

// `set_cookie`: a Set-Cookie header for the response (empty: none).
http::message_generator serve_static(const Request& req, const Target& target, const std::filesystem::path& root,
                                     const std::string& set_cookie = "");

}  // namespace dem::server
