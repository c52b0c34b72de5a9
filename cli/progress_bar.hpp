// Progress of a run on the terminal: a redrawn bar on a TTY, a plain line every few seconds otherwise.
#pragma once

#include <functional>
#include <string>

#include "sim/runner.hpp"

namespace dem::cli {

std::function<void(const Progress&)> make_progress_printer(bool terminal);

// A duration as "3m07s" or "1h05m".
std::string clock_text(double seconds);

}  // namespace dem::cli
