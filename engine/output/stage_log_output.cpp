#include "output/stage_log_output.hpp"

#include <cinttypes>

namespace dem {

StageLogWriter::StageLogWriter(const std::string& path, bool append) : file_(path, append) {
  if (!append) std::fprintf(file_.get(), "stage start_step start_time name\n");
}

// One line a stage: its number from 1, the step and time it began (%.16e: read back exactly), its
// name (no control characters: the spec refuses them).
void StageLogWriter::stage_begun(const Simulation& sim) {
  std::fprintf(file_.get(), "%d %" PRId64 " %.16e %s\n", sim.stage() + 1, sim.stage_start_step(),
               static_cast<double>(sim.stage_start_step()) * sim.dt(), sim.stage_name().c_str());
  file_.flush();
}

}  // namespace dem
