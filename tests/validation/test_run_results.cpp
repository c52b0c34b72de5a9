// A run's results (output/run_results.hpp) against closed forms: a loaded plate pressing on a sphere
// on the floor settles (2 F + m g) / 2 kn at each minimum of its load; free flight travels v t and drops g t^2 / 2; a
// lattice covers its own area; a bonded pair pulled apart is two fragments with half its mass broken off. And a run
// continued from a saved state gives the cycles of one run straight through.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "output/run_results.hpp"
#include "results/results_json.hpp"
#include "sim/state_io.hpp"
#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_run_results {
namespace {

constexpr double kKn = 1e7;        // N/m: a sphere on a rigid wall has 2 kn (docs/physics.md)
constexpr double kPlateMass = 10;  // kg
constexpr double kFMin = 100, kFMax = 1000, kFrequency = 3;
constexpr double kG = 9.81;

// The tracks of one test process, in one folder that goes when the process ends.
struct TrackFolder {
  std::filesystem::path path = std::filesystem::temp_directory_path() / ("dem_results_" + std::to_string(::getpid()));
  TrackFolder() = default;
  TrackFolder(const TrackFolder&) = delete;
  TrackFolder& operator=(const TrackFolder&) = delete;
  ~TrackFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

std::string track_path(const std::string& name) {
  static const TrackFolder folder;
  const auto dir = folder.path / name;
  std::filesystem::create_directories(dir);
  return (dir / ResultsRecorder::kTrackName).string();
}

constexpr double kR = 0.05;
const double kSphereMass = sphere_mass(2600, kR);

// A plate under a cyclic load, resting on a sphere on the floor (linear contacts, two springs in
// series): quasi-static, since the plate rings on them at about 70 Hz, twenty times the load's 3 Hz.
Scene plate_on_sphere(int cycles) {
  Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.3, 0.5, kKn);
  const double r = kR;
  s.particles.push_back(sphere(Vec3::Zero(), r));
  WallInit plate;
  plate.name = "sleeper";
  plate.material = 1;
  plate.shape = PlateShape{{Vec3(-0.1, -0.1, r), Vec3(-0.1, 0.1, r), Vec3(0.1, 0.1, r), Vec3(0.1, -0.1, r)}};
  LoadControl load;
  load.kind = LoadControl::Kind::Cyclic;
  load.mass = kPlateMass;
  load.direction = -Vec3::UnitZ();
  load.f_min = kFMin;
  load.f_max = kFMax;
  load.frequency = kFrequency;
  load.cycles = cycles;
  plate.load = load;
  s.walls = {plate, plane(Vec3(0, 0, -r), Vec3::UnitZ(), "floor")};
  s.gravity = Vec3(0, 0, -kG);
  s.time.dt = 2e-5;  // 1/55 of the contact time with the plate
  s.time.steps = static_cast<std::int64_t>((cycles + 0.2) / kFrequency / s.time.dt);
  return s;
}

// Runs `sim` with a recorder on `track` until its time reaches `until` (a run stopped there).
void run_until(Simulation& sim, const std::string& track, double until) {
  ResultsRecorder recorder(sim, track, false);
  RunOptions options;
  std::atomic<bool> stop{false};
  options.cancel = &stop;
  options.after_step = [&](const Simulation& s, bool) { stop = s.time() >= until; };
  run(sim, {&recorder}, options);
}

RunResults run_with_recorder(Simulation& sim, const std::string& track, bool append) {
  ResultsRecorder recorder(sim, track, append);
  run(sim, {&recorder});
  return recorder.results();
}

TEST(RunResults, APlateOnASphereSettlesItsStaticCompressionAtEachMinimumOfItsCyclicLoad) {
  Simulation sim(plate_on_sphere(3));
  const RunResults r = run_with_recorder(sim, track_path("plate"), false);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.loaded_walls.size(), 1u);
  const LoadedWallResults& w = r.loaded_walls[0];
  EXPECT_EQ(w.wall, "sleeper");
  EXPECT_TRUE(w.cyclic);
  ASSERT_EQ(w.cycles.size(), 3u);
  // both springs carry the plate's load and weight, the floor's the sphere's weight too
  const double weight = kPlateMass * kG, sphere_weight = kSphereMass * kG;
  const double k = 2 * kKn;
  const double at_min = (2 * (kFMin + weight) + sphere_weight) / k, at_max = (2 * (kFMax + weight) + sphere_weight) / k;
  for (const LoadCycle& c : w.cycles) {
    report("plate on a sphere: settlement at the end of cycle " + std::to_string(c.cycle), c.displacement, at_min);
    EXPECT_NEAR(c.displacement, at_min, 0.01 * at_min) << "cycle " << c.cycle;
    EXPECT_NEAR(c.peak_displacement, at_max, 0.01 * at_max) << "cycle " << c.cycle;
    EXPECT_NEAR(c.resilient, 2 * (kFMax - kFMin) / k, 0.01 * 2 * (kFMax - kFMin) / k) << "cycle " << c.cycle;
    EXPECT_NEAR(c.end_time, c.cycle / kFrequency, 1.5 * sim.dt());
    if (c.cycle > 1) {  // the first cycle starts with the plate's landing
      EXPECT_NEAR(c.force_min, kFMin + weight, 0.01 * (kFMin + weight));
      EXPECT_NEAR(c.force_max, kFMax + weight, 0.01 * (kFMax + weight));
    }
  }
  EXPECT_NEAR(w.force_max, kFMax + weight, 0.01 * (kFMax + weight));
  EXPECT_DOUBLE_EQ(w.start_time, 0);
}

