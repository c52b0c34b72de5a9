// Where dem-server finds the viewer's files and the bundled cases when not told: next to itself,
// so that an installed server (cmake --install) and one in a build folder of the source tree both
// work with no path compiled in.
#pragma once

#include <filesystem>

namespace dem::server {

// The folder of the running executable (/proc/self/exe), or "" when it cannot be read.
std::filesystem::path executable_dir();

// The first of <exe>/../share/dem/web (installed) and <exe>/../web/dist (a build folder in the
// source tree) that exists; the installed one when neither does (its absence is then told).
std::filesystem::path default_web_dir();

// The same for the cases: <exe>/../share/dem/cases, then <exe>/../cases.
std::filesystem::path default_cases_dir();

}  // namespace dem::server
