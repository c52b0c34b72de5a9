// Bonds under rigid rotation: a bonded body that turns as a whole carries only the bond forces
// its rotation needs (the centripetal pull), at any time step, for parallel and contact bonds.
// Bonds once opened by about omega dt R per radian turned (half-step velocities mixed with
// end-of-step geometry): a spinning cluster lost its energy to the contacts or broke apart.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bonds/bond_models.hpp"
#include "core/rotation.hpp"
#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_bond_rotation {
namespace {

constexpr double kR = 0.01, kDensity = 2600, kOmega = 20;

BondSettings strong_bonds(bool parallel) {
  BondSettings b;
  b.model = parallel ? ParallelBond::kName : ContactBond::kName;
  b.youngs_modulus = 5e6;  // a tenth of the landslide case's (a longer step, the same physics)
  b.tensile_strength = 1e6;
  b.shear_strength = 2e6;
  return b;
}

// Particles spinning with the body: v = w x (x - centre), spin w.
void spin(Scene& s, const Vec3& centre, const Vec3& w) {
  for (ParticleInit& p : s.particles) {
    p.velocity = w.cross(p.position - centre);
    p.angular_velocity = w;
  }
}

// A rigid motion of a bonded pair (any rotation, any centre, any translation, in one go) leaves
// the bond unloaded to round-off; and a loaded pair moved rigidly carries the same loads, turned.
TEST(BondRotation, ARigidMotionLoadsNoBondAndTurnsTheLoadsOfALoadedOne) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random_turn = [&](double max_angle) {
    return rotation_by(max_angle * std::abs(u(rng)) * Vec3(u(rng), u(rng), u(rng)).normalized());
  };
  for (bool parallel : {true, false}) {
    for (int trial = 0; trial < 50; ++trial) {
      BondSettings settings = strong_bonds(parallel);
      settings.tensile_strength = settings.shear_strength = 1e30;
      const BondEnd i0{Vec3(u(rng), u(rng), u(rng)) * 0.01, random_turn(3.1), 0.01};
      const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
      const BondEnd j0{i0.x - (0.017 + 1e-5 * u(rng)) * dir, random_turn(3.1), 0.007};
      Bond b = bond_between(settings, i0.radius, j0.radius, 1.0);
      glue(b, i0, j0);
      const Quat turn = random_turn(3.14159);
      const Vec3 centre = Vec3(u(rng), u(rng), u(rng)), shift = Vec3(u(rng), u(rng), u(rng));
      auto moved = [&](const BondEnd& e) {
        return BondEnd{centre + turn * (e.x - centre) + shift, turn * e.q, e.radius};
      };
      const double scale = b.kn * b.geometry.area * 0.017;  // the force of a 100% stretch
      const BondLoad rigid = bond_load(b, moved(i0), moved(j0), 0);
      EXPECT_LT(rigid.force.norm(), 1e-12 * scale) << trial;
      EXPECT_LT(rigid.moment_i.norm() + rigid.moment_j.norm(), 1e-12 * scale * 0.017) << trial;
      // deformed: i stretched, sheared and turned a little; then the whole pair moved rigidly
      const BondEnd i1{i0.x + 1e-5 * Vec3(u(rng), u(rng), u(rng)), random_turn(1e-3) * i0.q, i0.radius};
      const BondLoad loaded = bond_load(b, i1, j0, 0);
      const BondLoad loaded_moved = bond_load(b, moved(i1), moved(j0), 0);
      EXPECT_LT((loaded_moved.force - turn * loaded.force).norm(), 1e-9 * loaded.force.norm()) << trial;
      EXPECT_LT((loaded_moved.moment_i - turn * loaded.moment_i).norm(), 1e-9 * loaded.moment_i.norm()) << trial;
    }
  }
}

// Two touching spheres bonded end to end, turning about their middle at kOmega for 1 s (20 rad):
// the bond pulls with m w^2 r (stretching it by 6e-7 m) and nothing more, whatever the step.
double spinning_pair_force(bool parallel, double dt_scale) {
  Scene s = base_scene(LinearNormal::kName, kDensity, 0, 0, 0.3, 0.5, 5e5);
  s.particles.push_back(sphere({-kR, 0, 0}, kR));
  s.particles.push_back(sphere({kR, 0, 0}, kR));
  spin(s, Vec3::Zero(), {0, 0, kOmega});
  s.bonds = strong_bonds(parallel);
  {
    Simulation probe(s);
    s.time.dt = probe.dt() * dt_scale;
  }
  Simulation sim(s);
  const double m = sphere_mass(kDensity, kR);
  const double centripetal = m * kOmega * kOmega * kR;
  double worst = 0;
  while (sim.time() < 1.0) {
    sim.step();
    const Bond& b = sim.bonds().bonds()[0];
    EXPECT_EQ(b.state, BondBreak::Intact);
    if (b.state != BondBreak::Intact) break;
    // tension is a negative normal force; the pull oscillates about m w^2 r (it started at zero)
    worst = std::max(worst, std::abs(-b.normal_force - centripetal));
  }
  const std::string label = std::string(parallel ? "parallel" : "contact") + " bond, spinning pair, dt x" +
                            std::to_string(dt_scale) + ": largest departure of the bond force from m w^2 r";
  report(label, worst, 0.0);
  EXPECT_LT(worst, 1.05 * centripetal) << label;  // the pull rings about m w^2 r with its own amplitude
  return worst;
}

