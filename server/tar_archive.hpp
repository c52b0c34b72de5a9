// Writes the files of a folder into one POSIX ustar archive (what `tar xf` reads).
#pragma once

#include <string>

namespace dem::server {

// Every regular file directly in `folder`, by name, into `archive` (written beside it and renamed,
// so a crash never leaves half an archive under the final name). Throws std::runtime_error.
void write_tar(const std::string& folder, const std::string& archive);

}  // namespace dem::server
