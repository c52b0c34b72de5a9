#include "server/api_routes.hpp"

#include <algorithm>
#include <system_error>
#include <variant>

#include "core/errors.hpp"
#include "dem/version.hpp"
#include "server/bundled_cases.hpp"
#include "server/file_response.hpp"
#include "server/job_log.hpp"
#include "server/own_files.hpp"
#include "server/preferences.hpp"
#include "server/request_policy.hpp"
#include "spec/json_keys.hpp"
#include "spec/spec_loader.hpp"

namespace dem::server {
namespace fs = std::filesystem;
namespace {

using Response = http::response<http::string_body>;

std::string content_type(const Request& req) {
  std::string type(req[http::field::content_type]);
  type = type.substr(0, type.find(';'));
  type.erase(std::remove(type.begin(), type.end(), ' '), type.end());
  std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return std::tolower(c); });
  return type;
}

Response method_not_allowed(const Request& req, const char* allowed) {
  Response res = error_response(req, http::status::method_not_allowed,
                                std::string(req.method_string()) + " is not allowed here (allowed: " + allowed + ")");
  res.set(http::field::allow, allowed);
  return res;
}

// The methods each kind of resource answers (its Allow header), HEAD and OPTIONS with the rest.
constexpr const char* kReadOnly = "GET, HEAD, OPTIONS";
constexpr const char* kJobs = "GET, HEAD, POST, OPTIONS";
constexpr const char* kJob = "GET, HEAD, DELETE, OPTIONS";
constexpr const char* kAction = "POST, OPTIONS";

}  // namespace

const char* allowed_methods(const std::vector<std::string>& s) {
  if (s.size() == 2 && (s[1] == "health" || s[1] == "openapi.json" || s[1] == "cases")) return kReadOnly;
  if (s.size() == 3 && s[1] == "cases") return kReadOnly;
  if (s.size() >= 2 && s[1] == "studies") {
    if (s.size() == 2) return kJobs;
    if (s.size() == 3) return kReadOnly;
    if (s.size() == 4 && (s[3] == "cancel" || s[3] == "resume")) return kAction;
    if (s.size() == 4 && (s[3] == "results.json" || s[3] == "results.csv" || s[3] == "figure.svg")) return kReadOnly;
    return nullptr;
  }
  if (s.size() >= 2 && s[1] == "jobs") {
    if (s.size() == 2) return kJobs;
    if (s.size() == 3) return kJob;
    if (s.size() == 4 && (s[3] == "cancel" || s[3] == "resume")) return kAction;
    if (s.size() == 4 && (s[3] == "frames" || s[3] == "results" || s[3] == "log")) return kReadOnly;
    if (s[3] == "artifacts") return kReadOnly;
  }
  return nullptr;
}

void drop_api_version(Target& target) {
  std::vector<std::string>& s = target.segments;
  if (s.size() >= 2 && s[0] == "api" && s[1] == "v1") s.erase(s.begin() + 1);
}

namespace {

bool allows(const char* allowed, std::string_view method) {
  std::string_view list = allowed;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    if (list.substr(0, comma) == method) return true;
    if (comma == std::string_view::npos) break;
    list = list.substr(comma + 2);
  }
  return false;
}

