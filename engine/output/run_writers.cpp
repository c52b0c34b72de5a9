#include "output/run_writers.hpp"

#include <algorithm>
#include <filesystem>

#include "output/animation_2d_output.hpp"
#include "output/energy_output.hpp"
#include "output/stage_log_output.hpp"
#include "output/legacy_output.hpp"
#include "output/statistics_output.hpp"
#include "output/vtk_output.hpp"
#include "output/wall_statistics_output.hpp"

namespace dem {
namespace {

// The PDEM-EGD manual's NLast (outputs.last_frames): a file of the particles' frames keeps only the
// run's last N frames, those from N - 1 frame intervals before its end on (a stage that ends early
// moves the end, and the frames after the new count with it).
class LastFramesOnly final : public Observer {
 public:
  explicit LastFramesOnly(std::unique_ptr<Observer> writer) : writer_(std::move(writer)) {}
  void frame(const Simulation& sim) override {
    const OutputSettings& o = sim.scene().outputs;
    const std::int64_t every = o.every_steps > 0 ? o.every_steps : std::max<std::int64_t>(1, sim.total_steps());
    const double first = static_cast<double>(sim.total_steps()) - static_cast<double>(o.last_frames - 1) * every;
    if (static_cast<double>(sim.step_count()) >= first) writer_->frame(sim);
  }
  void finish(const Simulation& sim, const RunOutcome& outcome) override { writer_->finish(sim, outcome); }

 private:
  std::unique_ptr<Observer> writer_;
};

}  // namespace

std::vector<std::unique_ptr<Observer>> make_run_writers(const Simulation& sim, const std::string& folder, bool append) {
  const std::filesystem::path dir(folder);
  const Scene& scene = sim.scene();
  std::vector<std::unique_ptr<Observer>> writers;
  if (!append) SeriesFiles::remove_earlier(dir.string());  // before this run's writers make theirs
  auto particle_frames = [&](std::unique_ptr<Observer> writer) -> std::unique_ptr<Observer> {
    if (scene.outputs.last_frames > 0) return std::make_unique<LastFramesOnly>(std::move(writer));
    return writer;
  };
  if (scene.outputs.animation && scene.plane)
    writers.push_back(
        particle_frames(std::make_unique<Animation2DWriter>((dir / "ANIMATION_2D.dat").string(), sim, append)));
  else if (scene.outputs.animation)
    writers.push_back(
        particle_frames(std::make_unique<AnimationWriter>((dir / "ANIMATION_3D.dat").string(), sim, append)));
  if (scene.outputs.force_chains)
    writers.push_back(
        particle_frames(std::make_unique<ForceChainWriter>((dir / "ForceChain_3D.dat").string(), append)));
  if (WallWriter::wanted(sim)) writers.push_back(std::make_unique<WallWriter>(dir.string(), sim, append));
  if (scene.outputs.force_chains && !scene.walls.empty())
    writers.push_back(
        particle_frames(std::make_unique<WallForceChainWriter>((dir / "Wall_ForceChain_3D.dat").string(), append)));
  if (ForceDisplacementWriter::wanted(sim))
    writers.push_back(
        std::make_unique<ForceDisplacementWriter>((dir / "Force_Displacement.dat").string(), sim, append));
  writers.push_back(std::make_unique<StatisticsWriter>(dir.string(), sim, append));
  if (WallStatisticsWriter::wanted(sim))
    writers.push_back(std::make_unique<WallStatisticsWriter>(dir.string(), scene.outputs.csv, append));
  writers.push_back(std::make_unique<EnergyWriter>((dir / "Energy.dat").string(), scene.outputs.csv, append));
  if (!append) VtkWriter::remove_earlier(dir.string());  // on or off: none of another run's stays
  if (scene.outputs.vtk) writers.push_back(particle_frames(std::make_unique<VtkWriter>(dir.string(), sim, append)));
  if (StageLogWriter::wanted(sim))
    writers.push_back(std::make_unique<StageLogWriter>((dir / "Stages.dat").string(), append));
  return writers;
}

}  // namespace dem
