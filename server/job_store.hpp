// The job table, kept in SQLite (one file in the data folder). Every state change is committed
// before it is acted on, so a crash (kill -9) loses no job and no finished state.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "server/job.hpp"

struct sqlite3;

namespace dem::server {

class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class JobStore {
 public:
  explicit JobStore(const std::string& path);  // opens or creates; throws StoreError
  ~JobStore();
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  std::vector<JobRecord> load_all();  // in id order

  // Inserts `job` (its id is assigned) and calls `before_commit(id)` inside the transaction: the
  // row exists only if the callback (which writes the job's folder) returned.
  void insert(JobRecord& job, const std::function<void(std::int64_t)>& before_commit);
  void update(const JobRecord& job);
  void remove(std::int64_t id);

 private:
  void exec(const char* sql);
  sqlite3* db_ = nullptr;
  std::string path_;
};

}  // namespace dem::server
