// Particles entering during a run (Scene::sources): a stream of sand poured into a box inserts rate
// times time (within half a particle) without an overlap; a count rate, a face of a plate, a source
// of one stage, a crowded region that holds particles back; a run saved between batches continues to
// the uninterrupted run's bits; and a scene without a source steps as it did before sources existed.
#include <gtest/gtest.h>

#include <sstream>

#include "sim/particle_sources.hpp"
#include "sim/runner.hpp"
#include "sim/state_io.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_sources {
namespace {

constexpr double kG = 9.81;
constexpr double kDensity = 2650;  // quartz sand

// An open-topped box 0.1 m wide and 0.3 m tall, and sand of 4 to 6 mm poured at 0.05 kg/s from a
// layer near its top, moving down at 1 m/s.
Scene sand_stream(double duration) {
  Scene s = base_scene(LinearNormal::kName, kDensity, 0, 0.25, 0.3, 0.5, 2e3);
  s.gravity = {0, 0, -kG};
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "floor"));
  for (int d = 0; d < 2; ++d) {
    Vec3 n = Vec3::Zero();
    n[d] = 1;
    s.walls.push_back(plane(-0.05 * n, n, "side"));
    s.walls.push_back(plane(0.05 * n, -n, "side"));
  }
  ParticleSource sand;
  sand.name = "sand";
  sand.box = Box{{-0.05, -0.05, 0.25}, {0.05, 0.05, 0.3}};
  sand.sizes.kind = SizeKind::Uniform;
  sand.sizes.d_min = 0.004;
  sand.sizes.d_max = 0.006;
  sand.mass_rate = 0.05;
  sand.velocity = {0, 0, -1};
  s.sources.push_back(sand);
  s.time.steps = 0;
  s.time.duration = duration;
  return s;
}

// The stream from the underside of a lid over the box, at height z, in a layer `depth` deep.
void pour_from_a_lid(Scene& s, double z, double depth) {
  WallInit lid{"lid",
               1,
               PlateShape{{Vec3(-0.05, -0.05, z), Vec3(0.05, -0.05, z), Vec3(0.05, 0.05, z), Vec3(-0.05, 0.05, z)}},
               {},
               {}};
  s.walls.push_back(lid);
  s.sources[0].region = ParticleSource::Region::Face;
  s.sources[0].face_wall = static_cast<int>(s.walls.size()) - 1;
  s.sources[0].depth = depth;
}

double inserted_mass(const Simulation& sim) {
  double m = 0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i)
    if (sim.particles().id[i] >= static_cast<int>(sim.given_particles())) m += sim.particles().mass[i];
  return m;
}

TEST(Sources, ASandStreamInsertsItsMassRateTimesTheTimeWithoutOverlaps) {
  const double duration = 0.4;
  Simulation sim(sand_stream(duration));
  EXPECT_EQ(sim.particles().size(), 0u);
  const RunOutcome outcome = run(sim, {});  // the stability guard stops a deep overlap
  ASSERT_TRUE(outcome.ok) << outcome.error;
  const double expected = 0.05 * sim.time();
  const double largest = sphere_mass(kDensity, 0.003);
  EXPECT_NEAR(inserted_mass(sim), expected, 0.5 * largest);  // to the nearest particle
  EXPECT_NEAR(inserted_mass(sim), expected, 0.01 * expected);
  EXPECT_NEAR(sim.source_progress()[0].mass, inserted_mass(sim), 1e-12 * expected);
  EXPECT_GT(sim.particles().size(), 80u);  // of 0.18 g on average
  EXPECT_EQ(sim.source_progress()[0].crowded_batches, 0);
  // each inserted particle came in with the stream's velocity, inside the layer, sized within the bounds
  for (std::size_t id = 0; id < sim.scene().particles.size(); ++id) {
    const ParticleInit& p = sim.scene().particles[id];
    EXPECT_EQ(p.velocity, Vec3(0, 0, -1));
    EXPECT_GE(p.radius, 0.002);
    EXPECT_LE(p.radius, 0.003);
    EXPECT_GE(p.position.z() - p.radius, 0.25 - 1e-12);
    EXPECT_EQ(p.source, 0);
  }
  // the sand reached the floor, and no grain left the box
  double lowest = 1;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) {
    lowest = std::min(lowest, sim.particles().x[i].z());
    EXPECT_LE(sim.particles().x[i].head<2>().cwiseAbs().maxCoeff(), 0.05);
  }
  EXPECT_LT(lowest, 0.01);
  // what the grains brought is input to the energy ledger, not energy the integration made
  EXPECT_GT(sim.energy_input().sources, 0);
}

