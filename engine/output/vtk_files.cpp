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

// The XML of the arrays and their bytes in the appended block, offsets counted from its start.
class Appended {
 public:
  // `tuples`: given for field data, whose readers do not infer it
  std::string element(const DataArray& a, std::int64_t tuples = -1) {
    std::string xml = "<DataArray type=\"" + a.type + "\" Name=\"" + a.name + "\"";
    if (a.components > 1) xml += " NumberOfComponents=\"" + std::to_string(a.components) + "\"";
    if (tuples >= 0) xml += " NumberOfTuples=\"" + std::to_string(tuples) + "\"";
    xml += " format=\"appended\" offset=\"" + std::to_string(block_.size()) + "\"/>\n";
    const std::uint64_t length = a.bytes.size();
    block_.append(reinterpret_cast<const char*>(&length), sizeof length);
    block_ += a.bytes;
    return xml;
  }
  const std::string& block() const { return block_; }

 private:
  std::string block_;
};

struct CloseFile {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// Writes `head`, `body` and `tail` to `path`, or throws with the reason (a full disk).
void write_whole(const std::string& path, const std::string& head, const std::string& body, const std::string& tail) {
  std::unique_ptr<std::FILE, CloseFile> f(std::fopen(path.c_str(), "wb"));
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  errno = 0;
  bool ok = true;
  for (const std::string* part : {&head, &body, &tail})
    ok = ok && std::fwrite(part->data(), 1, part->size(), f.get()) == part->size();
  ok = ok && std::fflush(f.get()) == 0;
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
  std::vector<double> flat;
  flat.reserve(3 * values.size());
  for (const Vec3& v : values) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
  return raw(std::move(name), "Float64", 3, flat.data(), flat.size());
}

void write(const std::string& path, const Dataset& data, double time) {
  Appended appended;
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"" + data.type +
                    "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<" + data.type + ">\n";
  xml += "<FieldData>\n" + appended.element(float64("TimeValue", {time}), 1) + "</FieldData>\n<Piece";
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
  write_whole(path, xml, appended.block(), "\n</AppendedData>\n</VTKFile>\n");
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
  write_whole(beside, xml, kSeriesEnd, "");
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
