// A file a run writes, which says so when a write did not reach the system (output/legacy_output.hpp
// and the CSV tables write through it).
#pragma once

#include <cstdio>
#include <memory>
#include <string>

namespace dem {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// Opens `path` for writing (appending: a run continued from a saved state adds to its files);
// throws std::runtime_error naming the path and the system's reason.
FilePtr open_for_writing(const std::string& path, bool append = false);

// An output file of a run: flush() (after each frame) throws std::runtime_error naming the file and
// the system's reason when anything written since it was opened did not reach the system (a full
// disk, a quota, an I/O error), so that a run never ends "succeeded" with files cut short. What was
// flushed before stays readable.
class OutputFile {
 public:
  OutputFile() = default;
  OutputFile(const std::string& path, bool append) : file_(open_for_writing(path, append)), path_(path) {}
  std::FILE* get() const { return file_.get(); }
  explicit operator bool() const { return file_ != nullptr; }
  void flush();

 private:
  FilePtr file_;
  std::string path_;
};

}  // namespace dem
