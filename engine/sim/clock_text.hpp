// A duration as the progress lines of `dem run` and of a server job's log show it.
#pragma once

#include <string>

namespace dem {

// "3m07s" below an hour, "1h05m" from an hour on.
std::string clock_text(double seconds);

}  // namespace dem
