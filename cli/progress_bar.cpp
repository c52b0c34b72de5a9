#include "cli/progress_bar.hpp"

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

namespace dem::cli {

std::function<void(const Progress&)> make_progress_printer(bool terminal) {
  if (terminal) {
    return [](const Progress& p) {
      constexpr int kWidth = 30;
      const double done = p.total > 0 ? static_cast<double>(p.step) / static_cast<double>(p.total) : 1;
      const int filled = static_cast<int>(done * kWidth);
      std::string bar(filled, '#');
      bar.resize(kWidth, '.');
      std::fprintf(stderr, "\r[%s] %5.1f%%  step %lld/%lld  %.0f steps/s  %s left%s%s   ", bar.c_str(), 100 * done,
                   static_cast<long long>(p.step), static_cast<long long>(p.total), p.steps_per_second,
                   clock_text(p.seconds_left).c_str(), p.stage.empty() ? "" : "  stage: ", p.stage.c_str());
      if (p.step >= p.total) std::fputc('\n', stderr);
      std::fflush(stderr);
    };
  }
  // Logs and pipes get a line at most every 10 s, and the last one.
  auto last = std::make_shared<std::chrono::steady_clock::time_point>();
  return [last](const Progress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (p.step < p.total && now - *last < std::chrono::seconds(10)) return;
    *last = now;
    std::fprintf(stderr, "progress: step %lld/%lld (%.1f%%), %.0f steps/s, %s left%s%s\n",
                 static_cast<long long>(p.step), static_cast<long long>(p.total),
                 p.total > 0 ? 100.0 * p.step / p.total : 100.0, p.steps_per_second, clock_text(p.seconds_left).c_str(),
                 p.stage.empty() ? "" : ", stage ", p.stage.c_str());
  };
}

}  // namespace dem::cli
