// The folder a verb writes into (--out DIR), made with its parents. A path that is, or lies under,
// a file is refused naming the option and that file, not in the filesystem library's words
// ("cannot create directories: Not a directory [DIR]"); the file is left as it was.
#pragma once

#include <filesystem>
#include <string>

namespace dem::cli {

// Throws std::runtime_error "OPTION PATH: REASON" when the folder cannot be made.
void make_output_folder(const std::filesystem::path& folder, const std::string& option = "--out");

}  // namespace dem::cli
