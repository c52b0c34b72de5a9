#include "server/study_manager.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "server/durable_file.hpp"
#include "spec/spec_loader.hpp"

namespace dem::server {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

json record_json(const StudyRecord& s) {
  return {{"id", s.id},
          {"name", s.name},
          {"createdAt", s.created_at},
          {"jobs", s.jobs},
          {"study", s.study},
          {"idempotencyKey", s.idempotency_key},
          {"complete", s.complete}};
}

// The whole number at the start of `text` ("12" of "12 run 3" or of "12"), if it has one.
std::optional<std::int64_t> leading_number(const std::string& text) {
  std::int64_t n = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (error != std::errc() || end == text.data() || n < 0) return std::nullopt;
  return n;
}

std::string run_key(std::int64_t study, int run) {
  return StudyManager::kRunKeyPrefix + std::to_string(study) + " run " + std::to_string(run);
}

}  // namespace

StudyManager::StudyManager(const fs::path& data, JobManager& jobs) : folder_(data / "studies"), jobs_(jobs) {
  fs::create_directories(folder_);
  // A new study's id is past every id used before: those of the records, readable or not (a
  // damaged record keeps its file and its id), and those in the keys of the jobs of studies whose
  // record is gone. Reused, an id's run keys were the old study's jobs' keys, of other specs: the
  // new study's runs were none of them queued.
  for (const std::string& key : jobs_.keys_beginning(kRunKeyPrefix))
    if (const std::optional<std::int64_t> id = leading_number(key.substr(std::string(kRunKeyPrefix).size())))
      next_id_ = std::max(next_id_, *id + 1);
  for (const fs::directory_entry& e : fs::directory_iterator(folder_)) {
    if (e.path().extension() != ".json") continue;  // a .part of a write cut short
    if (const std::optional<std::int64_t> id = leading_number(e.path().stem().string()))
      next_id_ = std::max(next_id_, *id + 1);
    if (!e.is_regular_file()) {
      spdlog::warn("{} is not a file: left out of the studies", e.path().string());
      continue;
    }
    StudyRecord s;
    try {
      std::ifstream in(e.path(), std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      const json j = json::parse(text.str(), nullptr, false);
      if (!j.is_object()) throw std::runtime_error("not a JSON object");
      s.id = j.at("id").get<std::int64_t>();
      if (e.path().filename() != std::to_string(s.id) + ".json")
        throw std::runtime_error("its name is not its id's (" + std::to_string(s.id) + ".json)");
      s.name = j.at("name").get<std::string>();
      s.created_at = j.at("createdAt").get<std::string>();
      s.jobs = j.at("jobs").get<std::vector<std::int64_t>>();
      s.study = j.at("study");
      s.idempotency_key = j.value("idempotencyKey", "");
      s.complete = j.value("complete", true);
    } catch (const std::exception& error) {
      // one damaged record does not keep the server and the other studies down
      spdlog::warn("the study record {} cannot be read ({}): left out", e.path().string(), error.what());
      continue;
    }
    next_id_ = std::max(next_id_, s.id + 1);
    if (!s.complete) {  // the server died while it queued the runs: queue the rest
      try {
        queue_runs(s);
        s.complete = true;
        save(s);
      } catch (const std::exception& error) {
        spdlog::error("study {}: its runs cannot be queued ({})", s.id, error.what());
      }
    }
    studies_.push_back(std::move(s));
  }
  std::sort(studies_.begin(), studies_.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
}

void StudyManager::save(const StudyRecord& study) const {
  write_file_durably(folder_ / (std::to_string(study.id) + ".json"), record_json(study).dump());
}

void StudyManager::queue_runs(StudyRecord& study) const {
  const study::StudyPlan p = plan(study);
  study.jobs.resize(p.runs.size(), -1);
  for (std::size_t k = 0; k < p.runs.size(); ++k) {
    if (study.jobs[k] >= 0) continue;
    try {
      const JobManager::Submitted s =
          jobs_.submit(spec::parse_json(p.runs[k].spec.dump()), run_key(study.id, p.runs[k].index));
      study.jobs[k] = s.conflict ? -1 : s.job.id;  // a job of another spec under the run's key is not the run
    } catch (const spec::SpecError&) {
      study.jobs[k] = -1;  // checked when the study was made: the server's limits changed since
    } catch (const SceneError&) {
      study.jobs[k] = -1;
    }
  }
}

StudyManager::Created StudyManager::create(const json& posted, const std::string& idempotency_key) {
  // A key is the study's from the request's start: a retry while the first request still checks
  // its runs (seconds for hundreds) made a second study (an independent tester), and a client that
  // gave up waiting retries with its key exactly then.
  if (!idempotency_key.empty()) {
    std::lock_guard lock(mutex_);
    for (const StudyRecord& s : studies_)
      if (s.idempotency_key == idempotency_key) return {s, false, s.study != posted};
    if (!keys_being_made_.insert(idempotency_key).second) return {StudyRecord{}, false, false, true};
  }
  struct KeyRelease {  // however the request ends
    StudyManager& m;
    const std::string& key;
    ~KeyRelease() {
      if (key.empty()) return;
      std::lock_guard lock(m.mutex_);
      m.keys_being_made_.erase(key);
    }
  } release{*this, idempotency_key};
  if (posted.is_object() && posted.contains("base") && !posted["base"].is_object())
    throw study::StudyError(
        {"base: the server takes the base spec inline, with its files (meshes) in it "
         "(dem study --submit inlines them)"});
  study::StudyPlan plan = study::plan_study(posted, json());
  std::vector<std::string> problems;
  for (const study::StudyRun& run : plan.runs) {
    const std::string where = study::run_label(plan, run.index, run.values) + ": ";
    try {
      jobs_.check(spec::parse_json(run.spec.dump()));  // as a submission is checked: no file is read
    } catch (const spec::SpecError& e) {
      for (const std::string& p : e.problems()) problems.push_back(where + p);
    } catch (const SceneError& e) {
      problems.push_back(where + e.what());
    }
    if (problems.size() > 100) break;
  }
  if (!problems.empty()) throw study::StudyError(problems);

  StudyRecord record;
  record.name = plan.name;
  record.created_at = utc_now();
  record.study = posted;
  record.idempotency_key = idempotency_key;
  {
    std::lock_guard lock(mutex_);
    record.id = next_id_++;
  }
  save(record);  // first, incomplete: a server that dies while it queues queues the rest at its start
  queue_runs(record);
  record.complete = true;
  save(record);
  std::lock_guard lock(mutex_);
  studies_.push_back(record);
  return {record, true, false};
}

std::vector<StudyRecord> StudyManager::list() const {
  std::lock_guard lock(mutex_);
  return studies_;
}

std::optional<StudyRecord> StudyManager::get(std::int64_t id) const {
  std::lock_guard lock(mutex_);
  for (const StudyRecord& s : studies_)
    if (s.id == id) return s;
  return std::nullopt;
}

study::StudyPlan StudyManager::plan(const StudyRecord& study) const { return study::plan_study(study.study, json()); }

std::vector<study::StudyRow> StudyManager::rows(const StudyRecord& study, const study::StudyPlan& plan) const {
  return rows(study, plan, nullptr);
}

std::vector<study::StudyRow> StudyManager::rows(const StudyRecord& study, const study::StudyPlan& plan,
                                                std::vector<std::optional<JobRecord>>* snapshots) const {
  std::vector<study::StudyRow> rows;
  for (std::size_t k = 0; k < plan.runs.size(); ++k) {
    study::StudyRow row = study::row_of(plan.runs[k]);
    std::optional<JobRecord> job;
    if (k < study.jobs.size()) {
      row.job = study.jobs[k];
      if (row.job >= 0) job = jobs_.get(row.job);
      if (row.job < 0) {
        row.state = "not queued";
      } else if (job) {
        row.state = to_string(job->state);
        row.error = job->error;
        row.results = job->results;
      } else {
        row.state = "deleted";
      }
    }
    rows.push_back(std::move(row));
    if (snapshots) snapshots->push_back(std::move(job));
  }
  return rows;
}

json StudyManager::describe(const StudyRecord& study) const {
  const study::StudyPlan p = plan(study);
  // One read of each job for its row's state and error and for its progress and finish: read again
  // here, a job ending in between made a study "finished" with a run still "running" in its counts.
  std::vector<std::optional<JobRecord>> snapshots;
  const std::vector<study::StudyRow> r = rows(study, p, &snapshots);
  std::map<std::string, int> counts;
  json jobs = json::array();
  bool finished = true;
  double progress = 0;
  for (std::size_t run = 0; run < r.size(); ++run) {
    const study::StudyRow& row = r[run];
    const std::optional<JobRecord>& job = snapshots[run];
    ++counts[row.state];
    json values = json::object();
    for (std::size_t k = 0; k < p.parameters.size() && k < row.values.size(); ++k)
      values[p.parameters[k].path] = row.values[k];
    json j = {{"run", row.index}, {"job", row.job}, {"parameters", values}, {"state", row.state}};
    if (job) {
      j["progress"] = job->progress();
      progress += job->progress();
      finished = finished && is_final(job->state);
    } else {
      progress += 1;
    }
    if (!row.error.empty()) j["error"] = row.error;
    jobs.push_back(std::move(j));
  }
  std::string summary;
  for (const auto& [state, n] : counts) summary += (summary.empty() ? "" : ", ") + std::to_string(n) + " " + state;
  json parameters = json::array();
  for (const study::StudyParameter& parameter : p.parameters) parameters.push_back(parameter.path);
  const std::string base = std::string(kApiBase) + "/studies/" + std::to_string(study.id);
  return {{"id", study.id},
          {"name", study.name},
          {"createdAt", study.created_at},
          {"parameters", parameters},
          {"combine", p.grid ? "grid" : "zip"},
          {"jobs", jobs},
          {"counts", counts},
          {"summary", summary},
          {"progress", r.empty() ? 1.0 : progress / static_cast<double>(r.size())},
          {"finished", finished},
          {"results",
           {{"json", base + "/results.json"}, {"csv", base + "/results.csv"}, {"figure", base + "/figure.svg"}}}};
}

void StudyManager::cancel(const StudyRecord& study) {
  // the queued ones first, from the last: a worker freed by the running one's end finds nothing
  for (auto id = study.jobs.rbegin(); id != study.jobs.rend(); ++id) {
    const std::optional<JobRecord> job = jobs_.get(*id);
    if (job && job->state == JobState::Queued) jobs_.cancel(*id);
  }
  for (std::int64_t id : study.jobs) {
    const std::optional<JobRecord> job = jobs_.get(id);
    if (job && !is_final(job->state)) jobs_.cancel(id);
  }
}

void StudyManager::resume(const StudyRecord& study) {
  for (std::int64_t id : study.jobs) {
    const std::optional<JobRecord> job = jobs_.get(id);
    if (job && job->state == JobState::Interrupted) jobs_.resume(id);
  }
}

}  // namespace dem::server
