// A study's results table (one row per run: its parameter values, its job's state, its results
// summary) as JSON and CSV, and its comparison figure (SVG): each plotted result against the first
// parameter, every run a point and the mean of the runs at each value a line (seeds scatter
// about it).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/study_plan.hpp"

namespace dem::study {

struct StudyRow {
  int index = 0;
  std::vector<nlohmann::json> values;  // of each parameter
  std::string state;                   // the job's: succeeded, failed, queued, running, ...; "not run"
  std::int64_t job = -1;               // the server's job id; -1 locally
  std::string error;
  nlohmann::json results;  // results.json; null until the run ended
};

// A run's row before it has a job or results.
StudyRow row_of(const StudyRun& run);

// The scalar results as dotted names ("motion.runout.length", "loadedWalls.0.permanentSettlement"),
// in the order results.json has them; lists of objects other than loadedWalls (the cycles, the
// fragment sizes) stay in the JSON table.
std::vector<std::pair<std::string, nlohmann::json>> flatten(const nlohmann::json& results);

// A row's result by its dotted name (as flatten names it), or none; and the same when it is a number.
std::optional<nlohmann::json> result_at(const StudyRow& row, const std::string& key);
std::optional<double> number_at(const StudyRow& row, const std::string& key);

// "run 3 (bonds.tensileStrength=1000000.0)": a run as messages and lines name it.
std::string run_label(const StudyPlan& plan, int index, const std::vector<nlohmann::json>& values);

// The results the figure shows: the study's `plot`, else those of a set list the runs have
// (runout, deposit area, fragments, crushed mass, settlement, resilient displacement), else run time.
std::vector<std::string> plot_keys(const StudyPlan& plan, const std::vector<StudyRow>& rows);

nlohmann::json table_json(const StudyPlan& plan, const std::vector<StudyRow>& rows);
std::string table_csv(const StudyPlan& plan, const std::vector<StudyRow>& rows);
std::string figure_svg(const StudyPlan& plan, const std::vector<StudyRow>& rows);

}  // namespace dem::study