// A held sphere (fixed in place) under the loaded plate: the plate rests on it, at F / 2 kn at each
// minimum of its load. It fell through the sphere before: a held particle's contacts with walls
// were skipped, moving walls' too (found while writing the test above).
TEST(RunResults, ALoadedPlateRestsOnAHeldSphere) {
  Scene s = plate_on_sphere(2);
  s.walls.pop_back();  // no floor: the sphere is held
  s.particles[0].fixed = true;
  Simulation sim(s);
  const RunResults r = run_with_recorder(sim, track_path("held"), false);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.loaded_walls.size(), 1u);
  ASSERT_EQ(r.loaded_walls[0].cycles.size(), 2u);
  const double k = 2 * kKn, weight = kPlateMass * kG;
  for (const LoadCycle& c : r.loaded_walls[0].cycles) {
    EXPECT_NEAR(c.displacement, (kFMin + weight) / k, 0.01 * (kFMin + weight) / k) << "cycle " << c.cycle;
    EXPECT_NEAR(c.peak_displacement, (kFMax + weight) / k, 0.01 * (kFMax + weight) / k) << "cycle " << c.cycle;
  }
}

TEST(RunResults, ARunContinuedFromASavedStateGivesTheCyclesOfOneRunStraightThrough) {
  const Scene scene = plate_on_sphere(3);
  Simulation whole(scene);
  const RunResults straight = run_with_recorder(whole, track_path("whole"), false);

  const std::string track = track_path("parts");
  Simulation first(scene);
  run_until(first, track, 0.5);  // the middle of cycle 2
  std::stringstream saved;
  StateIO::write(first, saved);
  Simulation second(scene);
  StateIO::read(second, saved);
  const RunResults continued = run_with_recorder(second, track, true);

  ASSERT_EQ(continued.loaded_walls.size(), 1u);
  const std::vector<LoadCycle>& a = straight.loaded_walls[0].cycles;
  const std::vector<LoadCycle>& b = continued.loaded_walls[0].cycles;
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(b[k].end_step, a[k].end_step);
    EXPECT_DOUBLE_EQ(b[k].displacement, a[k].displacement);
    EXPECT_NEAR(b[k].peak_displacement, a[k].peak_displacement, 1e-3 * a[k].peak_displacement);
  }
  // the cycle cut in two has its range from the resume on: the peak of cycle 2 was at the cut
  EXPECT_NEAR(continued.loaded_walls[0].force_max, straight.loaded_walls[0].force_max,
              1e-6 * straight.loaded_walls[0].force_max);
}

