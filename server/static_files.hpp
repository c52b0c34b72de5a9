// The viewer's files (web/), served at / from a folder. Paths never leave the folder.
#pragma once

#include <filesystem>

#include "server/http_util.hpp"

namespace dem::server {

http::message_generator serve_static(const Request& req, const Target& target, const std::filesystem::path& root);

}  // namespace dem::server
