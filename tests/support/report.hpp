// Prints a measured value beside its reference, so that a run of the validation suite shows the
// numbers docs/validation.md quotes (the assertions stay in the tests).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace dem::test {

inline void report(const std::string& what, double measured, double reference) {
  const double error = reference != 0 ? 100 * (measured - reference) / std::abs(reference) : 0;
  std::printf("[ measured ] %s: %.6g (reference %.6g, error %+.3f%%)\n", what.c_str(), measured, reference, error);
}

}  // namespace dem::test
