#include "server/install_paths.hpp"

#include <system_error>

namespace dem::server {
namespace fs = std::filesystem;

fs::path executable_dir() {
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path() : exe.parent_path();
}

namespace {

fs::path first_existing(const fs::path& installed, const fs::path& in_source_tree) {
  std::error_code error;
  if (fs::is_directory(installed, error)) return installed;
  if (fs::is_directory(in_source_tree, error)) return in_source_tree;
  return installed;
}

}  // namespace

fs::path default_web_dir() {
  const fs::path here = executable_dir();
  return first_existing(here / ".." / "share" / "dem" / "web", here / ".." / "web" / "dist").lexically_normal();
}

fs::path default_cases_dir() {
  const fs::path here = executable_dir();
  return first_existing(here / ".." / "share" / "dem" / "cases", here / ".." / "cases").lexically_normal();
}

}  // namespace dem::server