Response submit(const Request& req, ApiContext& ctx) {
  const std::string type = content_type(req);
  api::JobSpec spec;
  try {
    if (type == "application/json") {
      spec = spec::parse_json(req.body());
    } else if (type == "application/x-protobuf" || type == "application/protobuf" ||
               type == "application/octet-stream") {
      spec = spec::parse_binary(req.body());
    } else {
      return error_response(
          req, http::status::unsupported_media_type,
          "Content-Type \"" + type +
              "\" is not a job spec: send application/json or application/x-protobuf (proto/dem.proto, JobSpec)");
    }
    const std::string key(req["Idempotency-Key"]);
    if (key.empty() && req.find("Idempotency-Key") != req.end())  // blank: meant as a key, would act as none
      return error_response(req, http::status::bad_request,
                            "Idempotency-Key is empty: give a key, or leave the header out");
    if (key.size() > 200 || !std::all_of(key.begin(), key.end(), [](unsigned char c) { return c >= 0x20 && c < 0x7f; }))
      return error_response(req, http::status::bad_request,
                            "Idempotency-Key must be printable ASCII of at most 200 characters");
    if (key.rfind(StudyManager::kRunKeyPrefix, 0) == 0)  // a job planted under a study's key would be its run
      return error_response(req, http::status::bad_request,
                            "Idempotency-Key \"" + key + "\": keys beginning \"" + StudyManager::kRunKeyPrefix +
                                "\" are the server's own (a study's runs)");
    const JobManager::Submitted s = ctx.jobs.submit(spec, key);
    if (s.conflict)
      return error_response(req, http::status::unprocessable_entity,
                            "Idempotency-Key \"" + key + "\" was used for job " + std::to_string(s.job.id) +
                                " with another spec: use a new key for a new job");
    Response res = json_response(req, s.created ? http::status::created : http::status::ok, to_json(s.job));
    res.set(http::field::location, std::string(kApiBase) + "/jobs/" + std::to_string(s.job.id));
    if (!s.created) res.set("Idempotent-Replayed", "true");
    apply_respond_async(req, res);  // the job runs after this answer, whatever the client prefers
    return res;
  } catch (const spec::SpecError& e) {
    return error_response(req, http::status::bad_request, "invalid spec", e.problems());
  } catch (const SceneError& e) {
    return error_response(req, http::status::bad_request, "invalid spec", {e.what()});
  }
}

Response create_study(const Request& req, ApiContext& ctx) {
  if (content_type(req) != "application/json")
    return error_response(req, http::status::unsupported_media_type,
                          "Content-Type \"" + content_type(req) + "\" is not a study: send application/json");
  const nlohmann::json study = nlohmann::json::parse(req.body(), nullptr, false);
  if (study.is_discarded())
    return error_response(req, http::status::bad_request, "the study is not JSON (docs/api.md, \"Studies\")");
  // a key given twice would be taken last, silently, where a job's spec is refused for it
  if (std::vector<std::string> twice = spec::repeated_keys(req.body()); !twice.empty()) {
    for (std::string& path : twice) path += ": is given twice in its object (the reader would keep the last one)";
    return error_response(req, http::status::bad_request, "invalid study", twice);
  }
  const std::string key(req["Idempotency-Key"]);
  if (key.size() > 200 || !std::all_of(key.begin(), key.end(), [](unsigned char c) { return c >= 0x20 && c < 0x7f; }))
    return error_response(req, http::status::bad_request,
                          "Idempotency-Key must be printable ASCII of at most 200 characters");
  try {
    const StudyManager::Created made = ctx.studies.create(study, key);
    if (made.being_made)
      return error_response(req, http::status::conflict,
                            "a study with Idempotency-Key \"" + key +
                                "\" is still being made (its runs checked and queued): ask again in a moment");
    if (made.conflict)
      return error_response(req, http::status::unprocessable_entity,
                            "Idempotency-Key \"" + key + "\" was used for study " + std::to_string(made.study.id) +
                                " with another study: use a new key for a new study");
    Response res =
        json_response(req, made.created ? http::status::created : http::status::ok, ctx.studies.describe(made.study));
    res.set(http::field::location, std::string(kApiBase) + "/studies/" + std::to_string(made.study.id));
    if (!made.created) res.set("Idempotent-Replayed", "true");
    apply_respond_async(req, res);
    return res;
  } catch (const study::StudyError& e) {
    return error_response(req, http::status::bad_request, "invalid study", e.problems());
  } catch (const spec::SpecError& e) {
    return error_response(req, http::status::bad_request, "invalid study", e.problems());
  }
}

