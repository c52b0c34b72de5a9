#include "output/csv_table.hpp"

#include <cstdio>
#include <filesystem>

namespace dem {

CsvTable::CsvTable(const std::string& path, const std::vector<std::string>& columns, bool append) {
  std::error_code ec;
  const bool empty = !append || !std::filesystem::exists(path, ec) || std::filesystem::file_size(path, ec) == 0;
  file_ = OutputFile(path, append);
  if (!empty) return;
  std::string header;
  for (const std::string& c : columns) {
    if (!header.empty()) header += ',';
    header += c;  // the names are ours: no commas or quotes to escape
  }
  header += '\n';
  std::fputs(header.c_str(), file_.get());
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

SeriesFiles::SeriesFiles(const std::string& dat_path, const std::vector<std::string>& columns, bool csv, bool append)
    : dat_(dat_path, append) {
  const std::string csv_path = dat_path.substr(0, dat_path.size() - 4) + ".csv";
  if (csv) {
    csv_ = CsvTable(csv_path, columns, append);
  } else if (!append) {
    std::error_code ec;  // an earlier run's twin in the same folder is not this run's
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
