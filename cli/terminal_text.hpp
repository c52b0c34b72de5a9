// Text from a server (job names, states, error messages) as it may be printed on a terminal: a
// name holding ESC, BEL or CR could retitle the window, clear the screen or forge lines of our
// output, and one holding U+202E shows its end first. Control characters and the bidi controls become
// visible escapes (\x1b, \u202e); everything else, UTF-8 included, stays.
#pragma once

#include <string>
#include <string_view>

namespace dem::cli {

std::string printable(std::string_view text);

}  // namespace dem::cli
