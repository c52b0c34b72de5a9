#include "server/job_store.hpp"

#include <sqlite3.h>

namespace dem::server {
namespace {

// A prepared statement, finalized when it goes out of scope.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql, const std::string& path) : db_(db), path_(path) {
    if (sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr) != SQLITE_OK) fail("prepare");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement& text(int k, const std::string& v) {
    sqlite3_bind_text(stmt_, k, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& integer(int k, std::int64_t v) {
    sqlite3_bind_int64(stmt_, k, v);
    return *this;
  }
  Statement& real(int k, double v) {
    sqlite3_bind_double(stmt_, k, v);
    return *this;
  }
  bool row() {  // steps; true while there is a row to read
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE) fail("step");
    return false;
  }
  std::string column_text(int k) const {
    const unsigned char* t = sqlite3_column_text(stmt_, k);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
  std::int64_t column_int(int k) const { return sqlite3_column_int64(stmt_, k); }
  double column_real(int k) const { return sqlite3_column_double(stmt_, k); }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw StoreError("job table " + path_ + ": " + what + " failed: " + sqlite3_errmsg(db_));
  }
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
  const std::string& path_;
};

constexpr const char* kColumns =
    "id, name, state, created_at, started_at, finished_at, error, idempotency_key, particles, step, total_steps, "
    "time_step, checkpoint_step, run_seconds, stream_seconds, length_unit, results, tags";

}  // namespace

JobStore::JobStore(const std::string& path) : path_(path) {
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw StoreError("cannot open the job table " + path + ": " + why);
  }
  sqlite3_busy_timeout(db_, 5000);
  // One server per data folder, holding the table for itself: the WAL's index then lives in the
  // process's memory, not in a -shm file, so that a full disk does not stop the table from opening
  // (it did: "disk I/O error", and the server refused to start); a second server on the same
  // folder is told the table is locked.
  exec("PRAGMA locking_mode=EXCLUSIVE");
  // WAL with synchronous=FULL: a committed change survives a crash of the process or the machine.
  exec("PRAGMA journal_mode=WAL");
  exec("PRAGMA synchronous=FULL");
  exec(
      "CREATE TABLE IF NOT EXISTS jobs ("
      " id INTEGER PRIMARY KEY AUTOINCREMENT,"
      " name TEXT NOT NULL DEFAULT '',"
      " state TEXT NOT NULL,"
      " created_at TEXT NOT NULL,"
      " started_at TEXT NOT NULL DEFAULT '',"
      " finished_at TEXT NOT NULL DEFAULT '',"
      " error TEXT NOT NULL DEFAULT '',"
      " idempotency_key TEXT,"
      " particles INTEGER NOT NULL DEFAULT 0,"
      " step INTEGER NOT NULL DEFAULT 0,"
      " total_steps INTEGER NOT NULL DEFAULT 0,"
      " time_step REAL NOT NULL DEFAULT 0,"
      " checkpoint_step INTEGER NOT NULL DEFAULT -1,"
      " run_seconds REAL NOT NULL DEFAULT 0,"
      " stream_seconds REAL NOT NULL DEFAULT 0,"
      " length_unit TEXT NOT NULL DEFAULT 'm',"
      " results TEXT NOT NULL DEFAULT '',"
      " tags TEXT NOT NULL DEFAULT '[]')");
  // columns added since the table was first made: a data folder of an older server gains them
  for (const char* column : {"run_seconds REAL NOT NULL DEFAULT 0", "stream_seconds REAL NOT NULL DEFAULT 0",
                             "length_unit TEXT NOT NULL DEFAULT 'm'", "results TEXT NOT NULL DEFAULT ''",
                             "tags TEXT NOT NULL DEFAULT '[]'"}) {
    const std::string sql = std::string("ALTER TABLE jobs ADD COLUMN ") + column;
    sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr);  // fails, harmlessly, when it is there
  }
  exec("CREATE UNIQUE INDEX IF NOT EXISTS jobs_idempotency ON jobs(idempotency_key) WHERE idempotency_key IS NOT NULL");
}