http::message_generator study_resource(const Request& req, const std::vector<std::string>& s, ApiContext& ctx) {
  if (s.size() == 2) {
    if (req.method() == http::verb::post) return create_study(req, ctx);
    nlohmann::json list = nlohmann::json::array();
    for (const StudyRecord& study : ctx.studies.list()) list.push_back(ctx.studies.describe(study));
    return json_response(req, http::status::ok, {{"studies", list}});
  }
  const std::optional<std::int64_t> id = parse_job_id(s[2]);
  const std::optional<StudyRecord> study = id ? ctx.studies.get(*id) : std::nullopt;
  if (!study) return error_response(req, http::status::not_found, "no study " + s[2]);
  if (s.size() == 3) return json_response(req, http::status::ok, ctx.studies.describe(*study));
  if (s[3] == "cancel" || s[3] == "resume") {
    if (s[3] == "cancel")
      ctx.studies.cancel(*study);
    else
      ctx.studies.resume(*study);
    return json_response(req, http::status::ok, ctx.studies.describe(*study));
  }
  const study::StudyPlan plan = ctx.studies.plan(*study);
  const std::vector<study::StudyRow> rows = ctx.studies.rows(*study, plan);
  if (s[3] == "results.json") return json_response(req, http::status::ok, study::table_json(plan, rows));
  if (s[3] == "results.csv")
    return text_response(req, http::status::ok, "text/csv; charset=utf-8", study::table_csv(plan, rows));
  return text_response(req, http::status::ok, "image/svg+xml", study::figure_svg(plan, rows));
}

std::vector<std::string> comma_list(const std::string& text) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    items.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return items;
}

// What GET /jobs was asked for: its filters and its page.
struct JobQuery {
  std::vector<JobState> states;  // any of them; none: every state
  std::optional<std::string> name;
  std::vector<std::string> tags;  // all of them
  std::optional<std::int64_t> limit;
  std::int64_t after = 0;  // ids above this one

  bool matches(const JobRecord& j) const {
    if (!states.empty() && std::find(states.begin(), states.end(), j.state) == states.end()) return false;
    if (name && j.name != *name) return false;
    return std::all_of(tags.begin(), tags.end(), [&](const std::string& t) {
      return std::find(j.tags.begin(), j.tags.end(), t) != j.tags.end();
    });
  }
  // The same query from the job after `last` on.
  std::string next(std::int64_t last) const {
    // appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string here
    std::string q = kApiBase;
    q.append("/jobs?limit=").append(std::to_string(*limit)).append("&after=").append(std::to_string(last));
    for (std::size_t k = 0; k < states.size(); ++k) q.append(k == 0 ? "&state=" : ",").append(to_string(states[k]));
    if (name) q.append("&name=").append(percent_encode(*name));
    for (std::size_t k = 0; k < tags.size(); ++k) q.append(k == 0 ? "&tag=" : "%2C").append(percent_encode(tags[k]));
    return q;
  }
};

constexpr std::int64_t kMaxPage = 1000;

// The query's problems name the parameter and the value given; the first is answered.
std::variant<JobQuery, std::string> parse_job_query(const Target& target) {
  JobQuery q;
  if (!target.repeated.empty())  // which one counts would be a guess: a filter must not loosen silently
    return target.repeated.front() +
           "= is given more than once: give it once (several states or tags go in one, "
           "separated by commas)";
  for (const auto& [key, value] : target.query) {
    if (key == "state") {
      for (const std::string& item : comma_list(value)) {
        const std::optional<JobState> st = job_state_from(item);
        if (!st)
          return "state=" + value + ": \"" + item +
                 "\" is not a job state (queued, running, succeeded, failed, cancelled, interrupted; several "
                 "separated by commas)";
        q.states.push_back(*st);
      }
    } else if (key == "name") {
      q.name = value;
    } else if (key == "tag") {
      q.tags = comma_list(value);
      if (static_cast<int>(q.tags.size()) > spec::kMaxTags)
        return "tag=" + value + ": at most " + std::to_string(spec::kMaxTags) + " tags (a job has no more)";
      for (const std::string& t : q.tags)
        if (!spec::is_tag(t))
          return "tag=" + value + ": \"" + t + "\" is not a tag (1 to " + std::to_string(spec::kMaxTagBytes) +
                 " letters, digits and - _ . : =; several separated by single commas)";
    } else if (key == "limit") {
      const std::optional<std::int64_t> n = parse_job_id(value);
      if (!n || *n < 1 || *n > kMaxPage)
        return "limit=" + value + ": the page's length must be a whole number from 1 to " + std::to_string(kMaxPage);
      q.limit = n;
    } else if (key == "after") {
      const std::optional<std::int64_t> n = parse_job_id(value);
      if (!n) return "after=" + value + ": a job id is expected (the last id of the page before)";
      q.after = *n;
    } else if (key != "access_token") {
      return "\"" + key + "\" is not a parameter of this list (state, name, tag, limit, after)";
    }
  }
  return q;
}