TEST(Sources, NoNewParticleOverlapsAnotherOrAWallWhenItEnters) {
  Scene s = sand_stream(0.2);
  s.sources[0].mass_rate = 0.5;  // ten times as dense a stream
  Simulation sim(std::move(s));
  std::size_t before = 0;
  while (sim.step_count() < sim.total_steps()) {
    sim.step();
    const Particles& p = sim.particles();
    if (p.size() == before) continue;
    // the step that inserted them: they touch nothing at their place of entry
    // (a step inserts after its drift, so every particle is still where it was then)
    for (std::size_t id = before; id < p.size(); ++id) {
      const ParticleInit& in = sim.scene().particles[id];
      for (std::size_t j = 0; j < p.size(); ++j) {
        if (p.id[j] == static_cast<int>(id)) continue;
        const double gap = (in.position - p.x[j]).norm() - in.radius - p.radius[j];
        ASSERT_GE(gap, 0) << "particle " << id << " entered on particle " << p.id[j];
      }
      EXPECT_GE(in.position.x() - in.radius, -0.05);
      EXPECT_LE(in.position.x() + in.radius, 0.05);
    }
    before = p.size();
  }
  EXPECT_NEAR(inserted_mass(sim), 0.5 * sim.time(), 0.01 * 0.5 * sim.time());
}

TEST(Sources, ACountRateInsertsRateTimesTimeToTheNearestParticle) {
  Scene s = sand_stream(0.1);
  s.sources[0].mass_rate = 0;
  s.sources[0].count_rate = 1234;
  s.sources[0].every_steps = 1;
  Simulation sim(std::move(s));
  while (sim.step_count() < sim.total_steps()) {
    sim.step();
    ASSERT_EQ(static_cast<double>(sim.particles().size()), std::floor(1234 * sim.time() + 0.5));
  }
}

// A source given a total (a study's sand mass: 0, 2, 4 kg) stops when it has inserted it, to the
// nearest particle; a total of 0 inserts nothing.
TEST(Sources, ATotalMassOrCountStopsTheStreamWhenItHasEntered) {
  for (double total : {0.0, 0.004, 0.02}) {
    Scene s = sand_stream(0.1);
    s.sources[0].mass_rate = 0.5;  // 0.05 kg over the run without the total
    s.sources[0].total_mass = total;
    Simulation sim(std::move(s));
    while (sim.step_count() < sim.total_steps()) sim.step();
    EXPECT_NEAR(inserted_mass(sim), total, 0.5 * sphere_mass(kDensity, 0.003)) << total << " kg";
    EXPECT_EQ(total_reached(sim.scene(), sim.scene().sources[0], sim.source_progress()[0]), true);
    if (total == 0) {
      EXPECT_EQ(sim.particles().size(), 0u);
    }
  }
  Scene s = sand_stream(0.1);
  s.sources[0].mass_rate = 0;
  s.sources[0].count_rate = 1234;
  s.sources[0].total_count = 17;
  Simulation sim(std::move(s));
  while (sim.step_count() < sim.total_steps()) sim.step();
  EXPECT_EQ(sim.particles().size(), 17u);
  EXPECT_EQ(total_reached(sim.scene(), sim.scene().sources[0], sim.source_progress()[0]), true);

  // a total the rate does not reach over the run is said to be short (the run's 0.05 kg of 1 kg)
  Scene beyond = sand_stream(0.1);
  beyond.sources[0].mass_rate = 0.5;
  beyond.sources[0].total_mass = 1;
  Simulation short_of(std::move(beyond));
  while (short_of.step_count() < short_of.total_steps()) short_of.step();
  EXPECT_EQ(total_reached(short_of.scene(), short_of.scene().sources[0], short_of.source_progress()[0]), false);
  EXPECT_EQ(total_reached(sim.scene(), ParticleSource{}, SourceProgress{}), std::nullopt);  // no total
}

