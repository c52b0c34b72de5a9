#include "server/job_log.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "server/job.hpp"
#include "sim/clock_text.hpp"

namespace dem::server {

void append_job_log(const std::filesystem::path& log, std::string_view text) noexcept {
  try {
    const std::string time = utc_now();
    std::string lines;
    std::size_t start = 0;
    do {  // every line of the text under the same time
      const std::size_t end = std::min(text.find('\n', start), text.size());
      lines.append(time).append("  ").append(text.substr(start, end - start)).append("\n");
      start = end + 1;
    } while (start < text.size());
    // O_NOFOLLOW and one name only: a link planted in the job's folder is not written through
    const int fd = ::open(log.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) return;
    struct stat about {};
    if (::fstat(fd, &about) == 0 && S_ISREG(about.st_mode) && about.st_nlink == 1) {
      const ssize_t written = ::write(fd, lines.data(), lines.size());
      (void)written;  // a short write on a full disk loses the line's end: nothing better to do
    }
    ::close(fd);
  } catch (...) {  // out of memory for a line: it is lost, the job goes on
  }
}

void ProgressLog::report(const Progress& p) {
  if (p.stage != stage_) {
    if (!p.stage.empty()) append_job_log(log_, "stage \"" + p.stage + "\" (at step " + std::to_string(p.step) + ")");
    stage_ = p.stage;
  }
  const auto now = std::chrono::steady_clock::now();
  if (reported_ && p.step < p.total && now - last_ < std::chrono::seconds(10)) return;
  // the rate over the steps since the last line: the runner's is over its last moment, which a
  // checkpoint just written had stalled ("2 steps/s, 31h52m left" at 4,000 steps/s)
  double rate = p.steps_per_second, left = p.seconds_left;
  const double seconds = std::chrono::duration<double>(now - last_).count();
  if (reported_ && seconds > 0 && p.step > last_step_) {
    rate = static_cast<double>(p.step - last_step_) / seconds;
    left = static_cast<double>(p.total - p.step) / rate;
  }
  last_ = now;
  last_step_ = p.step;
  reported_ = true;
  char line[256];
  std::snprintf(line, sizeof line, "progress: step %lld/%lld (%.1f%%), %.0f steps/s, %s left%s%s",
                static_cast<long long>(p.step), static_cast<long long>(p.total),
                p.total > 0 ? 100.0 * static_cast<double>(p.step) / static_cast<double>(p.total) : 100.0, rate,
                clock_text(left).c_str(), p.stage.empty() ? "" : ", stage ", p.stage.c_str());
  append_job_log(log_, line);
}

std::string last_lines(const std::filesystem::path& path, std::size_t count) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  // back from the end a block at a time, until the blocks hold the line end before the last `count`
  constexpr std::streamoff kBlock = std::streamoff{64} * 1024;
  std::vector<std::string> blocks;  // the last block first
  std::streamoff from = size;
  std::size_t ends = 0;
  while (from > 0 && ends <= count) {
    const std::streamoff length = std::min(kBlock, from);
    from -= length;
    std::string block(static_cast<std::size_t>(length), '\0');
    in.seekg(from);
    if (!in.read(block.data(), length)) throw std::runtime_error("cannot read " + path.string());
    ends += static_cast<std::size_t>(std::count(block.begin(), block.end(), '\n'));
    blocks.push_back(std::move(block));
  }
  std::string tail;  // the bytes from `from` to the end
  for (auto block = blocks.rbegin(); block != blocks.rend(); ++block) tail += *block;
  // whole lines only: what follows the last line end is a line still being written
  const std::size_t last_end = tail.rfind('\n');
  if (last_end == std::string::npos) return "";
  tail.resize(last_end + 1);
  // the start of the count-th line from the end
  std::size_t begin = tail.size() - 1;  // at the last line's end
  for (std::size_t seen = 0; seen < count; ++seen) {
    const std::size_t previous = begin == 0 ? std::string::npos : tail.rfind('\n', begin - 1);
    if (previous == std::string::npos) return tail;  // the file has fewer lines than asked
    begin = previous;
  }
  return tail.substr(begin + 1);
}

}  // namespace dem::server
