#include "output/vtk_files.hpp"

#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace dem::vtk {
namespace {

static_assert(std::endian::native == std::endian::little, "the files say LittleEndian and hold the memory's bytes");

template <class T>
DataArray raw(std::string name, std::string type, int components, const T* values, std::size_t count) {
  DataArray a{std::move(name), std::move(type), components, {}};
  a.bytes.assign(reinterpret_cast<const char*>(values), count * sizeof(T));
  return a;
}

// The XML of the arrays and where their bytes go in the appended block, offsets counted from its
// start; the bytes themselves are written from the arrays, not copied into a block first.
class Appended {
 public:
  // `tuples`: given for field data, whose readers do not infer it
  std::string element(const DataArray& a, std::int64_t tuples = -1) {
    std::string xml = "<DataArray type=\"" + a.type + "\" Name=\"" + a.name + "\"";
    if (a.components > 1) xml += " NumberOfComponents=\"" + std::to_string(a.components) + "\"";
    if (tuples >= 0) xml += " NumberOfTuples=\"" + std::to_string(tuples) + "\"";
    xml += " format=\"appended\" offset=\"" + std::to_string(size_) + "\"/>\n";
    arrays_.push_back(&a);
    size_ += sizeof(std::uint64_t) + a.bytes.size();
    return xml;
  }
  const std::vector<const DataArray*>& arrays() const { return arrays_; }

 private:
  std::vector<const DataArray*> arrays_;
  std::size_t size_ = 0;
};

struct CloseFile {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// Writes `head`, each array's length (UInt64) and bytes, and `tail` to `path`, or throws with the
// reason (a full disk).
void write_whole(const std::string& path, const std::string& head, const std::vector<const DataArray*>& arrays,
                 const std::string& tail) {
  std::unique_ptr<std::FILE, CloseFile> f(std::fopen(path.c_str(), "wb"));
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  errno = 0;
  auto put = [&](const void* data, std::size_t size) { return std::fwrite(data, 1, size, f.get()) == size; };
  bool ok = put(head.data(), head.size());
  for (const DataArray* a : arrays) {
    const std::uint64_t length = a->bytes.size();
    ok = ok && put(&length, sizeof length) && put(a->bytes.data(), a->bytes.size());
  }
  ok = ok && put(tail.data(), tail.size()) && std::fflush(f.get()) == 0;
  const int reason = errno;
  std::FILE* raw_file = f.release();
  ok = std::fclose(raw_file) == 0 && ok;
  if (!ok) throw std::runtime_error("cannot write " + path + ": " + std::strerror(reason != 0 ? reason : EIO));
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

}  // namespace

DataArray float64(std::string name, const std::vector<double>& values) {
  return raw(std::move(name), "Float64", 1, values.data(), values.size());
}
DataArray int64(std::string name, const std::vector<std::int64_t>& values) {
  return raw(std::move(name), "Int64", 1, values.data(), values.size());
}
DataArray int32(std::string name, const std::vector<int>& values) {
  static_assert(sizeof(int) == 4);
  return raw(std::move(name), "Int32", 1, values.data(), values.size());
}
DataArray uint8(std::string name, const std::vector<std::uint8_t>& values) {
  return raw(std::move(name), "UInt8", 1, values.data(), values.size());
}
DataArray vectors(std::string name, const std::vector<Vec3>& values) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "a Vec3 is its three doubles, x y z, unpadded");
  return raw(std::move(name), "Float64", 3, reinterpret_cast<const double*>(values.data()), 3 * values.size());
}

void write(const std::string& path, const Dataset& data, double time) {
  Appended appended;
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"" + data.type +
                    "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<" + data.type + ">\n";
  const DataArray time_value = float64("TimeValue", {time});
  xml += "<FieldData>\n" + appended.element(time_value, 1) + "</FieldData>\n<Piece";
  for (const auto& [name, count] : data.counts) xml += " " + name + "=\"" + std::to_string(count) + "\"";
  xml += ">\n<PointData>\n";
  for (const DataArray& a : data.point_data) xml += appended.element(a);
  xml += "</PointData>\n<CellData>\n";
  for (const DataArray& a : data.cell_data) xml += appended.element(a);
  xml += "</CellData>\n<Points>\n" + appended.element(data.points) + "</Points>\n";
  for (const auto& [section, arrays] : data.topology) {
    xml += "<" + section + ">\n";
    for (const DataArray& a : arrays) xml += appended.element(a);
    xml += "</" + section + ">\n";
  }
  xml += "</Piece>\n</" + data.type + ">\n<AppendedData encoding=\"raw\">\n_";
  write_whole(path, xml, appended.arrays(), "\n</AppendedData>\n</VTKFile>\n");
}

namespace {

constexpr const char kSeriesEnd[] = "</Collection>\n</VTKFile>\n";

std::string series_entry(const SeriesEntry& e) {
  return "<DataSet timestep=\"" + number(e.time) + "\" part=\"0\" file=\"" + e.file + "\"/>\n";
}

}  // namespace

SeriesFile::SeriesFile(std::string path, const std::vector<SeriesEntry>& entries) : path_(std::move(path)) {
  std::string xml =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "<Collection>\n";
  for (const SeriesEntry& e : entries) xml += series_entry(e);
  const std::string beside = path_ + ".tmp";
  write_whole(beside, xml, {}, kSeriesEnd);
  std::error_code ec;
  std::filesystem::rename(beside, path_, ec);
  if (ec) throw std::runtime_error("cannot write " + path_ + ": " + ec.message());
  file_ = std::fopen(path_.c_str(), "r+b");
  if (file_ == nullptr) throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno));
}

SeriesFile::~SeriesFile() {
  if (file_ != nullptr) std::fclose(file_);
}

void SeriesFile::add(const SeriesEntry& entry) {
  const std::string text = series_entry(entry) + kSeriesEnd;
  errno = 0;
  const bool ok = std::fseek(file_, -static_cast<long>(sizeof kSeriesEnd - 1), SEEK_END) == 0 &&
                  std::fwrite(text.data(), 1, text.size(), file_) == text.size() && std::fflush(file_) == 0;
  if (!ok) throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno != 0 ? errno : EIO));
}

}  // namespace dem::vtk