// Two spheres in free flight, v = (3, 4, 0) m/s under g: the centre of mass travels 5 t, drops
// g t^2 / 2 (velocity Verlet is exact for a constant force); the runout runs from the highest
// sphere's top to the front sphere's leading edge.
TEST(RunResults, FreeFlightTravelsVTAndDropsHalfGTSquared) {
  Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.5, 0.5, 1e5);
  const double r = 0.1, t = 0.5;
  s.particles.push_back(sphere({0, 0, 1.5}, r, {3, 4, 0}));
  s.particles.push_back(sphere({1, 0, 1}, r, {3, 4, 0}));
  s.gravity = Vec3(0, 0, -kG);
  s.time.dt = 1e-3;
  s.time.steps = 500;
  Simulation sim(s);
  const RunResults res = run_with_recorder(sim, track_path("flight"), false);
  ASSERT_TRUE(res.motion.has_value());
  const MotionResults& m = *res.motion;
  const double drop = kG * t * t / 2;
  EXPECT_NEAR(m.com_travel, 5 * t, 1e-9);
  EXPECT_NEAR(m.com_drop, drop, 1e-9);
  EXPECT_NEAR(m.direction.x(), 0.6, 1e-12);
  EXPECT_NEAR(m.direction.y(), 0.8, 1e-12);
  EXPECT_NEAR(m.com_travel_angle, std::atan2(drop, 5 * t) * 180 / std::numbers::pi, 1e-9);
  EXPECT_NEAR(m.front_end - m.front_start, 5 * t, 1e-9);
  // the crown: the top of the sphere at z = 1.5; the toe: the sphere from x = 1, its leading edge low
  const Vec3 d(0.6, 0.8, 0), up(0, 0, 1);
  const Vec3 crown(0, 0, 1.5 + r), toe = Vec3(1 + 3 * t, 4 * t, 1 - drop) + r * d - r * up;
  EXPECT_NEAR(m.runout_length, (toe - crown).dot(d), 1e-9);
  EXPECT_NEAR(m.fall_height, (crown - toe).dot(up), 1e-9);
  EXPECT_NEAR(m.h_over_l, m.fall_height / m.runout_length, 1e-12);
  EXPECT_EQ(res.steps, 500);
  EXPECT_TRUE(res.ok);
  EXPECT_NEAR(res.energy_dissipated, 0, 1e-9 * res.energy_start + 1e-9);  // nothing touches
}

// A layer of n x n spheres, each centred on a cell of one diameter: it covers n^2 d^2.
TEST(RunResults, ALayerCoversItsOwnArea) {
  Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.5, 0.5, 1e5);
  const double r = 0.02, d = 2 * r;
  const int n = 7;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) s.particles.push_back(sphere({(i + 0.5) * d * 1.0000001, (j + 0.5) * d, 0}, r));
  s.time.dt = 1e-4;
  s.time.steps = 10;
  Simulation sim(s);
  const RunResults res = run_with_recorder(sim, track_path("layer"), false);
  ASSERT_TRUE(res.motion.has_value());
  EXPECT_NEAR(res.motion->deposit_area, n * n * d * d, 1e-9);
  EXPECT_NEAR(res.motion->deposit_length, n * d, 1e-6);
  EXPECT_NEAR(res.motion->deposit_width, n * d, 1e-6);
  EXPECT_FALSE(res.fragments.has_value());  // no bonds
  EXPECT_TRUE(res.loaded_walls.empty());
}

// Adds a rigid clump of the two spheres `a` and `b` (its members, in that order) with its centroid
// at `centroid`, moving at `velocity` and spinning at `spin` (the members' own velocities as given).
void add_pair_clump(Scene& s, ParticleInit a, ParticleInit b, double mass, const Vec3& moments, const Vec3& centroid,
                    const Vec3& velocity = Vec3::Zero(), const Vec3& spin = Vec3::Zero()) {
  a.clump = b.clump = static_cast<int>(s.clumps.size());
  ClumpInit clump;
  clump.first = static_cast<int>(s.particles.size());
  clump.count = 2;
  clump.mass = mass;
  clump.moments = moments;
  clump.position = centroid;
  clump.velocity = velocity;
  clump.angular_velocity = spin;
  s.particles.push_back(a);
  s.particles.push_back(b);
  s.clumps.push_back(clump);
}

