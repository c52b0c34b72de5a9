// VTK's XML file formats, as VTK's and ParaView's own readers read them ("VTK File Formats", VTK
// User's Guide, 11th ed., ch. 19): a dataset's arrays are raw little-endian binary in one appended
// block after the XML header, each preceded by its length in bytes (header_type UInt64), so that a
// frame of a million spheres is written at the disk's speed and read without parsing text.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/vec.hpp"

namespace dem::vtk {

// One DataArray: its values' bytes as they go into the appended block.
struct DataArray {
  std::string name;
  std::string type;  // VTK's name of the value type: Float64, Int64, Int32, UInt8
  int components = 1;
  std::string bytes;
};

DataArray float64(std::string name, const std::vector<double>& values);
DataArray int64(std::string name, const std::vector<std::int64_t>& values);
DataArray int32(std::string name, const std::vector<int>& values);
DataArray uint8(std::string name, const std::vector<std::uint8_t>& values);
DataArray vectors(std::string name, const std::vector<Vec3>& values);  // Float64, 3 components

// A dataset of one piece. `counts` are the Piece element's attributes (NumberOfPoints, and
// NumberOfCells for an UnstructuredGrid or NumberOfVerts, NumberOfLines, ... for PolyData);
// `topology` its cell sections in order (Cells; or Verts, Lines, Polys), each with its arrays.
struct Dataset {
  std::string type;  // UnstructuredGrid or PolyData
  std::vector<std::pair<std::string, std::int64_t>> counts;
  DataArray points;  // Float64 x 3, named Points
  std::vector<DataArray> point_data;
  std::vector<DataArray> cell_data;
  std::vector<std::pair<std::string, std::vector<DataArray>>> topology;
};

// Writes `data` to `path` with the time as its TimeValue field (ParaView's time of a lone file).
// Throws std::runtime_error naming the file and the reason when it cannot be written whole.
void write(const std::string& path, const Dataset& data, double time);

// A series of frames (a .pvd "Collection"): ParaView opens it as one dataset in time.
struct SeriesEntry {
  double time = 0;
  std::string file;  // relative to the .pvd; the writer's own names, nothing XML must escape
};

// A .pvd file that grows a frame at a time: written whole at first (beside it, then renamed over
// it), then each frame is written over the closing tags and followed by them again, so a run of N
// frames writes N entries, not N^2/2. Throws std::runtime_error naming the file when it cannot.
class SeriesFile {
 public:
  SeriesFile(std::string path, const std::vector<SeriesEntry>& entries);
  ~SeriesFile();
  SeriesFile(const SeriesFile&) = delete;
  SeriesFile& operator=(const SeriesFile&) = delete;
  void add(const SeriesEntry& entry);

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

}  // namespace dem::vtk
