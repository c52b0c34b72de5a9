// A job's checkpoint: the simulation's whole state (sim/state_io.hpp) together with the length each
// output file had at that moment, in one file replaced atomically. Resuming cuts the outputs back to
// those lengths (dropping whatever was written after the checkpoint, a half-written frame included)
// and continues from the state, so the resumed job's files are those of an uninterrupted run.
#pragma once

#include <cstdint>
#include <string>

#include "sim/simulation.hpp"

namespace dem::server {

// Writes `path` (beside it, synced, then renamed over it).
void write_checkpoint(const Simulation& sim, const std::string& output_folder, const std::string& path);

// Restores `sim` and cuts the output files back; throws std::runtime_error naming what is wrong.
void resume_from_checkpoint(Simulation& sim, const std::string& output_folder, const std::string& path);

}  // namespace dem::server