// A bonded pair pulled apart (and a loose sphere beside it): two pieces become three, the lighter
// half of the pair is the mass broken off, one bond broke in tension.
TEST(RunResults, ABondedPairPulledApartIsTwoFragmentsWithHalfItsMassBrokenOff) {
  Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.5, 0.5, 1e5);
  const double r = 0.01;
  s.particles.push_back(sphere({0, 0, 0}, r, {-1, 0, 0}));
  s.particles.push_back(sphere({2 * r, 0, 0}, r, {1, 0, 0}));
  s.particles.push_back(sphere({1, 1, 1}, r));
  BondSettings bonds;
  bonds.youngs_modulus = 1e7;
  bonds.tensile_strength = 1e3;
  bonds.shear_strength = 1e3;
  s.bonds = bonds;
  s.time.dt = 1e-6;
  s.time.steps = 2000;
  Simulation sim(s);
  const RunResults res = run_with_recorder(sim, track_path("pair"), false);
  ASSERT_TRUE(res.fragments.has_value());
  const FragmentResults& f = *res.fragments;
  const double m = sphere_mass(2600, r);
  EXPECT_EQ(f.initial_count, 2);
  EXPECT_EQ(f.count, 3);
  EXPECT_EQ(f.bonds_initial, 1);
  EXPECT_EQ(f.bonds_intact, 0);
  EXPECT_EQ(f.bonds_broken_tension, 1);
  EXPECT_EQ(f.bonds_broken_shear, 0);
  EXPECT_NEAR(f.crushed_mass, m, 1e-12);
  EXPECT_NEAR(f.crushed_mass_fraction, 0.5, 1e-12);
  EXPECT_NEAR(f.largest_mass_fraction, 1.0 / 3, 1e-12);
  ASSERT_EQ(f.sizes.size(), 1u);
  EXPECT_EQ(f.sizes[0].fragments, 3);
  EXPECT_NEAR(f.sizes[0].mass, 3 * m, 1e-12);
}

// Bonds and rigid clumps in one scene: a clump is one piece among the bonded ones. A bonded pair
// and two clumps far apart were counted as two pieces (the pair and the first clump both "1": an
// independent tester).
TEST(RunResults, AClumpIsOnePieceBesideBondedPieces) {
  Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.5, 0.5, 1e5);
  const double r = 0.01;
  s.particles.push_back(sphere({0, 0, 0}, r));
  s.particles.push_back(sphere({2 * r, 0, 0}, r));
  for (int c = 0; c < 2; ++c) {
    const Vec3 at(2.0 * c, 0, 1);
    add_pair_clump(s, sphere(at - Vec3(0.5 * r, 0, 0), r), sphere(at + Vec3(0.5 * r, 0, 0), r),
                   2 * sphere_mass(2600, r), Vec3(1e-6, 2e-6, 2e-6), at);
  }
  BondSettings bonds;
  bonds.youngs_modulus = 1e7;
  bonds.tensile_strength = 1e9;
  bonds.shear_strength = 1e9;
  s.bonds = bonds;
  s.time.dt = 1e-6;
  s.time.steps = 10;
  Simulation sim(s);
  const RunResults res = run_with_recorder(sim, track_path("clumps"), false);
  ASSERT_TRUE(res.fragments.has_value());
  EXPECT_EQ(res.fragments->bonds_initial, 1);  // the pair's; clump members are never bonded
  EXPECT_EQ(res.fragments->initial_count, 3);
  EXPECT_EQ(res.fragments->count, 3);
  // each piece weighs 2 m (a clump: the mass its spec gives), counted once
  EXPECT_NEAR(res.fragments->largest_mass_fraction, 1.0 / 3, 1e-12);
  ASSERT_EQ(res.fragments->sizes.size(), 1u);  // three pieces of two
  EXPECT_NEAR(res.fragments->sizes[0].mass, 6 * sphere_mass(2600, r), 1e-12);
  std::vector<int> by_id(6);
  for (std::size_t i = 0; i < 6; ++i) by_id[sim.particles().id[i]] = sim.fragments()[i];
  EXPECT_EQ(by_id, (std::vector<int>{1, 1, 2, 2, 3, 3}));
}

