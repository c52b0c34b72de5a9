// The lines of one program's INPT.inp, read in order, each given the fate it met in the spec.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "import/inpt_import.hpp"
#include "legacy/inpt_file.hpp"

namespace dem::import {

class LineFates {
 public:
  // The manual's name of a line and how many values it holds.
  struct Expected {
    std::string name;
    std::size_t values;
  };
  // The file must have exactly these lines, each with its number of values.
  LineFates(const std::vector<legacy::InptLine>& lines, const std::vector<Expected>& expected,
            const std::string& program);

  const legacy::InptLine& line(int number) const { return lines_[number - 1]; }
  const std::string& name(int number) const { return names_[number - 1]; }
  double real(int number, std::size_t index = 0) const;
  long long integer(int number, std::size_t index = 0) const;
  bool logical(int number, std::size_t index = 0) const;
  std::string word(int number, std::size_t index = 0) const;  // upper case

  // Refuses the value (InptError naming the line and the manual's name).
  [[noreturn]] void refuse(int number, const std::string& what) const;

  void became(int number, const std::string& fate) { fates_[number - 1] = fate; }
  void dropped(int number, const std::string& why) { fates_[number - 1] = "dropped: " + why; }

  // Spec field `path` (and what lies under it) comes from line `number`: a problem the spec loader
  // finds there is traced back to the line (locate()).
  void feeds(int number, const std::string& path) { fields_.emplace_back(path, number); }

  // Every line with its fate (a line without one is a bug of the importer: std::logic_error).
  std::vector<LineFate> fates() const;
  std::vector<std::pair<std::string, int>> fields() const { return fields_; }

 private:
  const std::vector<legacy::InptLine>& lines_;
  std::vector<std::string> names_;
  std::vector<std::string> fates_;
  std::vector<std::pair<std::string, int>> fields_;
};

// A number as a spec or a note shows it: the shortest text that reads back the same.
std::string show(double v);

}  // namespace dem::import
