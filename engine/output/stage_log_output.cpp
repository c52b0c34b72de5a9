#include "output/stage_log_output.hpp"

#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace dem {

namespace {

// The last stage a file already lists (0-based; -1: none): a continued run goes on from there.
// The saved state may be anywhere in a stage, before or after its first frame wrote its line.
int last_logged(const std::string& path) {
  std::ifstream in(path);
  int last = -1;
  for (std::string line; std::getline(in, line);) {
    int stage = 0;
    if (std::sscanf(line.c_str(), "%d", &stage) == 1) last = stage - 1;
  }
  return last;
}

}  // namespace

StageLogWriter::StageLogWriter(const std::string& path, bool append) : logged_(append ? last_logged(path) : -1) {
  const bool fresh = !append || !std::filesystem::exists(path) || std::filesystem::file_size(path) == 0;
  file_ = OutputFile(path, append);
  if (fresh) std::fprintf(file_.get(), "stage start_step start_time name\n");
}

// One line a stage: its number from 1, the step and time it began (%.16e: read back exactly), its
// name (no control characters: the spec refuses them).
void StageLogWriter::frame(const Simulation& sim) {
  if (sim.stage() == logged_) return;
  logged_ = sim.stage();
  std::fprintf(file_.get(), "%d %" PRId64 " %.16e %s\n", sim.stage() + 1, sim.stage_start_step(),
               static_cast<double>(sim.stage_start_step()) * sim.dt(), sim.stage_name().c_str());
  file_.flush();
}

}  // namespace dem
