#pragma once

namespace dem::server {
inline constexpr const char* kVersion = "0.1.0";
}
