// Rigid clumps in the engine: members move as one body driven by their summed contact forces.
// A two-sphere clump dropped flat comes to rest without drifting; a free asymmetric clump keeps its
// energy and its shape; on an incline a clump slides or rolls as its shape dictates, with the
// closed-form accelerations.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "clumps/mass_properties.hpp"
#include "legacy/legacy_formats.hpp"
#include "output/statistics_output.hpp"
#include "sim/simulation.hpp"
#include "sim/state_io.hpp"
#include "spec/spec_loader.hpp"
#include "support/report.hpp"
#include "support/spec_problems.hpp"

namespace dem::test::test_clumps {
namespace {

constexpr double kR = 0.01, kG = 9.81;

// A scene of clumps of two spheres (radius kR, centres `gap` apart along x in the shape's frame)
// on a plane through the origin with normal `normal`, with the given clumps (JSON objects).
std::string clump_spec(double mu, const Vec3& normal, const std::string& clumps, double gravity, double duration) {
  std::ostringstream s;
  s.precision(17);
  s << R"({"name": "clumps",
  "materials": [{"name": "rock", "density": 2650, "normalStiffness": 2e5}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": )"
    << mu << R"(},
                   {"a": "rock", "b": "steel", "restitution": 0.5, "friction": )"
    << mu << R"(}],
  "contact": {"normal": "LINEAR", "rolling": "NONE"},
  "clumpShapes": [{"name": "pair", "spheres": [{"center": {"x": -0.006}, "radius": 0.01}, {"center": {"x": 0.006}, "radius": 0.01}]},
                  {"name": "odd", "spheres": [{"center": {}, "radius": 0.01}, {"center": {"x": 0.012}, "radius": 0.006},
                                             {"center": {"y": 0.009, "z": 0.004}, "radius": 0.007}]}],
  "clumps": [)"
    << clumps << R"(],
  "walls": [{"material": "steel", "plane": {"point": {}, "normal": {"x": )"
    << normal.x() << R"(, "y": )" << normal.y() << R"(, "z": )" << normal.z() << R"(}}}],
  "gravity": {"z": )"
    << -gravity << R"(},
  "time": {"duration": )"
    << duration << R"(},
  "outputs": {"everySteps": 1000000}})";
  return s.str();
}

Simulation simulation_of(const std::string& json) { return Simulation(spec::to_scene(spec::parse_json(json))); }

void run_until(Simulation& sim, double t) {
  while (sim.time() < t && sim.step_count() < sim.total_steps()) sim.step();
}

TEST(Clumps, ATwoSphereClumpDroppedFlatComesToRestWithoutDrifting) {
  Simulation sim = simulation_of(
      clump_spec(0.5, Vec3::UnitZ(), R"({"shape": "pair", "material": "rock", "position": {"z": 0.03}})", kG, 1.0));
  ASSERT_EQ(sim.particles().size(), 2u);
  run_until(sim, 1.0);
  const ClumpBodies& b = sim.state().bodies;
  const Particles& p = sim.particles();
  std::printf("at rest: |v| %.2e m/s, centroid (%.2e, %.2e, %.6f) m, member heights %.7f %.7f m\n", b.v[0].norm(),
              b.x[0].x(), b.x[0].y(), b.x[0].z(), p.x[0].z(), p.x[1].z());
  EXPECT_LT(b.v[0].norm(), 1e-4);
  EXPECT_LT(std::hypot(b.x[0].x(), b.x[0].y()), 1e-9) << "a symmetric drop must not drift";
  EXPECT_NEAR(p.x[0].z(), p.x[1].z(), 1e-9) << "it lies flat";
  EXPECT_NEAR(p.x[0].z(), kR, 0.02 * kR);  // resting on the plane, overlap about m g / k
  EXPECT_NEAR((p.x[0] - p.x[1]).norm(), 0.012, 1e-12) << "the members keep their places";
}

// Local damping (numerics.localDamping, alpha) takes alpha of a falling body's weight, once: a
// clump of three spheres falls as a sphere does, (1 - alpha) g t^2 / 2 in t. Each member took alpha
// of the whole body's weight, so a clump of n members fell with (1 - n alpha) g: at alpha 0.3 a
// ballast stone of four spheres floated up (the bed of the ballast-box case never settled).
TEST(Clumps, LocalDampingTakesItsShareOfAFallingClumpsWeightOnce) {
  const double alpha = 0.3, t = 0.2;
  std::string json = clump_spec(
      0.5, Vec3::UnitZ(),
      R"({"shape": "odd", "material": "rock", "position": {"z": 1}, "rotationAxis": {"x": 1, "y": 2, "z": 0.5}, "rotationDegrees": 40})",
      kG, t);
  json.replace(json.find(R"("outputs")"), 0, R"("numerics": {"localDamping": 0.3}, )");
  Simulation sim = simulation_of(json);
  ASSERT_EQ(sim.particles().size(), 3u);
  const double z0 = sim.state().bodies.x[0].z();
  run_until(sim, t);
  const double drop = z0 - sim.state().bodies.x[0].z();
  EXPECT_NEAR(drop, (1 - alpha) * kG * sim.time() * sim.time() / 2, 1e-3 * drop);
  // nothing turns it: no torque, no spin
  EXPECT_LT(sim.particles().w[0].norm(), 1e-9);
}

TEST(Clumps, AFreeAsymmetricClumpKeepsItsEnergyAndItsShape) {
  // no gravity, far above the plane: torque-free motion of the "odd" clump
  Simulation sim = simulation_of(clump_spec(
      0.5, Vec3::UnitZ(),
      R"({"shape": "odd", "material": "rock", "position": {"z": 1}, "velocity": {"x": 0.1}, "angularVelocity": {"x": 3, "y": -20, "z": 5}})",
      0, 1.0));
  const double e0 = sim.kinetic_energy();
  const Particles& p = sim.particles();
  const double d01 = (p.x[0] - p.x[1]).norm(), d02 = (p.x[0] - p.x[2]).norm();
  double worst = 0;
  while (sim.step_count() < sim.total_steps()) {
    sim.step();
    if (sim.step_count() % 100 == 0) worst = std::max(worst, std::abs(sim.kinetic_energy() / e0 - 1));
  }
  std::printf("free clump: %lld steps, largest relative energy change %.2e\n", static_cast<long long>(sim.step_count()),
              worst);
  EXPECT_LT(worst, 1e-6);
  EXPECT_NEAR((p.x[0] - p.x[1]).norm(), d01, 1e-12);
  EXPECT_NEAR((p.x[0] - p.x[2]).norm(), d02, 1e-12);
  EXPECT_GT(sim.step_count(), 100000);
}

// An incline of theta, made by tilting gravity (the plane stays z = 0, +x runs downhill): a clump
// lying along the slope (its axis downhill) cannot roll and slides at g (sin - mu cos); lying
// across it (turned 90 degrees about z), it rolls about its axis at g sin / (1 + I_axis / (m r^2))
// when friction holds it. The acceleration of the centroid over 0.1..0.4 s.
double downhill_acceleration(double theta_deg, double mu, double clump_turn_deg) {
  const double th = theta_deg * std::numbers::pi / 180;
  std::ostringstream clump;
  clump.precision(17);
  clump << R"({"shape": "pair", "material": "rock", "position": {"z": )" << kR * 0.9999
        << R"(}, "rotationAxis": {"z": 1}, "rotationDegrees": )" << clump_turn_deg << "}";
  Scene s = spec::to_scene(spec::parse_json(clump_spec(mu, Vec3::UnitZ(), clump.str(), 0, 0.5)));
  s.gravity = Vec3(kG * std::sin(th), 0, -kG * std::cos(th));
  Simulation sim(s);
  run_until(sim, 0.1);
  const double v1 = sim.state().bodies.v[0].x(), t1 = sim.time();
  run_until(sim, 0.4);
  return (sim.state().bodies.v[0].x() - v1) / (sim.time() - t1);
}

TEST(Clumps, OnAnInclineAClumpSlidesOrRollsAsItsShapeDictates) {
  const double theta = 20, th = theta * std::numbers::pi / 180;
  // along the slope: two contacts one behind the other, no rolling: it slides
  const double mu_slide = 0.2;
  const double slide = downhill_acceleration(theta, mu_slide, 0);
  const double slide_want = kG * (std::sin(th) - mu_slide * std::cos(th));
  report("two-sphere clump sliding along the slope", slide, slide_want);
  EXPECT_NEAR(slide, slide_want, 5e-3 * slide_want);
  // across the slope: it rolls about its own axis (I_axis of the union of the two spheres)
  const MassProperties mp = union_mass_properties({{Vec3(-0.006, 0, 0), kR}, {Vec3(0.006, 0, 0), kR}}, 1e-4);
  const double roll = downhill_acceleration(theta, 0.5, 90);
  const double roll_want = kG * std::sin(th) / (1 + mp.principal_moments[0] / (mp.volume * kR * kR));
  report("two-sphere clump rolling across the slope", roll, roll_want);
  EXPECT_NEAR(roll, roll_want, 5e-3 * roll_want);
}

// A three-legged clump on a plane with gravity tilted to tan(theta) = 0.99 mu, below Coulomb's
// limit: it must come to rest and stay (an independent tester's finding: it crept down at 3e-5 m/s
// for as long as it ran, 3,000 times its springs' deflection over 4 s, at the default step and
// both laws; the tangential dashpot predicted the members' velocities from their own forces
// instead of their body's).
TEST(Clumps, AClumpBelowTheFrictionLimitOnAnInclineStaysAtRest) {
  for (const char* law : {"LINEAR", "HERTZ"}) {
    const double mu = 0.4, th = std::atan(0.99 * mu);
    std::ostringstream s;
    s.precision(17);
    s << R"({"name": "tripod",
  "materials": [{"name": "g", "density": 2500, "youngsModulus": 1e7, "poissonRatio": 0.25, "normalStiffness": 1e5},
                {"name": "w", "rigid": true}],
  "interactions": [{"a": "g", "b": "w", "restitution": 0.5, "friction": 0.4}, {"a": "g", "b": "g", "restitution": 0.5, "friction": 0.4}],
  "contact": {"normal": ")"
      << law << R"("},
  "clumpShapes": [{"name": "tri", "spheres": [{"center": {"x": 0.006}, "radius": 0.005},
                  {"center": {"x": -0.003, "y": 0.005196152422706633}, "radius": 0.005},
                  {"center": {"x": -0.003, "y": -0.00519615242270663}, "radius": 0.005}]}],
  "clumps": [{"shape": "tri", "material": "g", "position": {"z": 0.005}}],
  "walls": [{"material": "w", "plane": {"point": {}, "normal": {"z": 1}}}],
  "gravity": {"x": )"
      << 9.81 * std::sin(th) << R"(, "z": )" << -9.81 * std::cos(th) << R"(},
  "time": {"duration": 1.0},
  "outputs": {"everySteps": 1000000}})";
    Simulation sim = simulation_of(s.str());
    run_until(sim, 0.5);
    const double x_half = sim.state().bodies.x[0].x();
    run_until(sim, 1.0);
    const double crept = sim.state().bodies.x[0].x() - x_half;
    report(std::string(law) + " tripod at 0.99 mu: creep over 0.5 s (m)", crept, 0);
    EXPECT_LT(std::abs(crept), 1e-8) << law;
  }
}

// A dumbbell rolling like a log under a stiff rolling dashpot (EPSD, eta_r 1000) stops, and stays
// stopped. The dashpot's cap, the moment that stops the relative rolling within a step, took the
// rolling inertia I + m r^2 (Ai et al.'s eq. 13), 3.5 times a sphere's spin inertia: each step
// reversed the spin 2.5 times over and the springs sat at their limits; the dumbbell rolled on at
// 8e-6 m/s for ever and the springs gained 1.1e-3 of its energy (an independent tester's finding).
TEST(Clumps, ADumbbellUnderAStiffRollingDashpotStopsAndStays) {
  for (const char* law : {"LINEAR", "HERTZ"}) {
    std::ostringstream s;
    s << R"({"materials": [{"name": "g", "density": 2650, "youngsModulus": 5e8, "poissonRatio": 0.25, "normalStiffness": 1e5},
                {"name": "st", "rigid": true}],
  "interactions": [{"a": "g", "b": "g", "restitution": 0.5, "friction": 0.5, "rollingFriction": 0.3},
                   {"a": "g", "b": "st", "restitution": 0.5, "friction": 0.5, "rollingFriction": 0.3}],
  "contact": {"normal": ")"
      << law << R"(", "rolling": "EPSD", "rollingDampingRatio": 1000},
  "clumpShapes": [{"name": "db", "spheres": [{"center": {"x": -0.01}, "radius": 0.01}, {"center": {"x": 0.01}, "radius": 0.01}]}],
  "clumps": [{"shape": "db", "material": "g", "position": {"z": 0.0099999}, "velocity": {"y": 0.05}, "angularVelocity": {"x": -5.0}}],
  "walls": [{"material": "st", "plane": {"point": {}, "normal": {"z": 1}}}],
  "gravity": {"z": -9.81}, "time": {"duration": 1.0}, "outputs": {"everySteps": 1000000}})";
    Simulation sim = simulation_of(s.str());
    const double e0 = sim.kinetic_energy();
    run_until(sim, 0.5);
    const double energy_half = sim.mechanical_energy(), y_half = sim.state().bodies.x[0].y();
    run_until(sim, 1.0);
    const double moved = sim.state().bodies.x[0].y() - y_half;
    const double gained = (sim.mechanical_energy() - energy_half) / e0;
    report(std::string(law) + " dumbbell, eta_r 1000: moved over the last 0.5 s (m)", moved, 0);
    report(std::string(law) + " dumbbell, eta_r 1000: energy gained over it / initial", gained, 0);
    EXPECT_LT(std::abs(moved), 1e-8) << law;
    EXPECT_LT(gained, 1e-5) << law;
  }
}