// GET /jobs: the jobs in id order, filtered; with ?limit=, a page, and "next" (a link, also in the
// Link header) when more follow.
Response list_jobs(const Request& req, const Target& target, ApiContext& ctx) {
  const std::variant<JobQuery, std::string> parsed = parse_job_query(target);
  if (const std::string* problem = std::get_if<std::string>(&parsed))
    return error_response(req, http::status::bad_request, *problem);
  const JobQuery& q = std::get<JobQuery>(parsed);
  nlohmann::json jobs = nlohmann::json::array();
  std::optional<std::int64_t> last_shown;
  bool more = false;
  for (const JobRecord& j : ctx.jobs.list()) {  // in id order
    if (j.id <= q.after || !q.matches(j)) continue;
    if (q.limit && static_cast<std::int64_t>(jobs.size()) == *q.limit) {
      more = true;
      break;
    }
    jobs.push_back(to_json(j));
    last_shown = j.id;
  }
  nlohmann::json body = {{"jobs", jobs}};
  if (more) body["next"] = q.next(*last_shown);
  Response res = json_response(req, http::status::ok, body);
  if (more) res.set(http::field::link, "<" + q.next(*last_shown) + ">; rel=\"next\"");
  return res;
}

// GET /jobs/{id}/results: what the run found (results.json), once it ended.
Response job_results(const Request& req, const JobRecord& job) {
  if (job.results.is_null())
    return error_response(req, http::status::not_found,
                          is_final(job.state)
                              ? "job " + std::to_string(job.id) + " ended (" + to_string(job.state) +
                                    ") without results: it was cancelled, or stopped before its run could write them"
                              : "job " + std::to_string(job.id) + " has no results yet: it is " + to_string(job.state) +
                                    "; they come when it ends");
  return json_response(req, http::status::ok, job.results);
}

// the last lines are read into memory: 10,000 lines of a job log are about 1 MB (an attack with 450-byte
// lines and 100,000 took 45 MB a request); more of the log is had with Range, streamed
constexpr std::int64_t kMostLogLines = 10000;
constexpr const char* kLogType = "text/plain; charset=utf-8";

// GET /jobs/{id}/log: the job's own log (job_log.hpp), whole, as an artifact is sent (ETag, ranges,
// gzip), or its last lines (?tail=N). A job from before the server kept logs has an empty one.
http::message_generator job_log(const Request& req, const Target& target, std::int64_t id, ApiContext& ctx) {
  if (!target.repeated.empty())
    return error_response(req, http::status::bad_request, target.repeated.front() + "= is given more than once");
  std::optional<std::int64_t> tail;
  for (const auto& [key, value] : target.query) {
    if (key == "tail") {
      tail = parse_job_id(value);
      if (!tail || *tail < 1 || *tail > kMostLogLines)
        return error_response(req, http::status::bad_request,
                              "tail=" + value + ": the number of lines must be a whole number from 1 to " +
                                  std::to_string(kMostLogLines));
    } else if (key != "access_token") {
      return error_response(req, http::status::bad_request, "\"" + key + "\" is not a parameter of a job's log (tail)");
    }
  }
  const JobFolder folder = ctx.jobs.folder(id);
  // a link planted in the job's folder is never followed, as for artifacts
  if (!is_own_folder(folder.root) || !is_own_file(folder.log()))
    return text_response(req, http::status::ok, kLogType, "");
  if (tail)
    return text_response(req, http::status::ok, kLogType, last_lines(folder.log(), static_cast<std::size_t>(*tail)));
  std::optional<http::message_generator> file = file_response(
      req, folder.log(), {{http::field::content_type, kLogType}, {http::field::cache_control, "no-cache"}},
      Compression::GzipWhenAccepted);
  if (!file) return text_response(req, http::status::ok, kLogType, "");
  return std::move(*file);
}

