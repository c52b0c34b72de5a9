// Text from a server (job names, states, error messages) as it may be printed on a terminal: a
// name holding ESC, BEL or CR could retitle the window, clear the screen or forge lines of our
// output, and one holding U+202E shows its end first. Control characters and the bidi controls become
// visible escapes (\x1b, \u202e), and so do bytes that are not well-formed UTF-8 (\x9b, a lone
// 8-bit CSI); everything else, UTF-8 characters included, stays.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace dem::cli {

std::string printable(std::string_view text);

// A spec's problems, each line on its own indented line of stderr, as printable text: a problem
// names the user's own field names and values, which may hold the same controls.
void print_problems(const std::vector<std::string>& problems);

}  // namespace dem::cli