TEST(Clumps, MembersAreTheirClumpsPartAndNeverTouchEachOther) {
  Simulation sim = simulation_of(clump_spec(0.5, Vec3::UnitZ(),
                                            R"({"shape": "pair", "material": "rock", "position": {"z": 0.05}},
                                               {"shape": "odd", "material": "rock", "position": {"x": 0.1, "z": 0.05}})",
                                            kG, 0.01));
  const std::vector<int> part = sim.fragments();
  const std::vector<int>& id = sim.particles().id;
  for (std::size_t i = 0; i < part.size(); ++i) EXPECT_EQ(part[i], id[i] < 2 ? 1 : 2);
  EXPECT_EQ(sim.state().neighbors.partner.size(), 0u) << "members of one clump are not neighbours";
}

// Masscenter.dat weighs each clump once, with its mass at its centroid (a member is not a body of
// the clump's whole mass): two clumps of different shapes, one of them turned.
TEST(Clumps, TheMassCentreCountsEachClumpOnce) {
  Simulation sim = simulation_of(clump_spec(0.5, Vec3::UnitZ(),
                                            R"({"shape": "pair", "material": "rock", "position": {"z": 0.05}},
                                               {"shape": "odd", "material": "rock", "position": {"x": 0.1, "z": 0.08},
                                                "rotationAxis": {"y": 1}, "rotationDegrees": 40})",
                                            kG, 0.01));
  const ClumpBodies& b = sim.state().bodies;
  ASSERT_EQ(b.x.size(), 2u);
  const Vec3 want = (b.mass[0] * b.x[0] + b.mass[1] * b.x[1]) / (b.mass[0] + b.mass[1]);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "dem_clump_mass_centre";
  std::filesystem::create_directories(dir);
  {
    StatisticsWriter writer(dir.string(), sim);
    writer.frame(sim);
  }
  std::ifstream in(dir / "Masscenter.dat");
  const auto rows = legacy::read_rows(in, 4);
  ASSERT_EQ(rows.frames.size(), 1u) << rows.problem;
  for (int d = 0; d < 3; ++d)
    EXPECT_NEAR(rows.frames[0][1 + d], want[d], 1e-7) << "axis " << d;  // 8 digits in the file
  std::filesystem::remove_all(dir);
}

