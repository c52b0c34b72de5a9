// Text from a server (job names, states, error messages) as it may be printed on a terminal: a
// name holding ESC, BEL or CR could retitle the window, clear the screen or forge lines of our
// output. Control characters become visible escapes (\x1b); everything else, UTF-8 included, stays.
#pragma once

#include <string>
#include <string_view>

namespace dem::cli {

std::string printable(std::string_view text);

}  // namespace dem::cli
