// The CSV twin of a legacy time-series file (Energy.dat, Masscenter.dat, ...): the same rows under a
// header row that names each column with its unit ("time (s)", "x (mm)"), every number in full
// (%.17g: a double read back exactly). Spreadsheets, pandas and ParaView's CSV reader open it as it
// is; the legacy .dat beside it keeps its exact format. docs/formats.md, section 8.
#pragma once

#include <string>
#include <vector>

#include "legacy/legacy_formats.hpp"
#include "output/output_file.hpp"

namespace dem {

class CsvTable {
 public:
  CsvTable() = default;  // writes nothing
  // The header is written when the file starts empty (a new run, or a continued one whose file
  // was not there); a continued run's file must have this header (the same columns and units),
  // else std::runtime_error.
  CsvTable(const std::string& path, const std::vector<std::string>& columns, bool append);
  explicit operator bool() const { return static_cast<bool>(file_); }
  void write(const std::vector<double>& row);
  void flush() { file_.flush(); }

 private:
  OutputFile file_;
};

// A legacy time-series file and its CSV twin (when the spec's outputs.csv is on), written together.
class SeriesFiles {
 public:
  SeriesFiles() = default;  // writes nothing
  // `dat_path` ends in .dat; the CSV is the same name ending in .csv.
  SeriesFiles(const std::string& dat_path, const std::vector<std::string>& columns, bool csv, bool append);
  explicit operator bool() const { return static_cast<bool>(dat_); }
  std::FILE* dat() const { return dat_.get(); }  // for a legacy writer with a row format of its own
  void write(const std::vector<double>& row, legacy::NumberFormat format);
  void write_csv(const std::vector<double>& row);  // after dat() was written by such a writer
  void flush();
  // Removes the twins another run left in `folder` (a new run's writers make their own again).
  static void remove_earlier(const std::string& folder);

 private:
  OutputFile dat_;
  CsvTable csv_;
};

}  // namespace dem
