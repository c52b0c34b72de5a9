// The set of legacy files a run writes into its folder, chosen from what the scene has. The CLI and
// the server both use it, so a job gives the same files, byte for byte, wherever it runs.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim/runner.hpp"

namespace dem {

// ANIMATION_3D.dat, ForceChain_3D.dat, Wall*.dat (the wall statistics too), Force_Displacement.dat
// and the statistics files
// (not restart.dat: the caller decides how it saves state). `append`: continue the files of a run
// resumed from a saved state.
std::vector<std::unique_ptr<Observer>> make_run_writers(const Simulation& sim, const std::string& folder, bool append);

}  // namespace dem