// The automatic time step sees a clump's member as the body it moves: the contact time scales with
// the square root of the body's effective mass at the member, 1 / (1/M + d^2 / I_across) for the
// two-sphere clump (members d = 6 mm from the centroid on its long axis), not the member's own mass.
TEST(Clumps, TheTimeStepUsesTheBodysEffectiveMassAtAMember) {
  const Scene clumped =
      spec::to_scene(spec::parse_json(clump_spec(0.5, Vec3::UnitZ(),
                                                 R"({"shape": "pair", "material": "rock", "position": {"z": 0.05},
                                                                       "rotationAxis": {"y": 1}, "rotationDegrees": 35})",
                                                 kG, 0.01)));
  Scene single = clumped;
  single.clumps.clear();
  single.particles.resize(1);
  single.particles[0].clump = -1;
  const double t_clump = Simulation(clumped).time_step().contact_time,
               t_sphere = Simulation(single).time_step().contact_time;
  const ClumpInit& c = clumped.clumps[0];
  const double d = 0.006, m_sphere = 2650 * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR;
  const double m_eff = 1 / (1 / c.mass + d * d / c.moments[1]);  // moments ascending: [0] about the axis
  ASSERT_NEAR(c.moments[1], c.moments[2], 1e-12 * c.moments[2]);
  report("clump contact time / member sphere's", t_clump / t_sphere, std::sqrt(m_eff / m_sphere));
  EXPECT_NEAR(t_clump / t_sphere, std::sqrt(m_eff / m_sphere), 1e-9);
  EXPECT_GT(m_eff, m_sphere);
}

