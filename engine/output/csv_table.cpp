#include "output/csv_table.hpp"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dem {
namespace {

bool has_bytes(const std::string& path) {
  std::error_code ec;
  return std::filesystem::exists(path, ec) && std::filesystem::file_size(path, ec) > 0;
}

}  // namespace

CsvTable::CsvTable(const std::string& path, const std::vector<std::string>& columns, bool append) {
  std::string header;
  for (const std::string& c : columns) {
    if (!header.empty()) header += ',';
    header += c;  // the names are ours: no commas or quotes to escape
  }
  if (append && has_bytes(path)) {
    // a continued run writes under the header it finds: the same columns in the same units
    std::ifstream in(path);
    std::string found;
    std::getline(in, found);
    if (found != header)
      throw std::runtime_error("cannot continue " + path + ": its columns are \"" + found + "\", this run's \"" +
                               header + "\" (continue with the saved run's outputs.lengthUnit)");
    file_ = OutputFile(path, true);
    return;
  }
  file_ = OutputFile(path, append);
  header += '\n';
  std::fputs(header.c_str(), file_.get());
}

// The time series' names (every SeriesFiles of engine/output): a test checks a run writes no
// other twin.
constexpr std::array<const char*, 11> kSeriesNames = {
    "Energy",         "Masscenter",  "Disp_Max",           "Coord_OL",        "Force_Displacement", "Fragments",
    "Fragment_Sizes", "Bond_Breaks", "Wall_Mean_Force_CN", "Wall_PDF_CoordN", "Wall_PDF_ForceChain"};

void SeriesFiles::remove_earlier(const std::string& folder) {
  for (const char* name : kSeriesNames) {
    std::error_code ec;
    std::filesystem::remove(std::filesystem::path(folder) / (std::string(name) + ".csv"), ec);
  }
}

void CsvTable::write(const std::vector<double>& row) {
  if (!file_) return;
  char number[40];
  std::string line;
  for (double v : row) {
    if (!line.empty()) line += ',';
    std::snprintf(number, sizeof number, "%.17g", v);
    line += number;
  }
  line += '\n';
  std::fputs(line.c_str(), file_.get());
}

SeriesFiles::SeriesFiles(const std::string& dat_path, const std::vector<std::string>& columns, bool csv, bool append) {
  const std::string csv_path = dat_path.substr(0, dat_path.size() - 4) + ".csv";
  // A continued run whose twin was not written (begun with outputs.csv false, or by a version
  // before the twins) would give it only the rows from here: it gets the .dat's rows first, at
  // the .dat's precision.
  const bool catch_up = csv && append && has_bytes(dat_path) && !has_bytes(csv_path);
  dat_ = OutputFile(dat_path, append);
  if (csv) {
    csv_ = CsvTable(csv_path, columns, append);
    if (catch_up) {
      std::ifstream earlier(dat_path);
      for (std::string line; std::getline(earlier, line);) {
        std::istringstream numbers(line);
        std::vector<double> row;
        for (double v; numbers >> v;) row.push_back(v);
        if (!row.empty()) csv_.write(row);
      }
    }
  } else {
    std::error_code ec;  // a twin it does not go on with would hold part of the rows
    std::filesystem::remove(csv_path, ec);
  }
}

void SeriesFiles::write(const std::vector<double>& row, legacy::NumberFormat format) {
  legacy::write_row(dat_.get(), row, format);
  csv_.write(row);
}

void SeriesFiles::write_csv(const std::vector<double>& row) { csv_.write(row); }

void SeriesFiles::flush() {
  dat_.flush();
  csv_.flush();
}

}  // namespace dem