// Each piece's travel (a rockfall's runout distribution): five loose spheres in free flight, no
// gravity, at 0.1 to 0.5 m/s in five horizontal directions, and a two-sphere clump at 1 m/s across
// and 0.3 m/s up, for 1 s: six pieces (the clump one, each loose sphere its own) travelling 0.1, 0.2,
// 0.3, 0.4, 0.5 and 1 m (only the horizontal counts); the quantiles linear between them.
TEST(RunResults, EachPieceTravelsItsOwnVT) {
  Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.5, 0.5, 1e5);
  const double r = 0.01;
  for (int k = 0; k < 5; ++k) {
    const double angle = 1.2 * k, speed = 0.1 * (k + 1);
    s.particles.push_back(sphere({3.0 * k, 0, 0}, r, {speed * std::cos(angle), speed * std::sin(angle), 0}));
  }
  const Vec3 at(0, 5, 0), v(0.6, 0.8, 0.3);
  add_pair_clump(s, sphere(at - Vec3(0.5 * r, 0, 0), r, v), sphere(at + Vec3(0.5 * r, 0, 0), r, v),
                 2 * sphere_mass(2600, r), Vec3(1e-6, 2e-6, 2e-6), at, v);
  s.time.dt = 5e-5;
  s.time.steps = 20000;
  Simulation sim(s);
  const RunResults res = run_with_recorder(sim, track_path("pieces"), false);
  ASSERT_TRUE(res.motion.has_value());
  const MotionResults& m = *res.motion;
  EXPECT_EQ(m.pieces, 6);
  EXPECT_NEAR(m.piece_travel_mean, 2.5 / 6, 1e-9);
  ASSERT_EQ(m.piece_travel.size(), static_cast<std::size_t>(MotionResults::kPieceQuantiles));
  const std::vector<double> sorted{0.1, 0.2, 0.3, 0.4, 0.5, 1.0};
  for (int k = 0; k < MotionResults::kPieceQuantiles; ++k) {
    const double at_sorted = 5.0 * k / (MotionResults::kPieceQuantiles - 1);
    const auto below = static_cast<std::size_t>(at_sorted);
    const double expected =
        below >= 5 ? 1.0 : sorted[below] + (at_sorted - below) * (sorted[below + 1] - sorted[below]);
    EXPECT_NEAR(m.piece_travel[k], expected, 1e-9) << "quantile " << k;
  }
  EXPECT_NEAR(m.piece_travel[10], 0.35, 1e-9);  // the median
}

// A clump of unequal spheres travelling and turning: its travel is its centroid's, not its members'
// mean's. Two clumps of a sphere of radius 2r and one of r, their centroid 0.3 of the way from the
// big one: one moving at 0.2 m/s and turning half a turn in 0.5 s, one turning in place. They
// travelled 0.083 and 0.017 m for 0.1 and 0 (an independent tester), and the centre of mass too.
TEST(RunResults, AClumpOfUnequalSpheresTravelsWithItsCentroid) {
  Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.5, 0.5, 1e5);
  const double r = 0.01, t = 0.5, spin = std::numbers::pi / t;
  const std::vector<Vec3> at{{0, 0, 0}, {1, 0, 0}};
  const std::vector<Vec3> v{{0.2, 0, 0}, {0, 0, 0}};
  for (int c = 0; c < 2; ++c)
    add_pair_clump(s, sphere(at[c] - Vec3(0.006, 0, 0), 2 * r, v[c]), sphere(at[c] + Vec3(0.014, 0, 0), r, v[c]),
                   9 * sphere_mass(2600, r), Vec3(1e-5, 2e-5, 2e-5), at[c], v[c], Vec3(0, 0, spin));
  s.time.dt = 5e-5;
  s.time.steps = 10000;
  Simulation sim(s);
  const RunResults res = run_with_recorder(sim, track_path("unequal"), false);
  ASSERT_TRUE(res.motion.has_value());
  const MotionResults& m = *res.motion;
  EXPECT_EQ(m.pieces, 2);
  EXPECT_NEAR(m.piece_travel.front(), 0, 1e-9);
  EXPECT_NEAR(m.piece_travel.back(), 0.2 * t, 1e-9);
  EXPECT_NEAR(m.com_travel, 0.1 * t, 1e-9);  // the two clumps weigh the same
}

