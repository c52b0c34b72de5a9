#include "server/durable_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <stdexcept>

namespace dem::server {

bool sync_file(std::FILE* file) { return std::fflush(file) == 0 && ::fsync(fileno(file)) == 0; }

void sync_path(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void sync_folder(const std::filesystem::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void write_file_durably(const std::filesystem::path& path, const std::string& bytes) {
  const std::string temporary = path.string() + ".tmp";
  std::FILE* f = std::fopen(temporary.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + temporary);
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size() && sync_file(f);
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);  // never left behind half written
    throw std::runtime_error("cannot write " + temporary + " (disk full?)");
  }
  std::filesystem::rename(temporary, path);
  sync_folder(path.parent_path());
}

}  // namespace dem::server