TEST(Sources, ACrowdedRegionHoldsParticlesBackUntilThereIsRoom) {
  Scene s = sand_stream(0.05);
  s.sources[0].box = Box{{-0.01, -0.01, 0.25}, {0.01, 0.01, 0.26}};  // room for a few grains only
  s.sources[0].velocity = Vec3::Zero();
  s.sources[0].mass_rate = 1;
  Simulation sim(std::move(s));
  while (sim.step_count() < sim.total_steps()) sim.step();
  EXPECT_GT(sim.source_progress()[0].crowded_batches, 0);
  EXPECT_LT(inserted_mass(sim), 0.5 * sim.time());
  EXPECT_GT(sim.particles().size(), 0u);
}

TEST(Sources, AFaceOfAPlateInsertsOnTheSideTheStreamMovesTo) {
  Scene s = sand_stream(0.1);
  pour_from_a_lid(s, 0.3, 0.02);
  Simulation sim(std::move(s));
  while (sim.step_count() < sim.total_steps()) sim.step();
  ASSERT_GT(sim.scene().particles.size(), 20u);
  for (const ParticleInit& p : sim.scene().particles) {
    EXPECT_LE(p.position.z() + p.radius, 0.3);          // below the lid: the stream moves down
    EXPECT_GE(p.position.z() - p.radius, 0.28 - 1e-9);  // within the layer
  }
  EXPECT_NEAR(inserted_mass(sim), 0.05 * sim.time(), 0.5 * sphere_mass(kDensity, 0.003));
}

// A layer thinner than the particles puts each at its radius from the face: the particles near the
// face must still be seen (an independent tester's face source of depth 1 mm made overlaps of 0.5 mm).
TEST(Sources, AFaceLayerThinnerThanTheParticlesInsertsNoOverlaps) {
  Scene s = sand_stream(0.02);
  pour_from_a_lid(s, 0.2, 0.001);
  s.sources[0].mass_rate = 0.5;
  Simulation sim(std::move(s));
  std::size_t before = 0;
  while (sim.step_count() < sim.total_steps()) {
    sim.step();
    const Particles& p = sim.particles();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.id[i] < static_cast<int>(before)) continue;  // only the step's new ones
      for (std::size_t j = 0; j < p.size(); ++j) {
        if (j == i) continue;
        const double gap = (p.x[i] - p.x[j]).norm() - p.radius[i] - p.radius[j];
        ASSERT_GE(gap, 0) << "particle " << p.id[i] << " entered on particle " << p.id[j] << " at step "
                          << sim.step_count();
      }
    }
    before = p.size();
  }
  EXPECT_GT(before, 20u);
}

// What a particle brings is what it has at the end of the step it enters: without contacts the
// energy balance holds to round-off (it was off by m g v dt / 2 a particle).
TEST(Sources, ParticlesEnteringInFreeFlightMakeNoEnergy) {
  for (double speed : {0.0, 1.0, 10.0}) {
    Scene s = sand_stream(0.002);
    s.walls.clear();
    s.sources[0].mass_rate = 0;
    s.sources[0].count_rate = 1e5;
    s.sources[0].velocity = {0, 0, -speed};
    Simulation sim(std::move(s));
    while (sim.step_count() < sim.total_steps()) sim.step();
    ASSERT_GT(sim.particles().size(), 100u);
    EXPECT_EQ(sim.contact_summary().elastic_energy, 0);
    const double balance = sim.mechanical_energy() - sim.energy_input().total() - sim.energy_input().initial_energy;
    EXPECT_NEAR(balance, 0, 1e-12 * sim.energy_input().magnitude) << "entering at " << speed << " m/s";
    for (std::size_t i = 0; i < sim.particles().size(); ++i)
      if (sim.particles().id[i] == static_cast<int>(sim.particles().size()) - 1) {
        EXPECT_NEAR(sim.particles().v[i].z(), -speed, 1e-12) << "the last one has the source's velocity";
      }
  }
}