// A staged run's reference is where the particles are as its last stage begins: free flight through
// that stage travels v T exactly (it was one step late: 0.19999 of 0.2, an independent tester).
TEST(RunResults, TheReferenceIsTheLastStagesStart) {
  Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.5, 0.5, 1e5);
  s.particles.push_back(sphere({0, 0, 0}, 0.01, {1, 0, 0}));
  s.time.dt = 1e-3;
  s.time.allow_unstable_dt = true;  // nothing touches
  Stage first, second;
  first.name = "before";
  first.steps = 100;
  second.name = "after";
  second.steps = 200;
  s.stages = {first, second};
  Simulation sim(s);
  const RunResults r = run_with_recorder(sim, track_path("stages"), false);
  ASSERT_TRUE(r.motion.has_value());
  EXPECT_EQ(r.motion->reference_step, 100);
  EXPECT_NEAR(r.motion->reference_time, 0.1, 1e-12);
  EXPECT_EQ(r.motion->reference_stage, "after");
  EXPECT_NEAR(r.motion->com_travel, 0.2, 1e-12);
}

// A hopper 0.3 m over a floor lets ten spheres of 1 cm fall (200 a second for 0.05 s); 0.4 s: all have landed.
Scene hopper_over_a_floor() {
  Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.3, 0.5, 1e5);
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "floor"));
  ParticleSource source;
  source.name = "hopper";
  source.box = {Vec3(-0.05, -0.05, 0.28), Vec3(0.05, 0.05, 0.32)};
  source.sizes.mean = 0.01;
  source.count_rate = 200;
  source.end = 0.05;
  s.sources.push_back(source);
  s.gravity = Vec3(0, 0, -kG);
  s.time.dt = 2e-5;
  s.time.steps = 20000;  // 0.4 s: all have landed
  return s;
}

// Particles a source inserts after the reference count from where they entered: spheres entering
// at 0.3 m and falling to a floor drop, and the crown is the top of the entry region, not 0 (the
// centre of mass read 0 -> 0 and H/L was negative: an independent tester).
TEST(RunResults, ParticlesASourceInsertsCountFromWhereTheyEntered) {
  Simulation sim(hopper_over_a_floor());
  const RunResults r = run_with_recorder(sim, track_path("source"), false);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_GT(r.particles, 5u);
  ASSERT_TRUE(r.motion.has_value());
  EXPECT_GT(r.motion->com_start.z(), 0.28);
  EXPECT_LT(r.motion->com_end.z(), 0.05);
  EXPECT_GT(r.motion->com_drop, 0.23);
  EXPECT_GT(r.motion->fall_height, 0.25);
}

// What a source put in, and where its particles lie at the end (the sand-infiltration case's depth
// of the sand): 0.05 s at 200 a second is 10 spheres of 5 mm radius, on the floor or on each other at the end.
TEST(RunResults, ASourceSaysWhatItInsertedAndHowHighItsParticlesEnd) {
  Simulation sim(hopper_over_a_floor());
  const RunResults r = run_with_recorder(sim, track_path("source_heights"), false);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.sources.size(), 1u);
  const SourceResults& hopper = r.sources[0];
  EXPECT_EQ(hopper.name, "hopper");
  EXPECT_EQ(hopper.inserted, 10);
  EXPECT_NEAR(hopper.mass, 10 * sphere_mass(2600, 0.005), 1e-12);
  EXPECT_EQ(hopper.crowded_batches, 0);
  ASSERT_EQ(hopper.heights.size(), static_cast<std::size_t>(SourceResults::kHeightQuantiles));
  EXPECT_NEAR(hopper.heights.front(), 0.005, 5e-4);  // the lowest rests on the floor
  EXPECT_LT(hopper.heights.back(), 0.03);            // the highest on two others at most
  EXPECT_GT(hopper.height_mean, 0.0045);
  EXPECT_LT(hopper.height_mean, 0.02);
  const nlohmann::json j = results::to_json(r);
  EXPECT_EQ(j["sources"][0]["inserted"], 10);
  EXPECT_EQ(j["sources"][0]["heights"].size(), 21u);
  EXPECT_EQ(j["sources"][0]["heights"][20]["fraction"], 1.0);
}

