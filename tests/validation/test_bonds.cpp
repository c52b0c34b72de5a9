// Parallel bonds, two-particle checks of validation.md section 5 (Potyondy & Cundall 2004): axial,
// shear, bending and twist stiffness, and the four break loads, whichever particle is listed first;
// then a bonded pair in a simulation, which must oscillate at the bond's frequency.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "bonds/bond_law.hpp"
#include "core/rotation.hpp"
#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_bonds {
namespace {

constexpr double kRa = 0.01, kRb = 0.01, kEb = 1e8, kShearRatio = 0.4, kSigma = 2e6, kTau = 3e6;

Bond make_bond() {
  Bond b;
  b.i = 0;
  b.j = 1;
  b.geometry = BondGeometry::of(std::min(kRa, kRb));
  b.kn = kEb / (kRa + kRb);
  b.ks = kShearRatio * b.kn;
  b.tensile_strength = kSigma;
  b.shear_strength = kTau;
  return b;
}

// The motion of the two checks: body A (radius kRa), along `axis` from body B (radius kRb, at the
// origin), moves with `velocity`; A and B turn about their own centres in opposite senses, each by
// half of the relative rotation `spin` t: their points at the bond centre then move together (the
// radii are equal), so a turn bends or twists the bond without shearing or stretching it.
// `flip`: the bond lists B first (the roles of i and j swapped).
struct Drive {
  Vec3 axis;
  Vec3 velocity;
  Vec3 spin;
};

// Drives the bond for `steps` steps of dt (or until it breaks); returns the last load carried.
BondLoad drive(Bond& b, const Drive& d, bool flip, int steps, double dt) {
  auto a_at = [&](double t) {
    return BondEnd{(kRa + kRb) * d.axis + d.velocity * t, rotation_by(0.5 * t * d.spin), kRa};
  };
  auto b_at = [&](double t) { return BondEnd{Vec3::Zero(), rotation_by(-0.5 * t * d.spin), kRb}; };
  if (flip)
    glue(b, b_at(0), a_at(0));
  else
    glue(b, a_at(0), b_at(0));
  BondLoad last{};
  for (int k = 1; k <= steps; ++k) {
    const double t = k * dt;
    const BondLoad load = flip ? bond_load(b, b_at(t), a_at(t), t) : bond_load(b, a_at(t), b_at(t), t);
    if (b.state != BondBreak::Intact) break;
    last = load;
  }
  return last;
}

const double kL = kRa + kRb;
const BondGeometry kG = BondGeometry::of(0.01);

class TwoParticleBond : public ::testing::TestWithParam<bool> {};

TEST_P(TwoParticleBond, StiffnessesMatchTheBeamFormulas) {
  const bool flip = GetParam();
  const Vec3 n(0, 0, 1);
  const double dt = 1e-6, du = 1e-7, dth = 1e-5;
  const int steps = 100;
  {  // axial: pulling i away by du: tension F = Eb A du / L
    Bond b = make_bond();
    drive(b, {n, (du / (steps * dt)) * n, Vec3::Zero()}, flip, steps, dt);
    report("bond axial force", -b.normal_force, kEb * kG.area * du / kL);
    EXPECT_NEAR(-b.normal_force, kEb * kG.area * du / kL, 5e-3 * kEb * kG.area * du / kL);
  }
  {  // shear: F = ks A du
    Bond b = make_bond();
    drive(b, {n, (du / (steps * dt)) * Vec3::UnitX(), Vec3::Zero()}, flip, steps, dt);
    const double want = kShearRatio * kEb / kL * kG.area * du;
    report("bond shear force", b.shear_force.norm(), want);
    EXPECT_NEAR(b.shear_force.norm(), want, 5e-3 * want);
  }
  {  // bending: M = Eb I dth / L
    Bond b = make_bond();
    drive(b, {n, Vec3::Zero(), (dth / (steps * dt)) * Vec3::UnitY()}, flip, steps, dt);
    const double want = kEb * kG.inertia * dth / kL;
    report("bond bending moment", b.bending.norm(), want);
    EXPECT_NEAR(b.bending.norm(), want, 5e-3 * want);
  }
  {  // twist: M = ks J dth
    Bond b = make_bond();
    drive(b, {n, Vec3::Zero(), (dth / (steps * dt)) * n}, flip, steps, dt);
    const double want = kShearRatio * kEb / kL * kG.polar * dth;
    report("bond twisting moment", b.twist.norm(), want);
    EXPECT_NEAR(b.twist.norm(), want, 5e-3 * want);
  }
}

TEST_P(TwoParticleBond, BreaksAtTheFourStrengthLoads) {
  const bool flip = GetParam();
  const Vec3 n(0, 0, 1);
  const double dt = 1e-6;
  const int steps = 200000;  // slow loading: the load at the break is resolved to ~1e-4
  const double rb = kG.radius;
  {
    Bond b = make_bond();
    const double u_break = kSigma * kL / kEb;
    const BondLoad last = drive(b, {n, (2 * u_break / (steps * dt)) * n, Vec3::Zero()}, flip, steps, dt);
    EXPECT_EQ(b.state, BondBreak::Tension);
    report("bond break: tension force", last.force.norm(), kSigma * kG.area);
    EXPECT_NEAR(last.force.norm(), kSigma * kG.area, 5e-3 * kSigma * kG.area);
  }
  {
    Bond b = make_bond();
    const double th_break = kSigma * kL / (kEb * rb);
    drive(b, {n, Vec3::Zero(), (2 * th_break / (steps * dt)) * Vec3::UnitX()}, flip, steps, dt);
    EXPECT_EQ(b.state, BondBreak::Tension);
    // the moment carried at the break: the last intact step's, one increment below
    const double want = kSigma * kG.inertia / rb;
    report("bond break: bending moment", b.bending.norm(), want);
    EXPECT_NEAR(b.bending.norm(), want, 5e-3 * want);
  }
  {
    Bond b = make_bond();
    const double th_break = kTau * kL / (kShearRatio * kEb * rb);
    drive(b, {n, Vec3::Zero(), (2 * th_break / (steps * dt)) * n}, flip, steps, dt);
    EXPECT_EQ(b.state, BondBreak::Shear);
    const double want = kTau * kG.polar / rb;
    report("bond break: twisting moment", b.twist.norm(), want);
    EXPECT_NEAR(b.twist.norm(), want, 5e-3 * want);
  }
  {
    Bond b = make_bond();
    const double u_break = kTau * kL / (kShearRatio * kEb);
    drive(b, {n, (2 * u_break / (steps * dt)) * Vec3::UnitY(), Vec3::Zero()}, flip, steps, dt);
    EXPECT_EQ(b.state, BondBreak::Shear);
    const double want = kTau * kG.area;
    report("bond break: shear force", b.shear_force.norm(), want);
    EXPECT_NEAR(b.shear_force.norm(), want, 5e-3 * want);
  }
}

INSTANTIATE_TEST_SUITE_P(EitherParticleFirst, TwoParticleBond, ::testing::Values(false, true),
                         [](const auto& info) { return std::string(info.param ? "j_first" : "i_first"); });

// Two bonded spheres in a simulation, one held: the free one oscillates along the bond at
// omega = sqrt(kn A / m). They are bonded across a gap of 1e-4 radii, which the oscillation (2e-9 m)
// never closes: only the bond acts.
TEST(BondedPair, OscillatesAtTheBondFrequency) {
  constexpr double kGap = 1e-6;
  Scene s = base_scene(LinearNormal::kName, 2500, 1e8, 0.25, 0.5, 0.0, 1e4);
  s.particles.push_back(sphere({0, 0, 0}, kRa));
  s.particles.back().fixed = true;
  s.particles.push_back(sphere({kRa + kRb + kGap, 0, 0}, kRb, {1e-5, 0, 0}));
  BondSettings bonds;
  bonds.youngs_modulus = kEb;
  bonds.tensile_strength = 1e12;
  bonds.shear_strength = 1e12;
  s.bonds = bonds;
  Simulation sim(s);
  ASSERT_EQ(sim.bonds().bonds().size(), 1u);
  EXPECT_GT(sim.time_step().bond_time, 0);
  const double m = sphere_mass(2500, kRb);
  const double omega = std::sqrt(kEb / kL * kG.area / m);  // kn = Eb / (RA + RB), whatever the gap
  // the first time the free sphere comes back through its start moving outwards: one period
  double previous = 0, period = 0;
  for (int k = 0; k < 1000000 && period == 0; ++k) {
    sim.step();
    const double x = sim.particles().x[1].x() - (kRa + kRb + kGap);
    if (k > 10 && previous < 0 && x >= 0) period = sim.time() - sim.dt() * x / (x - previous);
    previous = x;
  }
  const double want = 2 * std::numbers::pi / omega;
  report("bonded pair: period of the axial oscillation", period, want);
  EXPECT_NEAR(period, want, 5e-3 * want);
  EXPECT_EQ(sim.bonds().counts().intact, 1);
}

// An undamped bonded lattice vibrating (validation: energy within 1e-4 over 1e5 steps). The spheres
// stand 0.04% of a radius apart, bonded across the gap but never touching, so only the bonds act.
TEST(BondedLattice, KeepsItsEnergyOver1e5Steps) {
  const double r = 0.005;
  Scene s = base_scene(LinearNormal::kName, 2600, 1e8, 0.25, 1.0, 0.0, 1e5);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        s.particles.push_back(sphere(2 * r * 1.0002 * Vec3(i, j, k), r, 1e-4 * Vec3(u(rng), u(rng), u(rng)),
                                     1e-2 * Vec3(u(rng), u(rng), u(rng))));
  BondSettings bonds;
  bonds.youngs_modulus = 2e7;
  bonds.shear_stiffness_ratio = 0.5;
  bonds.tensile_strength = bonds.shear_strength = 1e12;
  s.bonds = bonds;
  s.time.dt_fraction = 0.005;  // as the energy test: Verlet's bounded energy wobble is (w dt)^2 / 8
  Simulation sim(s);
  ASSERT_EQ(sim.bonds().bonds().size(), 54u);
  auto energy = [&] { return sim.kinetic_energy() + sim.bonds().elastic_energy(); };
  const double e0 = energy();
  double worst = 0;
  for (int k = 0; k < 100000; ++k) {
    sim.step();
    if (k % 100 == 0) worst = std::max(worst, std::abs(energy() - e0) / e0);
  }
  report("bonded lattice: largest relative energy change over 1e5 steps", worst, 0.0);
  EXPECT_LT(worst, 1e-4);
  EXPECT_EQ(sim.bonds().counts().intact, 54);
}

// A cantilever of N = 10 parallel bonds, clamped at one end (a held sphere), tip load P (validation
// section 5): delta = P L^3 / (3 Eb I) (1 - 1/(4 N^2)) + N P / (ks A), L = N l. Local damping
// brings it to rest; the deflection must not change when the step is halved.
double cantilever_deflection(double dt_scale, double* want_out) {
  constexpr int kBonds = 10;
  const double r = 0.005, l = 2 * r * 1.0001, eb = 1e8, ratio = 0.5, load = 0.01;
  Scene s = base_scene(LinearNormal::kName, 2500, 1e8, 0.25, 0.5, 0.0, 1e4);
  for (int k = 0; k <= kBonds; ++k) s.particles.push_back(sphere({k * l, 0, 0}, r));
  s.particles.front().fixed = true;
  s.particles.back().force = {0, 0, -load};
  BondSettings bonds;
  bonds.youngs_modulus = eb;
  bonds.shear_stiffness_ratio = ratio;
  bonds.tensile_strength = bonds.shear_strength = 1e12;
  s.bonds = bonds;
  s.numerics.local_damping = 0.7;
  {
    Simulation probe(s);
    s.time.dt = probe.dt() * dt_scale;
  }
  Simulation sim(s);
  EXPECT_EQ(sim.bonds().bonds().size(), static_cast<std::size_t>(kBonds));
  while (sim.time() < 0.4) sim.step();
  const BondGeometry g = BondGeometry::of(r);
  const double length = kBonds * l, kn = eb / (2 * r);
  *want_out = load * length * length * length / (3 * eb * g.inertia) * (1 - 1.0 / (4 * kBonds * kBonds)) +
              kBonds * load / (ratio * kn * g.area);
  EXPECT_LT(std::abs(sim.particles().v[kBonds].z()), 1e-6) << "the tip has not come to rest";
  return -sim.particles().x[kBonds].z();
}

TEST(BondedCantilever, TipDeflectionMatchesBeamTheoryAndNotTheStep) {
  double want = 0;
  const double delta = cantilever_deflection(1.0, &want);
  const double delta_half = cantilever_deflection(0.5, &want);
  report("cantilever tip deflection", delta, want);
  report("cantilever tip deflection, half the step", delta_half, want);
  EXPECT_NEAR(delta, want, 0.02 * want);
  EXPECT_NEAR(delta_half, delta, 1e-3 * delta);
}

}  // namespace
}  // namespace dem::test::test_bonds