Response action(const Request& req, const ActionResult& r, http::status done = http::status::ok) {
  switch (r.outcome) {
    case Outcome::NotFound:
      return error_response(req, http::status::not_found, r.message);
    case Outcome::Conflict:
      return error_response(req, http::status::conflict, r.message);
    case Outcome::Done:
      break;
  }
  if (done == http::status::no_content) {
    Response res{http::status::no_content, req.version()};
    res.set(http::field::date, http_date_now());
    res.keep_alive(req.keep_alive());  // no Content-Length in a 204 (RFC 9110 8.6): no prepare_payload
    return res;
  }
  return json_response(req, done, to_json(r.job));
}

Response list_artifacts(const Request& req, std::int64_t id, ApiContext& ctx) {
  const JobFolder folder = ctx.jobs.folder(id);
  nlohmann::json files = nlohmann::json::array();
  std::vector<std::pair<std::string, std::uintmax_t>> found;
  std::error_code ec;
  const bool own_root = is_own_folder(folder.root);
  if (own_root && is_own_folder(folder.outputs()))
    for (const fs::directory_entry& e : fs::directory_iterator(folder.outputs(), ec))
      if (is_own_file(e.path())) found.emplace_back(e.path().filename().string(), e.file_size());
  if (own_root && is_own_file(folder.archive()))
    found.emplace_back(JobFolder::kArchiveName, fs::file_size(folder.archive()));
  std::sort(found.begin(), found.end());
  for (const auto& [name, size] : found)
    files.push_back({{"name", name},
                     {"size", size},
                     {"url", std::string(kApiBase) + "/jobs/" + std::to_string(id) + "/artifacts/" + name}});
  return json_response(req, http::status::ok, {{"job", id}, {"artifacts", files}});
}

http::message_generator artifact(const Request& req, std::int64_t id, const std::string& name, ApiContext& ctx) {
  if (!is_artifact_name(name))
    return error_response(req, http::status::bad_request,
                          "\"" + name + "\" is not an artifact name (a file name from GET /api/v1/jobs/" +
                              std::to_string(id) + "/artifacts; no folders, no '..')");
  const JobFolder folder = ctx.jobs.folder(id);
  const fs::path path = name == JobFolder::kArchiveName ? folder.archive() : folder.outputs() / name;
  const bool tar = name == JobFolder::kArchiveName;
  const bool own = is_own_folder(folder.root) && (tar || is_own_folder(folder.outputs())) && is_own_file(path);
  if (!own)  // a link planted in the job's folder leads anywhere (/etc/shadow): never followed
    return error_response(req, http::status::not_found, "job " + std::to_string(id) + " has no artifact " + name);
  // the legacy files and results are text, the time series' twins CSV; ParaView's series is XML, its frames
  // binary after an XML header
  const std::string extension = fs::path(name).extension().string();
  const bool binary = extension == ".vtu" || extension == ".vtp";
  const char* type = tar                   ? "application/x-tar"
                     : extension == ".pvd" ? "application/xml"
                     : binary              ? "application/octet-stream"
                     : extension == ".csv" ? "text/csv; charset=utf-8"
                                           : "text/plain; charset=utf-8";
  // text is gzipped for a client that asks (about threefold smaller); ParaView's frames are float
  // arrays that deflate barely pays for, and the archive is kept as the file it is (its size listed)
  const Compression compression = tar || binary ? Compression::None : Compression::GzipWhenAccepted;
  std::optional<http::message_generator> file =
      file_response(req, path,
                    {{http::field::content_type, type},
                     {http::field::content_disposition, "attachment; filename=\"" + name + "\""},
                     {http::field::cache_control, "no-cache"}},  // kept, asked again by its ETag
                    compression);
  if (!file)
    return error_response(req, http::status::not_found, "job " + std::to_string(id) + " has no artifact " + name);
  return std::move(*file);
}

}  // namespace