JobStore::~JobStore() { sqlite3_close(db_); }

void JobStore::exec(const char* sql) {
  char* message = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string why = message ? message : sqlite3_errmsg(db_);
    sqlite3_free(message);
    throw StoreError("job table " + path_ + ": " + why);
  }
}

std::vector<JobRecord> JobStore::load_all() {
  Statement q(db_, (std::string("SELECT ") + kColumns + " FROM jobs ORDER BY id").c_str(), path_);
  std::vector<JobRecord> jobs;
  while (q.row()) {
    JobRecord j;
    j.id = q.column_int(0);
    j.name = q.column_text(1);
    const std::string state = q.column_text(2);
    const std::optional<JobState> s = job_state_from(state);
    if (!s)
      throw StoreError("job table " + path_ + ": job " + std::to_string(j.id) + " has an unknown state \"" + state +
                       "\"");
    j.state = *s;
    j.created_at = q.column_text(3);
    j.started_at = q.column_text(4);
    j.finished_at = q.column_text(5);
    j.error = q.column_text(6);
    j.idempotency_key = q.column_text(7);
    j.particles = q.column_int(8);
    j.step = q.column_int(9);
    j.total_steps = q.column_int(10);
    j.time_step = q.column_real(11);
    j.checkpoint_step = q.column_int(12);
    j.run_seconds = q.column_real(13);
    j.stream_seconds = q.column_real(14);
    j.length_unit = q.column_text(15);
    // a results text the table cannot parse (never written by the server) is shown as none
    j.results = nlohmann::json::parse(q.column_text(16), nullptr, false);
    if (j.results.is_discarded()) j.results = nullptr;
    const nlohmann::json tags = nlohmann::json::parse(q.column_text(17), nullptr, false);
    if (tags.is_array())
      for (const nlohmann::json& tag : tags)
        if (tag.is_string()) j.tags.push_back(tag.get<std::string>());
    jobs.push_back(std::move(j));
  }
  return jobs;
}

void JobStore::insert(JobRecord& job, const std::function<void(std::int64_t)>& before_commit) {
  exec("BEGIN IMMEDIATE");
  try {
    Statement q(
        db_,
        "INSERT INTO jobs (name, state, created_at, idempotency_key, particles, total_steps, time_step, length_unit,"
        " tags) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
        path_);
    q.text(1, job.name).text(2, to_string(job.state)).text(3, job.created_at);
    if (!job.idempotency_key.empty()) q.text(4, job.idempotency_key);  // unbound stays NULL: unique only when given
    q.integer(5, job.particles).integer(6, job.total_steps).real(7, job.time_step).text(8, job.length_unit);
    q.text(9, nlohmann::json(job.tags).dump());
    q.row();
    job.id = sqlite3_last_insert_rowid(db_);
    before_commit(job.id);
    exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

void JobStore::update(const JobRecord& job) {
  Statement q(
      db_,
      "UPDATE jobs SET name = ?, state = ?, started_at = ?, finished_at = ?, error = ?, particles = ?, step = ?,"
      " total_steps = ?, time_step = ?, checkpoint_step = ?, run_seconds = ?, stream_seconds = ?, results = ?"
      " WHERE id = ?",
      path_);
  q.text(1, job.name).text(2, to_string(job.state)).text(3, job.started_at).text(4, job.finished_at).text(5, job.error);
  q.integer(6, job.particles).integer(7, job.step).integer(8, job.total_steps).real(9, job.time_step);
  q.integer(10, job.checkpoint_step).real(11, job.run_seconds).real(12, job.stream_seconds);
  q.text(13, job.results.is_null() ? std::string()
                                   : job.results.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace))
      .integer(14, job.id);
  q.row();
}

void JobStore::remove(std::int64_t id) {
  Statement q(db_, "DELETE FROM jobs WHERE id = ?", path_);
  q.integer(1, id);
  q.row();
}

}  // namespace dem::server
