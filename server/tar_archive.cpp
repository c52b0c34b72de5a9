#include "server/tar_archive.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "server/own_files.hpp"

#include "output/legacy_output.hpp"
#include "server/durable_file.hpp"

namespace dem::server {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kBlock = 512;

// Octal, zero-padded to width-1 digits and a NUL (the ustar numeric fields).
void put_octal(char* field, std::size_t width, std::uintmax_t value) {
  std::snprintf(field, width, "%0*jo", static_cast<int>(width - 1), value);
}

std::array<char, kBlock> header(const std::string& name, std::uintmax_t size, std::time_t mtime) {
  std::array<char, kBlock> h{};
  std::memcpy(h.data(), name.data(), std::min<std::size_t>(name.size(), 100));
  put_octal(&h[100], 8, 0644);  // mode
  put_octal(&h[108], 8, 0);     // uid
  put_octal(&h[116], 8, 0);     // gid
  put_octal(&h[124], 12, size);
  put_octal(&h[136], 12, static_cast<std::uintmax_t>(mtime));
  h[156] = '0';  // a regular file
  std::memcpy(&h[257], "ustar", 6);
  std::memcpy(&h[263], "00", 2);
  // the checksum is taken with its own field counted as spaces
  std::memset(&h[148], ' ', 8);
  unsigned sum = 0;
  for (char c : h) sum += static_cast<unsigned char>(c);
  std::snprintf(&h[148], 8, "%06o", sum);  // six digits, NUL, and the space left from above
  h[155] = ' ';
  return h;
}

// The archive of every regular file of `folder` (links are not followed: a link planted there would
// put any file of the machine in the archive), written to `temporary` and synced.
void write_tar_through(const std::string& folder, const std::string& temporary) {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder))
    if (is_own_file(e.path())) files.push_back(e.path());
  std::sort(files.begin(), files.end());

  FilePtr out_file = open_for_writing(temporary);
  std::FILE* out = out_file.get();
  std::vector<char> buffer(1 << 20);
  bool ok = true;
  for (const fs::path& file : files) {
    const std::string name = file.filename().string();
    if (name.size() > 100) throw std::runtime_error("file name too long for tar: " + name);
    const std::uintmax_t size = fs::file_size(file);
    if (size >= (std::uintmax_t{1} << 33)) throw std::runtime_error(name + " is 8 GiB or more, too large for ustar");
    const auto mtime = std::time(nullptr);
    const std::array<char, kBlock> h = header(name, size, mtime);
    ok = ok && std::fwrite(h.data(), 1, kBlock, out) == kBlock;
    const FilePtr in_file(std::fopen(file.c_str(), "rb"));
    if (!in_file) throw std::runtime_error("cannot read " + file.string());
    std::FILE* in = in_file.get();
    std::uintmax_t copied = 0;
    for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), in)) > 0 && copied < size;) {
      n = static_cast<std::size_t>(std::min<std::uintmax_t>(n, size - copied));  // as listed, even if it grew
      ok = ok && std::fwrite(buffer.data(), 1, n, out) == n;
      copied += n;
    }
    if (copied != size) throw std::runtime_error(file.string() + " shrank while it was archived");
    const std::size_t pad = (kBlock - size % kBlock) % kBlock;
    const std::vector<char> zeros(kBlock, 0);
    ok = ok && std::fwrite(zeros.data(), 1, pad, out) == pad;
  }
  const std::vector<char> end(2 * kBlock, 0);  // two zero blocks end the archive
  ok = ok && std::fwrite(end.data(), 1, end.size(), out) == end.size();
  ok = ok && sync_file(out);
  ok = std::fclose(out_file.release()) == 0 && ok;
  if (!ok) throw std::runtime_error("cannot write " + temporary + " (disk full?)");
}

}  // namespace

void write_tar(const std::string& folder, const std::string& archive) {
  const std::string temporary = archive + ".tmp";
  try {
    write_tar_through(folder, temporary);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);  // a half archive (a full disk) is not left in the job's folder
    throw;
  }
  fs::rename(temporary, archive);
  sync_folder(fs::path(archive).parent_path());
}

}  // namespace dem::server