// A zero is written 0, never -0.0 (a press's force before it touches the stone: an independent
// tester found "forceMin": -0.0 in the stone-crush case's results).
TEST(RunResults, NoNumberIsWrittenAsMinusZero) {
  RunResults r;
  r.energy_input = -0.0;
  LoadedWallResults w;
  w.wall = "press";
  w.force_min = -0.0;
  w.force_max = 1573.0;
  r.loaded_walls.push_back(w);
  const std::string text = results::to_json(r).dump();
  EXPECT_EQ(text.find("-0.0"), std::string::npos) << text;
  EXPECT_NE(text.find("\"forceMin\":0.0"), std::string::npos) << text;
  EXPECT_NE(text.find("\"forceMax\":1573.0"), std::string::npos) << text;
}

// A run continued without its track file says its results count from the continuation (they were
// silently from there: a settlement of the wrong sign, an independent tester).
TEST(RunResults, AContinuationWithoutItsTrackFileSaysSo) {
  const Scene scene = plate_on_sphere(2);
  Simulation first(scene);
  run_until(first, track_path("first"), 0.3);
  std::stringstream saved;
  StateIO::write(first, saved);
  Simulation second(scene);
  StateIO::read(second, saved);
  const std::string elsewhere = track_path("elsewhere");
  std::filesystem::remove(elsewhere);
  const RunResults r = run_with_recorder(second, elsewhere, true);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0],
            "results_track.dat was not in the run's folder: the motion and the load cycles count from the "
            "continuation at step 15000, not from the run's start");
  ASSERT_TRUE(r.motion.has_value());
  EXPECT_EQ(r.motion->reference_step, 15000);  // where it says (it was a step later)
  // a track file of its magic line alone: the motion from the continuation, and said so
  Simulation third(scene);
  saved.clear();
  saved.seekg(0);
  StateIO::read(third, saved);
  {
    std::ofstream header(elsewhere);
    header << "DEM-RESULTS-TRACK 1\n";
  }
  const RunResults h = run_with_recorder(third, elsewhere, true);
  ASSERT_EQ(h.notes.size(), 1u);
  EXPECT_EQ(h.notes[0],
            "results_track.dat holds no reference: the motion count from the continuation at step 15000, "
            "not from the run's start");
}

// A track file that is not one is refused by name, not read as nothing.
TEST(RunResults, ADamagedTrackFileIsRefusedByName) {
  const std::string track = track_path("damaged");
  {
    std::ofstream out(track);
    out << "DEM-RESULTS-TRACK 1\nload 7 0 0 0 1\n";
  }
  Simulation sim(plate_on_sphere(1));
  try {
    ResultsRecorder recorder(sim, track, true);
    FAIL() << "read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(track), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such wall"), std::string::npos) << e.what();
  }
  // a cycle number out of order (a million once took 1.8 GB of empty cycles), and other impossible lines
  const std::pair<const char*, const char*> damaged[] = {
      {"load 0 0 0 0 1\ncycle 0 0 1000000 0 0.1 0 0 0 0\n", "cycle 1000000 after 0 cycles"},
      {"cycle 0 0 1 0 0.1 0 0 0 0\n", "a cycle of a load that never began"},
      {"reference 0 0 0 1 \np 5 0 0 0 1\n", "no particle 5 in the run"},
      {"reference 0 0 0 1 \np 0 0 0 0 1\nreference 0 0 0 0 \n", "a second reference"},
      {"reference -100 0 0 0 \n", "a reference at a step below 0"},
      {"entered 0 1\np 0 0 0 0 1\n", "particles entered before the reference"},
  };
  for (const auto& [lines, why] : damaged) {
    {
      std::ofstream out(track);
      out << "DEM-RESULTS-TRACK 1\n" << lines;
    }
    try {
      ResultsRecorder recorder(sim, track, true);
      ADD_FAILURE() << "read: " << lines;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace dem::test::test_run_results
