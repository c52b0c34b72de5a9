// A run's results (engine/output/run_results.hpp) as JSON: results.json in the run's folder, and the
// `results` of a server job's record. Lengths in metres, forces in newtons, energies in joules.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "output/run_results.hpp"

namespace dem::results {

nlohmann::json to_json(const RunResults& r);

// Writes results.json into `folder` (through a temporary file renamed over it: a reader never sees
// half a file). Throws std::runtime_error naming the file when it cannot be written.
void write_results_file(const RunResults& r, const std::string& folder);

constexpr const char* kResultsName = "results.json";

}  // namespace dem::results
