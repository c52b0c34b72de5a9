// Progress of a run on the terminal: a redrawn bar on a TTY, a plain line every few seconds otherwise.
#pragma once

#include <functional>
#include <string>

#include "sim/clock_text.hpp"
#include "sim/runner.hpp"

namespace dem::cli {

std::function<void(const Progress&)> make_progress_printer(bool terminal);

}  // namespace dem::cli