TEST(BondRotation, ASpinningPairCarriesOnlyTheCentripetalPull) {
  for (bool parallel : {true, false}) {
    const double at_dt = spinning_pair_force(parallel, 1.0);
    const double at_quarter = spinning_pair_force(parallel, 0.25);
    EXPECT_NEAR(at_dt, at_quarter, 0.05 * at_dt) << (parallel ? "parallel" : "contact");
  }
}

// A body of touching bonded spheres (friction 0.5, restitution 0.3: the landslide case's) spinning at
// kOmega about a tilted axis for 1 s: it keeps its kinetic energy and every bond. Parallel bonds: a
// 3 x 3 x 3 cubic block (54 bonds). Contact bonds carry no moment, so spheres may roll on each other
// at no cost: a cubic block of them is a mechanism, which spinning drives out of shape (it gains
// moment of inertia at no cost in bond energy; its contacts then rub); the body is a tetrahedral
// pile of 10 (24 bonds), all of whose faces are triangles, in which no sphere can roll alone.
TEST(BondRotation, ASpinningBondedBodyKeepsItsEnergyAndItsBonds) {
  for (bool parallel : {true, false}) {
    Scene s = base_scene(LinearNormal::kName, kDensity, 0, 0, 0.3, 0.5, 5e5);
    if (parallel) {
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) s.particles.push_back(sphere(2 * kR * Vec3(i, j, k), kR));
    } else {
      const double h = 2 * kR * std::sqrt(2.0 / 3.0);
      for (int layer = 0; layer < 3; ++layer) {
        const Vec3 offset = layer * Vec3(kR, kR / std::sqrt(3.0), h);
        for (int j = 0; j < 3 - layer; ++j)
          for (int i = 0; i + j < 3 - layer; ++i)
            s.particles.push_back(sphere(offset + 2 * kR * Vec3(i + 0.5 * j, 0.5 * std::sqrt(3.0) * j, 0), kR));
      }
    }
    Vec3 centre = Vec3::Zero();
    for (const ParticleInit& p : s.particles) centre += p.position / static_cast<double>(s.particles.size());
    spin(s, centre, Vec3(1, 2, 3).normalized() * kOmega);
    s.bonds = strong_bonds(parallel);
    Simulation sim(s);
    const std::size_t bonds = sim.bonds().bonds().size();
    ASSERT_EQ(bonds, parallel ? 54u : 24u);
    const double e0 = sim.kinetic_energy();
    while (sim.time() < 1.0) sim.step();
    const double e = sim.kinetic_energy();
    const std::string label = parallel ? "parallel bonds, spinning block" : "contact bonds, spinning tetrahedral pile";
    report(label + ": kinetic energy after 1 s / at the start", e / e0, 1.0);
    EXPECT_NEAR(e / e0, 1.0, 1e-3) << label;
    EXPECT_EQ(sim.bonds().counts().intact, static_cast<int>(bonds)) << label;
  }
}

// Two bonded spheres of 10 and 5 mm, a hair apart (only the bond acts), rolling on each other like
// gears (spins -10 and +20 rad/s: their surfaces move together at the bond), with nothing else
// touching them: the bond's springs are all there is, so kinetic plus bond energy stays and so does
// the angular momentum. A contact bond's shear force once turned each sphere about the line of
// centres instead of about its own attachment point, which rolls away from that line: the pair
// gained 5% of its energy in 0.05 s (10:7 radii 1.3%), at any time step, until the guard stopped it.
TEST(BondRotation, SpheresRollingOnEachOtherKeepTheirEnergy) {
  for (bool parallel : {true, false}) {
    Scene s = base_scene(LinearNormal::kName, kDensity, 0, 0, 0.3, 0.5, 1e5);
    const double r1 = 0.01, r2 = 0.005, gap = 4e-6;
    s.particles.push_back(sphere({0, 0, 0}, r1, Vec3::Zero(), {0, 0, -10}));
    s.particles.push_back(sphere({r1 + r2 + gap, 0, 0}, r2, Vec3::Zero(), {0, 0, 20}));
    s.bonds = strong_bonds(parallel);
    s.bonds->youngs_modulus = 1e8;
    s.bonds->tensile_strength = s.bonds->shear_strength = 1e12;
    Simulation sim(s);
    ASSERT_EQ(sim.bonds().bonds().size(), 1u);
    auto energy = [&] { return sim.kinetic_energy() + sim.bonds().elastic_energy(); };
    const double e0 = energy();
    const Vec3 l0 = sim.angular_momentum();
    double worst = 0, worst_l = 0;
    while (sim.time() < 0.1) {
      sim.step();
      worst = std::max(worst, std::abs(energy() - e0) / e0);
      worst_l = std::max(worst_l, (sim.angular_momentum() - l0).norm() / l0.norm());
    }
    const std::string label = std::string(parallel ? "parallel" : "contact") + " bond, spheres rolling on each other";
    report(label + ": largest relative energy change", worst, 0.0);
    EXPECT_LT(worst, 1e-3) << label;
    EXPECT_LT(worst_l, 1e-12) << label;
    EXPECT_EQ(sim.bonds().counts().intact, 1) << label;
  }
}

}  // namespace
}  // namespace dem::test::test_bond_rotation
