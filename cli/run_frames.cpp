#include "cli/run_frames.hpp"

namespace dem::cli {

std::pair<int, int> plane_axes(const std::string& view) {
  if (view == "x") return {1, 2};
  if (view == "y") return {0, 2};
  if (view == "z") return {0, 1};
  throw std::invalid_argument("--view: x, y or z (got \"" + view + "\")");
}

std::string time_text(double t, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "t = %.*f s", decimals, t);
  return buf;
}

std::string folder_name(const std::string& dir) {
  std::string folder = std::filesystem::absolute(std::filesystem::path(dir)).lexically_normal().string();
  while (folder.size() > 1 && folder.back() == '/') folder.pop_back();
  return std::filesystem::path(folder).filename().string();
}

}  // namespace dem::cli
