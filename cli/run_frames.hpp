// Reading a run folder's frame files for the figure verbs (dem chains, dem deposits).
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "legacy/legacy_formats.hpp"

namespace dem::cli {

// Every complete frame of `path` read by `reader`; a problem after them is told on stderr, as
// `verb: path: problem`. Throws when the file is not there (saying `need`, what writes it, when
// given), cannot be read, or holds no complete frame.
template <class Frame>
std::vector<Frame> read_frames(const std::filesystem::path& path, legacy::ReadResult<Frame> (*reader)(std::istream&),
                               const char* verb, const std::string& need = "") {
  std::error_code error;
  if (!std::filesystem::exists(path, error))
    throw std::runtime_error(path.string() + ": not there" + (need.empty() ? "" : " (" + need + ")"));
  if (!std::filesystem::is_regular_file(path, error)) throw std::runtime_error(path.string() + ": not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open it");
  legacy::ReadResult<Frame> read = reader(in);
  if (!read.problem.empty()) std::fprintf(stderr, "%s: %s: %s\n", verb, path.string().c_str(), read.problem.c_str());
  if (read.frames.empty()) throw std::runtime_error(path.string() + ": no complete frame in it");
  return std::move(read.frames);
}

// The two axes of the drawing plane for a view along `view` (x, y or z; right-handed: y is seen
// from -y, x to the right and z up). Throws std::invalid_argument naming --view otherwise.
std::pair<int, int> plane_axes(const std::string& view);

// "t = 1.234 s" with `decimals` decimals.
std::string time_text(double t, int decimals = 3);

// The folder's own name, however it is written ("runs/a/", "." ...).
std::string folder_name(const std::string& dir);

}  // namespace dem::cli
