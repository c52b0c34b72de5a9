#include "server/own_files.hpp"

#include <system_error>

namespace dem::server {
namespace fs = std::filesystem;

bool is_own_folder(const fs::path& path) {
  std::error_code ec;
  return fs::symlink_status(path, ec).type() == fs::file_type::directory;
}

bool is_own_file(const fs::path& path) {
  std::error_code ec;
  if (fs::symlink_status(path, ec).type() != fs::file_type::regular) return false;
  const std::uintmax_t names = fs::hard_link_count(path, ec);
  return !ec && names == 1;
}

}  // namespace dem::server
