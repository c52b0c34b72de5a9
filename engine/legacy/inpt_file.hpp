// The legacy parameter file INPT.inp of PDEM-EGD and BallastDEM (docs/formats.md section 2): one
// parameter group per line, its values first (separated by commas, spaces or tabs), then a comment
// in parentheses. This splits it into lines; what each line means is the importer's (import/).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace dem::legacy {

struct InptLine {
  int number = 0;                   // 1-based, in the file
  std::vector<std::string> values;  // as written
  std::string comment;              // inside the parentheses, trimmed ("" when there is none)
};

class InptError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The lines of an INPT.inp file. Blank lines at its end are ignored; a blank line inside it, a
// line without values, a comment left open or a control character is refused, naming the line.
std::vector<InptLine> read_inpt(std::string_view text);

// One value of a line, read as the Fortran program would (a real in Fortran form, "1.0E9", "2.5D0";
// an integer; a logical .true./.false./T/F); `what` names the value in the error.
double inpt_real(const InptLine& line, std::size_t index, const std::string& what);
long long inpt_integer(const InptLine& line, std::size_t index, const std::string& what);
bool inpt_logical(const InptLine& line, std::size_t index, const std::string& what);

}  // namespace dem::legacy