TEST(Clumps, ARunContinuedFromItsSavedStateIsTheUninterruptedRunBitForBit) {
  const std::string spec =
      clump_spec(0.5, Vec3::UnitZ(),
                 R"({"shape": "pair", "material": "rock", "position": {"z": 0.03}, "angularVelocity": {"y": 4}},
                                         {"shape": "odd", "material": "rock", "position": {"x": 0.005, "y": 0.002, "z": 0.07}})",
                 kG, 0.2);
  Simulation whole = simulation_of(spec), first = simulation_of(spec), second = simulation_of(spec);
  run_until(whole, 0.2);
  run_until(first, 0.1);
  std::stringstream saved;
  StateIO::write(first, saved);
  StateIO::read(second, saved);
  run_until(second, 0.2);
  for (int b = 0; b < 2; ++b) {
    EXPECT_EQ(whole.state().bodies.x[b], second.state().bodies.x[b]);
    EXPECT_EQ(whole.state().bodies.rotation[b].angular_momentum, second.state().bodies.rotation[b].angular_momentum);
  }
  EXPECT_EQ(whole.particles().x, second.particles().x);
}

// Clumps that fall in a heap, re-sorted at every neighbour build: the particles' order changes many
// times, and every member must stay where its body puts it (the bodies keep their members' list
// between steps and must follow each re-sort); a run continued from a state saved in that shuffled
// order is the uninterrupted run bit for bit.
TEST(Clumps, MembersFollowTheirBodiesThroughEveryReSortAndARestart) {
  std::ostringstream clumps;
  for (int k = 0; k < 48; ++k) {
    const double x = 0.03 * (k % 4), y = 0.03 * ((k / 4) % 3), z = 0.03 + 0.03 * (k / 12) + 0.004 * (k % 5);
    clumps << (k ? ", " : "") << R"({"shape": ")" << (k % 3 ? "odd" : "pair") << R"(", "material": "rock",
        "position": {"x": )"
           << x << R"(, "y": )" << y << R"(, "z": )" << z << R"(}, "rotationAxis": {"x": 1, "y": )" << k % 7
           << R"(}, "rotationDegrees": )" << 13 * k << R"(, "angularVelocity": {"z": )" << (k % 5) - 2 << "}}";
  }
  std::string spec = clump_spec(0.5, Vec3::UnitZ(), clumps.str(), kG, 0.1);
  spec.insert(spec.rfind('}'), R"(, "numerics": {"reorderInterval": 1, "searchInterval": 20})");
  Simulation whole = simulation_of(spec), first = simulation_of(spec), second = simulation_of(spec);
  run_until(first, 0.05);
  const Particles& p = first.particles();
  int moved = 0;
  for (std::size_t i = 0; i < p.size(); ++i) moved += p.id[i] != static_cast<int>(i);
  EXPECT_GT(moved, 20) << "the heap re-sorted the particles";
  const ClumpBodies& b = first.state().bodies;
  double worst_place = 0, worst_velocity = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int c = p.body[i];
    worst_place = std::max(worst_place, (p.x[i] - (b.x[c] + b.rotation[c].orientation * p.body_offset[i])).norm());
    const Vec3 w = angular_velocity(b.rotation[c], b.moments[c]);
    worst_velocity = std::max(worst_velocity, (p.v[i] - (b.v[c] + w.cross(p.x[i] - b.x[c]))).norm());
  }
  report("members' largest distance from where their bodies put them, m", worst_place, 0.0);
  report("members' largest velocity off their bodies' rigid motion, m/s", worst_velocity, 0.0);
  EXPECT_LT(worst_place, 1e-12);
  EXPECT_LT(worst_velocity, 1e-12);
  std::stringstream saved;
  StateIO::write(first, saved);
  StateIO::read(second, saved);
  run_until(whole, 0.1);
  run_until(second, 0.1);
  EXPECT_EQ(whole.particles().x, second.particles().x);
  EXPECT_EQ(whole.particles().v, second.particles().v);
}

