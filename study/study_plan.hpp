// A parameter study (the mission's scripted job queue): a base job spec and the values of one or more
// of its fields, combined as a grid (every combination) or zipped (the k-th value of each), each
// combination one job. The same plan runs locally (dem study) or on the server (/api/studies).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dem::study {

// Every problem of a study file, each naming its field ("parameters[1].path: ...").
class StudyError : public std::runtime_error {
 public:
  explicit StudyError(std::vector<std::string> problems);
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

struct StudyParameter {
  // as the study gives it ("bonds.tensileStrength", "/packings/0/seed"); a list of fields that take
  // one value together (a bond strength that is both the tensile and the shear one) is named by its
  // fields joined with " = "
  std::string path;
  std::vector<std::string> pointers;  // each field as a JSON pointer (RFC 6901)
  std::vector<nlohmann::json> values;
};

struct StudyRun {
  int index = 0;                       // 1, 2, ...
  std::vector<nlohmann::json> values;  // of each parameter, in the study's order
  nlohmann::json spec;                 // the base with those values, named after the study and the values
};

struct StudyPlan {
  std::string name;
  bool grid = true;
  std::vector<StudyParameter> parameters;
  std::vector<std::string> plot;  // results to plot (dotted keys of results.json); empty: chosen from the results
  std::vector<StudyRun> runs;
};

constexpr int kMaxRuns = 10000;

// Checks a study and makes its runs. `base` is the base spec when the study names it by file
// ("base": "spec.json", read by the caller) and is ignored when the study holds it inline.
StudyPlan plan_study(const nlohmann::json& study, const nlohmann::json& base);

// "bonds.tensileStrength", "packings[0].seed" or "/packings/0/seed" as a JSON pointer; throws
// std::invalid_argument when it is none of these.
std::string to_pointer(const std::string& path);

// "bonds.tensileStrength=4000000.0, bonds.seed=2": a run's values, for names and tables.
std::string describe_values(const std::vector<StudyParameter>& parameters, const std::vector<nlohmann::json>& values);

}  // namespace dem::study
