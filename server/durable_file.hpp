// Files that survive a crash of the machine, not only of the process: written beside their final
// name, synced, renamed over it, and the folder synced so that the rename itself is kept.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace dem::server {

// Writes `bytes` to `path` that way; throws std::runtime_error naming the file.
void write_file_durably(const std::filesystem::path& path, const std::string& bytes);

// Flushes and syncs an open file; false when the disk refused (full, failing).
bool sync_file(std::FILE* file);
// Syncs a file by name (output files written by others), and a folder's entries.
void sync_path(const std::filesystem::path& path);
void sync_folder(const std::filesystem::path& folder);

}  // namespace dem::server
