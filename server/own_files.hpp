// What the server treats as a job's own files and folders: a folder that is a folder, not a link to
// one, and a file that is a regular file with no other name (a symbolic link, or a hard link to a
// file elsewhere, planted among a job's outputs was served, archived, and cut and appended to on
// resume). Anything else in a job's folder is left alone: never listed, served, archived or written.
#pragma once

#include <filesystem>

namespace dem::server {

bool is_own_folder(const std::filesystem::path& path);
bool is_own_file(const std::filesystem::path& path);

}  // namespace dem::server