TEST(Sources, ASourceOfOneStageInsertsOnlyDuringItFromItsStart) {
  Scene s = sand_stream(0);
  s.time.duration = 0;
  Stage quiet;
  quiet.name = "quiet";
  quiet.duration = 0.02;
  Stage pour;
  pour.name = "pour";
  pour.duration = 0.05;
  Stage settle;
  settle.name = "settle";
  settle.duration = 0.02;
  s.stages = {quiet, pour, settle};
  s.sources[0].stage = 1;
  Simulation sim(std::move(s));
  while (sim.stage() == 0 && sim.step_count() < sim.total_steps()) {
    sim.step();
    if (sim.stage() == 0) {
      ASSERT_EQ(sim.particles().size(), 0u);
    }
  }
  double pour_time = 0;
  std::size_t poured = 0;
  double mass = 0;
  while (sim.stage() == 1 && sim.step_count() < sim.total_steps()) {
    pour_time = static_cast<double>(sim.stage_end_step() - sim.stage_start_step()) * sim.dt();
    poured = sim.particles().size();
    mass = inserted_mass(sim);
    sim.step();
  }
  ASSERT_GT(poured, 0u);
  while (sim.step_count() < sim.total_steps()) sim.step();
  EXPECT_EQ(sim.particles().size(), poured);
  EXPECT_NEAR(mass, 0.05 * pour_time, 0.5 * sphere_mass(kDensity, 0.003));
}

TEST(Sources, ARunSavedBetweenBatchesContinuesToTheUninterruptedRunsBits) {
  Simulation whole(sand_stream(0.1));
  while (whole.step_count() < whole.total_steps()) whole.step();
  for (std::int64_t at : {std::int64_t{1}, whole.total_steps() / 3, whole.total_steps() / 2 + 7}) {
    Simulation first(sand_stream(0.1));
    while (first.step_count() < at) first.step();
    std::stringstream saved;
    StateIO::write(first, saved);
    Simulation second(sand_stream(0.1));
    StateIO::read(second, saved);
    ASSERT_EQ(second.particles().size(), first.particles().size());
    while (second.step_count() < second.total_steps()) second.step();
    ASSERT_EQ(second.particles().size(), whole.particles().size()) << "saved at step " << at;
    for (std::size_t i = 0; i < whole.particles().size(); ++i) {
      ASSERT_EQ(whole.particles().x[i], second.particles().x[i]) << "saved at step " << at << ", particle " << i;
      ASSERT_EQ(whole.particles().v[i], second.particles().v[i]) << "saved at step " << at << ", particle " << i;
    }
    EXPECT_EQ(whole.source_progress()[0].draws, second.source_progress()[0].draws);
    EXPECT_EQ(whole.energy_input().sources, second.energy_input().sources);
  }
}

TEST(Sources, AStateWithInsertedParticlesIsRefusedByAJobWithoutTheirSource) {
  Simulation first(sand_stream(0.1));
  for (int k = 0; k < 3000; ++k) first.step();
  ASSERT_GT(first.particles().size(), 0u);
  std::stringstream saved;
  StateIO::write(first, saved);
  // the same job without its source, with a sphere of the sand's size so that the step is the same
  Scene other = sand_stream(0.1);
  other.sources.clear();
  other.particles.push_back(sphere({0, 0, 0.1}, 0.002));
  Simulation second(std::move(other));
  ASSERT_EQ(second.dt(), first.dt());
  try {
    StateIO::read(second, saved);
    FAIL() << "read a state of a source into a scene without one";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("source"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dem::test::test_sources
