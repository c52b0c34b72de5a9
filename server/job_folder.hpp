// Where a job keeps its files: DATA/jobs/ID/ holds the spec, the outputs (the legacy files, written
// as the job runs), the checkpoint, the job's log and, when the job has succeeded, the archive of its
// outputs. The log is beside the outputs, not among them: a resume cuts the outputs back to their
// checkpoint's lengths, and the log must keep what happened since.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace dem::server {

struct JobFolder {
  std::filesystem::path root;

  JobFolder(const std::filesystem::path& data, std::int64_t id) : root(data / "jobs" / std::to_string(id)) {}
  std::filesystem::path spec() const { return root / "spec.pb"; }
  std::filesystem::path outputs() const { return root / "outputs"; }
  std::filesystem::path checkpoint() const { return root / "checkpoint.dat"; }
  std::filesystem::path archive() const { return root / kArchiveName; }
  std::filesystem::path log() const { return root / "job.log"; }

  static constexpr const char* kArchiveName = "outputs.tar";
};

}  // namespace dem::server