// A clump thrown down in free fall with local damping alpha falls as a sphere does, at g (1 - alpha)
// from its first step: v(t) = v0 - g (1 - alpha) t. The first half kick took the force of the start's
// evaluation, which left a clump's undamped (dt = 0): every later velocity was off by alpha g dt / 2
// (7.4e-5 m/s here; an independent tester's find).
TEST(Clumps, AClumpThrownDownWithLocalDampingFallsAtGTimesOneMinusAlphaFromItsFirstStep) {
  std::string spec = clump_spec(0.5, Vec3::UnitZ(), R"({"shape": "odd", "material": "rock", "position": {"z": 1},
      "velocity": {"z": -1}})",
                                kG, 0.1);
  spec.insert(spec.rfind('}'), R"(, "numerics": {"localDamping": 0.3})");
  Simulation sim = simulation_of(spec);
  run_until(sim, 0.05);
  const double want = -1 - kG * (1 - 0.3) * sim.time();
  const double got = sim.state().bodies.v[0].z();
  report("a damped clump's fall speed against v0 - g (1 - alpha) t, m/s", got, want);
  EXPECT_NEAR(got, want, 1e-12);
  EXPECT_NEAR(sim.state().bodies.v[0].x(), 0, 1e-15);
}

TEST(Clumps, BadClumpsAreRefusedWithTheirPaths) {
  std::string bad =
      clump_spec(0.5, Vec3::UnitZ(),
                 R"({"shape": "nothing", "material": "rock"}, {"shape": "pair", "material": "lead"})", kG, 0.1);
  const std::string all = spec_problems(bad);
  ASSERT_FALSE(all.empty()) << "expected a SpecError";
  EXPECT_NE(all.find("clumps[0].shape: unknown clump shape \"nothing\""), std::string::npos) << all;
  EXPECT_NE(all.find("clumps[1].material"), std::string::npos) << all;
}

}  // namespace
}  // namespace dem::test::test_clumps
