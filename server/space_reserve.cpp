#include "server/space_reserve.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <system_error>

namespace dem::server {
namespace fs = std::filesystem;

SpaceReserve::SpaceReserve(fs::path path, std::uint64_t bytes) : path_(std::move(path)), bytes_(bytes) {
  std::error_code ec;
  held_ = fs::is_regular_file(path_, ec) && fs::file_size(path_, ec) >= bytes_;
  if (!held_) restore();
}

bool SpaceReserve::release() {
  if (!held_) return false;
  std::error_code ec;
  fs::remove(path_, ec);
  held_ = false;
  return true;
}

bool SpaceReserve::restore() {
  if (held_) return true;
  std::error_code ec;
  const fs::space_info space = fs::space(path_.parent_path(), ec);
  if (ec || space.available < 4 * bytes_) return false;  // not while the disk is still nearly full
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return false;
  // allocated blocks, not a sparse file: the space must really be there to give back
  const bool ok = ::posix_fallocate(fd, 0, static_cast<off_t>(bytes_)) == 0 && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) fs::remove(path_, ec);
  held_ = ok;
  return held_;
}

}  // namespace dem::server
