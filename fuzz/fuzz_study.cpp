// libFuzzer target: a parameter study as a client sends it (POST /api/studies, dem study): the
// plan from its JSON (paths into the base, grid or zip, every problem named), then its table (JSON,
// CSV) and figure (SVG) with the base standing in for every run's results, so that any JSON goes
// through the flattening and the chart.
#include <cstddef>
#include <cstdint>
#include <string>

#include "study/study_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 1 << 16) return 0;
  const nlohmann::json study =
      nlohmann::json::parse(std::string(reinterpret_cast<const char*>(data), size), nullptr, false);
  if (study.is_discarded()) return 0;
  try {
    const dem::study::StudyPlan plan = dem::study::plan_study(study, nlohmann::json());
    if (plan.runs.size() > 200) return 0;  // each run's spec is the base again: large grids only cost time
    std::vector<dem::study::StudyRow> rows;
    for (const dem::study::StudyRun& run : plan.runs) {
      rows.push_back(dem::study::row_of(run));
      rows.back().results = run.spec;
      rows.back().state = "succeeded";
    }
    (void)dem::study::table_json(plan, rows).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    (void)dem::study::table_csv(plan, rows);
    (void)dem::study::figure_svg(plan, rows);
  } catch (const dem::study::StudyError&) {
  }
  return 0;
}