bool is_artifact_name(const std::string& name) {
  if (name.empty() || name.size() > 100 || name[0] == '.') return false;
  return std::all_of(name.begin(), name.end(),
                     [](unsigned char c) { return std::isalnum(c) || c == '.' || c == '_' || c == '-'; });
}

http::message_generator handle_api(const Request& req, const Target& target, ApiContext& ctx) {
  const std::vector<std::string>& s = target.segments;  // s[0] == "api"
  const http::verb m = req.method();
  const bool get = m == http::verb::get || m == http::verb::head;
  const char* allowed = allowed_methods(s);
  if (!allowed)
    return error_response(req, http::status::not_found,
                          "no API at " + std::string(req.target()) + " (see /api/v1/openapi.json)");
  if (!allows(allowed, req.method_string())) return method_not_allowed(req, allowed);
  if (m == http::verb::options) {
    Response res{http::status::no_content, req.version()};
    res.set(http::field::allow, allowed);
    res.set(http::field::date, http_date_now());
    res.keep_alive(req.keep_alive());  // no Content-Length in a 204 (RFC 9110 8.6): no prepare_payload
    return res;
  }
  // the method is one the resource allows (above)
  if (s.size() == 2 && s[1] == "health") {
    nlohmann::json counts = nlohmann::json::object();
    for (const auto& [state, n] : ctx.jobs.counts()) counts[state] = n;
    const JobManager::StoreHealth h = ctx.jobs.store_health();
    nlohmann::json store = {
        {"freeBytes", h.free_bytes}, {"totalBytes", h.total_bytes}, {"unsavedJobs", h.unsaved_jobs}};
    if (!h.problem.empty()) store["problem"] = h.problem;
    return json_response(
        req, http::status::ok,
        {{"status", h.problem.empty() ? "ok" : "degraded"}, {"version", kVersion}, {"jobs", counts}, {"store", store}});
  }
  if (s.size() == 2 && s[1] == "openapi.json")
    return text_response(req, http::status::ok, "application/json", ctx.openapi);
  if (s[1] == "cases") {
    if (s.size() == 2) return json_response(req, http::status::ok, {{"cases", list_cases(ctx.cases)}});
    if (std::optional<std::string> spec = case_spec(ctx.cases, s[2]))
      return text_response(req, http::status::ok, "application/json", std::move(*spec));
    return error_response(req, http::status::not_found, "no bundled case " + s[2]);
  }
  if (s[1] == "studies") return study_resource(req, s, ctx);
  // s[1] == "jobs"
  if (s.size() == 2) return m == http::verb::post ? submit(req, ctx) : list_jobs(req, target, ctx);
  const std::optional<std::int64_t> id = parse_job_id(s[2]);
  const std::optional<JobRecord> job = id ? ctx.jobs.get(*id) : std::nullopt;
  if (!job) return error_response(req, http::status::not_found, "no job " + s[2]);
  if (s.size() == 3) {
    if (get) return json_response(req, http::status::ok, to_json(*job));
    return action(req, ctx.jobs.remove(*id), http::status::no_content);
  }
  if (s[3] == "cancel" || s[3] == "resume")
    return action(req, s[3] == "cancel" ? ctx.jobs.cancel(*id) : ctx.jobs.resume(*id));
  if (s[3] == "results") return job_results(req, *job);
  if (s[3] == "log") return job_log(req, target, *id, ctx);
  if (s[3] == "frames") {
    Response res = error_response(req, http::status::upgrade_required,
                                  "the frames of job " + s[2] + " are a WebSocket stream: connect with ws://");
    res.set(http::field::upgrade, "websocket");
    // RFC 9110 7.8: Upgrade is named in Connection; a client that asked to close is still closed on
    res.set(http::field::connection, req.keep_alive() ? "Upgrade" : "Upgrade, close");
    return res;
  }
  // artifacts
  if (s.size() == 4) return list_artifacts(req, *id, ctx);
  std::string name = s[4];
  for (std::size_t k = 5; k < s.size(); ++k) name += "/" + s[k];  // a path, refused by is_artifact_name
  return artifact(req, *id, name, ctx);
}

}  // namespace dem::server
