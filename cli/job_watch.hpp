// A job of dem-server as the client verbs show it: a one-line summary, and following it to its end.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

#include "cli/server_api.hpp"

namespace dem::cli {

// `job` when it has dem-server's job form (a whole-number id and a state); else throws
// std::runtime_error saying so (an answer of another server, or a proxy's).
const nlohmann::json& checked_job(const nlohmann::json& job);

// "job 12 "demo": running 42.0% (step 32000/77988, 1203 steps/s, 0m38s left)", from the job JSON.
std::string job_summary(const nlohmann::json& job);

// What following a job shows: its progress on stderr and a summary line at the end (lines), nothing
// but the error (quiet), or its progress and then the job's JSON at its end on stdout (json).
enum class WatchOutput { lines, quiet, json };

// Polls the job about twice a second until it has ended. Returns the exit status: 0 when it
// succeeded (its summary then goes to stdout unless quiet), 1 when it failed, was cancelled or
// interrupted (its summary, with the error, goes to stderr). Throws what ServerApi throws.
int watch_job(const ServerApi& api, std::int64_t id, const std::string& verb, WatchOutput output);

}  // namespace dem::cli
