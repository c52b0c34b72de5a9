#include "output/run_writers.hpp"

#include <filesystem>

#include "output/energy_output.hpp"
#include "output/stage_log_output.hpp"
#include "output/legacy_output.hpp"
#include "output/statistics_output.hpp"
#include "output/wall_statistics_output.hpp"

namespace dem {

std::vector<std::unique_ptr<Observer>> make_run_writers(const Simulation& sim, const std::string& folder, bool append) {
  const std::filesystem::path dir(folder);
  const Scene& scene = sim.scene();
  std::vector<std::unique_ptr<Observer>> writers;
  if (scene.outputs.animation)
    writers.push_back(std::make_unique<AnimationWriter>((dir / "ANIMATION_3D.dat").string(), sim, append));
  if (scene.outputs.force_chains)
    writers.push_back(std::make_unique<ForceChainWriter>((dir / "ForceChain_3D.dat").string(), append));
  if (WallWriter::wanted(sim)) writers.push_back(std::make_unique<WallWriter>(dir.string(), sim, append));
  if (scene.outputs.force_chains && !scene.walls.empty())
    writers.push_back(std::make_unique<WallForceChainWriter>((dir / "Wall_ForceChain_3D.dat").string(), append));
  if (ForceDisplacementWriter::wanted(sim))
    writers.push_back(std::make_unique<ForceDisplacementWriter>((dir / "Force_Displacement.dat").string(), append));
  writers.push_back(std::make_unique<StatisticsWriter>(dir.string(), sim, append));
  if (WallStatisticsWriter::wanted(sim))
    writers.push_back(std::make_unique<WallStatisticsWriter>(dir.string(), append));
  writers.push_back(std::make_unique<EnergyWriter>((dir / "Energy.dat").string(), append));
  if (StageLogWriter::wanted(sim))
    writers.push_back(std::make_unique<StageLogWriter>((dir / "Stages.dat").string(), append));
  return writers;
}

}  // namespace dem
