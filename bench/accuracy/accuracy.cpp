// Run time against error for our engine (bench/accuracy/SCENARIOS.md): every validation scenario at
// a sweep of time steps dt = t_c / N, and once at the engine's automatic step (code "dem-default").
// Writes the CSV rows of SCENARIOS.md to stdout. The stepping loop is timed in-process; a short
// scenario is repeated until it has run for 20 ms, and its time divided.
//
// The many-body scenes are chaotic: a nudge of 1e-9 m to one sphere of the collapse changes its
// quantities at 0.15 s as much as going from dt = t_c/800 to t_c/50 does. So they run as ensembles
// of `--seeds` scenes that differ only in their random details (the collapse's nudges, the block's
// bond strengths), each at every dt and at the reference N = 800; their rows (one per run, the
// measured values themselves) go to `--runs FILE` in the format of SCENARIOS.md, and
// bench/accuracy/run compares the ensembles' means against the reference ensemble's, with the
// scatter of the means as the floor below which no error can be seen.
//
// usage: bench_accuracy [--quick] [--only NAME,...] [--seeds K] [--runs FILE]
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "clumps/rigid_rotation.hpp"
#include "contact/models.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"

namespace dem::bench {
namespace {

constexpr double kPi = std::numbers::pi;

enum Kind { kNormal, kTangential, kRotational };

// One measured quantity of a run, of a kind, with its closed-form value (0 where there is none:
// the many-body scenes, compared with their own ensemble at N = 800, and the clump's turn).
struct Q {
  Kind kind;
  double value;
  double reference;
};
using Quantities = std::vector<Q>;

// The relative errors of a run by kind (against `reference` where given, else the quantities'
// own references); a negative value: that kind is not measured.
struct Errors {
  double normal = -1, tangential = -1, rotational = -1;
};

struct Scenario {
  std::string name;
  double contact_time;                             // the reference t_c of the sweep, s
  std::function<Scene(int seed)> scene;            // at the engine's automatic step; seed: many-body only
  std::function<Quantities(Simulation&)> measure;  // runs the simulation and measures
  bool many_body = false;                          // an ensemble against its own ensemble at N = 800
};

double sphere_mass(double rho, double r) { return rho * 4.0 / 3.0 * kPi * r * r * r; }

Scene base(std::string_view law, double rho, double e_mod, double nu, double restitution, double mu, double kn = 0) {
  Scene s;
  s.materials.push_back({"p", rho, e_mod, nu, kn, false});
  s.materials.push_back({"wall", 0, 0, 0, 0, true});
  s.interactions.assign(4, Interaction{restitution, mu, 0});
  s.contact.normal = std::string(law);
  s.time.steps = 100000000;
  s.outputs.animation = false;
  return s;
}

ParticleInit sphere(const Vec3& x, double r, const Vec3& v = Vec3::Zero(), const Vec3& w = Vec3::Zero()) {
  ParticleInit p;
  p.position = x;
  p.radius = r;
  p.velocity = v;
  p.angular_velocity = w;
  return p;
}

WallInit plane(const Vec3& normal = Vec3::UnitZ(), const Vec3& point = Vec3::Zero()) {
  return WallInit{"plane", 1, PlaneShape{point, normal.normalized()}, {}, {}};
}

double rel(double got, double want) { return std::abs(got - want) / std::abs(want); }

// Overlap of the first contact: particles 0 and 1, or particle 0 and the plane z = 0.
double overlap(const Simulation& sim) {
  const Particles& p = sim.particles();
  if (p.size() >= 2) return p.radius[0] + p.radius[1] - (p.x[0] - p.x[1]).norm();
  return p.radius[0] - p.x[0].z();
}

// Steps through one impact: touch to parting (interpolated), the largest overlap and normal force.
struct Impact {
  double contact_time = 0, max_overlap = 0, max_force = 0;
};
Impact impact(Simulation& sim) {
  Impact r;
  double prev = overlap(sim), start = -1;
  for (int k = 0; k < 10000000; ++k) {
    const double t0 = sim.time();
    sim.step();
    const double d = overlap(sim);
    r.max_overlap = std::max(r.max_overlap, d);
    if (d > 0) {
      const auto pairs = sim.pair_contacts();
      double f = 0;
      for (const auto& c : pairs) f = std::max(f, c.fn);
      for (const auto& c : sim.wall_contacts()) f = std::max(f, c.fn);
      r.max_force = std::max(r.max_force, f);
    }
    if (prev <= 0 && d > 0) start = t0 + sim.dt() * (-prev) / (d - prev);
    if (prev > 0 && d <= 0 && start >= 0) {
      r.contact_time = t0 + sim.dt() * prev / (prev - d) - start;
      return r;
    }
    prev = d;
  }
  return r;
}

double hertz_time(double m_eff, double r_eff, double e_star, double v) {
  const double alpha = std::pow(15 * m_eff * v * v / (16 * std::sqrt(r_eff) * e_star), 0.4);
  return 2.9432 * alpha / v;
}

// ------------------------------------------------------------------------------------------------
// The scenarios

Scenario normal_pair() {
  const double r = 0.01, rho = 2800, e = 4.8e10, nu = 0.2, v = 20;
  const double m_eff = sphere_mass(rho, r) / 2, r_eff = r / 2, e_star = e / (2 * (1 - nu * nu));
  const double alpha = std::pow(15 * m_eff * v * v / (16 * std::sqrt(r_eff) * e_star), 0.4);
  const double force = 4.0 / 3.0 * e_star * std::sqrt(r_eff) * std::pow(alpha, 1.5), t_c = 2.9432 * alpha / v;
  return {"normal-pair", t_c,
          [=](int) {
            Scene s = base(HertzNormal::kName, rho, e, nu, 1.0, 0.0);
            s.particles = {sphere({-r * 1.0001, 0, 0}, r, {10, 0, 0}), sphere({r * 1.0001, 0, 0}, r, {-10, 0, 0})};
            return s;
          },
          [=](Simulation& sim) {
            const Impact i = impact(sim);
            return Quantities{
                {kNormal, i.contact_time, t_c}, {kNormal, i.max_overlap, alpha}, {kNormal, i.max_force, force}};
          }};
}

Scenario normal_plane() {
  const double r = 0.1, rho = 2699, e = 7.0e10, nu = 0.3, v = 0.2;
  const double m = sphere_mass(rho, r), e_star = e / (1 - nu * nu);
  const double alpha = std::pow(15 * m * v * v / (16 * std::sqrt(r) * e_star), 0.4);
  const double force = 4.0 / 3.0 * e_star * std::sqrt(r) * std::pow(alpha, 1.5), t_c = 2.9432 * alpha / v;
  return {"normal-plane", t_c,
          [=](int) {
            Scene s = base(HertzNormal::kName, rho, e, nu, 1.0, 0.0);
            s.particles = {sphere({0, 0, r * 1.00001}, r, {0, 0, -v})};
            s.walls = {plane()};
            return s;
          },
          [=](Simulation& sim) {
            const Impact i = impact(sim);
            return Quantities{
                {kNormal, i.contact_time, t_c}, {kNormal, i.max_overlap, alpha}, {kNormal, i.max_force, force}};
          }};
}

// Test 3: Al oxide onto a plane at e = 0.5 (the validation suite sweeps e).
Scenario restitution(std::string_view law) {
  const double r = 0.0025, rho = 4000, e = 3.8e11, nu = 0.23, v = 3.9, kn = 1e7;
  const double m = sphere_mass(rho, r);
  const double t_c = law == HertzNormal::kName ? hertz_time(m, r, e / (1 - nu * nu), v) : kPi * std::sqrt(m / (2 * kn));
  return {"restitution-" + std::string(law == HertzNormal::kName ? "hertz" : "linear"), t_c,
          [=](int) {
            Scene s = base(law, rho, e, nu, 0.5, 0.0, kn);
            s.particles = {sphere({0, 0, r * 1.0001}, r, {0, 0, -v})};
            s.walls = {plane()};
            return s;
          },
          [=](Simulation& sim) {
            impact(sim);
            return Quantities{{kNormal, sim.particles().v[0].z() / v, 0.5}};
          }};
}

// Test 4 at 40 degrees: tangential rebound, rebound angle of the contact point, spin.
Scenario oblique(std::string_view law) {
  const double r = 0.0025, rho = 4000, e_mod = 3.8e11, nu = 0.23, v = 3.9, mu = 0.092, e = 0.98, kn = 1e7;
  const double th = 40 * kPi / 180, vn = v * std::cos(th), vt = v * std::sin(th);
  const double m = sphere_mass(rho, r);
  const double t_c =
      law == HertzNormal::kName ? hertz_time(m, r, e_mod / (1 - nu * nu), v) : kPi * std::sqrt(m / (2 * kn));
  const double vt_after = vt - mu * (1 + e) * vn, spin = 5 * mu * (1 + e) * vn / (2 * r);
  const double angle = std::atan((std::tan(th) - 3.5 * mu * (1 + e)) / e);
  return {"oblique-" + std::string(law == HertzNormal::kName ? "hertz" : "linear"), t_c,
          [=](int) {
            Scene s = base(law, rho, e_mod, nu, e, mu, kn);
            s.particles = {sphere({0, 0, r * 1.0001}, r, {vt, 0, -vn})};
            s.walls = {plane()};
            return s;
          },
          [=](Simulation& sim) {
            impact(sim);
            const Vec3 vel = sim.particles().v[0], w = sim.particles().w[0];
            const Vec3 vc = vel + w.cross(Vec3(0, 0, -r));
            return Quantities{{kTangential, vel.x(), vt_after},
                              {kTangential, std::atan2(vc.x(), vc.z()), angle},
                              {kRotational, w.norm(), spin}};
          }};
}

// Test 6 (and 8, two spheres, with `pair`): velocity and spin changes against impact theory.
Scenario sliding(std::string_view law, bool pair) {
  const double r = 0.1, rho = 2699, e_mod = 7.0e10, nu = 0.3, e = 0.5, kn = 1e7;
  const double mu = pair ? 0.05 : 0.4, vn = 0.2, vt = pair ? 0.15 : 1.0;
  const double m = sphere_mass(rho, r), inertia = 0.4 * m * r * r;
  const double m_eff = pair ? m * (m / 8) / (m + m / 8) : m, r_eff = pair ? r * (r / 2) / (1.5 * r) : r;
  const double e_star = pair ? e_mod / (2 * (1 - nu * nu)) : e_mod / (1 - nu * nu);
  const double t_c =
      law == HertzNormal::kName ? hertz_time(m_eff, r_eff, e_star, vn) : kPi * std::sqrt(m_eff / (pair ? kn : 2 * kn));
  const double pn = (1 + e) * m_eff * vn;
  return {std::string(pair ? "sliding-pair-" : "sliding-plane-") + (law == HertzNormal::kName ? "hertz" : "linear"),
          t_c,
          [=](int) {
            Scene s = base(law, rho, e_mod, nu, e, mu, kn);
            if (pair) {
              s.particles = {sphere({0, 0, -r * 1.00001}, r, {vt / 2, 0, vn / 2}),
                             sphere({0, 0, r / 2 * 1.00002}, r / 2, {-vt / 2, 0, -vn / 2})};
            } else {
              s.particles = {sphere({0, 0, r * 1.00001}, r, {vt, 0, -vn})};
              s.walls = {plane()};
            }
            return s;
          },
          [=](Simulation& sim) {
            const Vec3 v0 = sim.particles().v[0], w0 = sim.particles().w[0];
            impact(sim);
            // sphere 0 (the lower one of the pair moves up into the other: its normal is -z)
            const double sign = pair ? -1 : 1;
            const Vec3 dv = sim.particles().v[0] - v0, dw = sim.particles().w[0] - w0;
            const double dvn = sign * pn / m, dvt = -mu * pn / m, dwy = mu * pn * r / inertia;
            return Quantities{
                {kNormal, dv.z(), dvn}, {kTangential, dv.x(), dvt}, {kRotational, std::abs(dw.y()), std::abs(dwy)}};
          }};
}

// Ai et al. (2011): a sphere rolling on a plane stops after 7 v0^2 / (10 mu_r g).
Scenario rolling(std::string_view model) {
  const double r = 0.005, rho = 2500, v0 = 0.5, mu_r = 0.1, g = 9.81;
  const double m = sphere_mass(rho, r);
  const double t_c = hertz_time(m, r, 5e9 / (1 - 0.25 * 0.25), 0.1);
  const double want = 7 * v0 * v0 / (10 * mu_r * g);
  return {"rolling-" + std::string(model == CdtRolling::kName ? "cdt" : "epsd"), t_c,
          [=](int) {
            Scene s = base(HertzNormal::kName, rho, 5e9, 0.25, 0.5, 0.5);
            s.contact.rolling = std::string(model);
            for (Interaction& in : s.interactions) in.rolling_friction = mu_r;
            s.gravity = {0, 0, -g};
            s.particles = {sphere({0, 0, r * 0.99999}, r, {v0, 0, 0}, {0, v0 / r, 0})};
            s.walls = {plane()};
            return s;
          },
          [=](Simulation& sim) {
            while (sim.particles().v[0].norm() > 1e-5 && sim.time() < 2) sim.step();
            return Quantities{{kRotational, sim.particles().x[0].x(), want}};
          }};
}

// A sphere rolling down a 20-degree incline made of 700 triangles: a = 5/7 g sin(theta).
Scenario incline_mesh() {
  const double r = 0.005, rho = 2500, g = 9.81, th = 20 * kPi / 180;
  const double m = sphere_mass(rho, r);
  const double t_c = kPi * std::sqrt(m / (2 * 1e5));
  return {"incline-mesh", t_c,
          [=](int) {
            Scene s = base(LinearNormal::kName, rho, 0, 0, 0.5, 0.5, 1e5);
            s.gravity = {g * std::sin(th), 0, -g * std::cos(th)};  // the incline: tilted gravity
            MeshShape mesh;
            const int nu = 70, nv = 10;
            const double du = 0.01, dv = 0.01;
            for (int j = 0; j <= nv; ++j)
              for (int i = 0; i <= nu; ++i) mesh.vertices.push_back({-0.05 + i * du, -0.05 + j * dv, 0});
            auto at = [&](int i, int j) { return j * (nu + 1) + i; };
            for (int j = 0; j < nv; ++j)
              for (int i = 0; i < nu; ++i) {
                mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
              }
            WallInit w;
            w.material = 1;
            w.shape = mesh;
            s.walls = {w};
            s.particles = {sphere({0, 0.002, r * 0.9999}, r)};
            return s;
          },
          [=](Simulation& sim) {
            while (sim.time() < 0.1) sim.step();
            const double t1 = sim.time(), v1 = sim.particles().v[0].x();
            while (sim.time() < 0.4) sim.step();
            const double a = (sim.particles().v[0].x() - v1) / (sim.time() - t1);
            return Quantities{{kTangential, a, 5.0 / 7.0 * g * std::sin(th)}};
          }};
}

// A bonded pair, one held: the free sphere oscillates at omega = sqrt(kn A / m).
Scenario bond_pair() {
  const double r = 0.01, eb = 1e8, rho = 2500;
  const double m = sphere_mass(rho, r), area = kPi * r * r, k = eb / (2 * r) * area;
  const double period = 2 * kPi * std::sqrt(m / k);
  // a swing of 1e-5 m/s / omega = 8e-10 m, far inside the gap of 1e-6 m
  return {"bond-axial", period / 2,
          [=](int) {
            Scene s = base(LinearNormal::kName, rho, 0, 0, 0.5, 0.0, 1e4);
            // bonded across a gap of 1e-4 r: only the bond acts, the contact never touches
            s.particles = {sphere({0, 0, 0}, r), sphere({2 * r * 1.00005, 0, 0}, r, {1e-5, 0, 0})};
            s.particles[0].fixed = true;
            BondSettings b;
            b.youngs_modulus = eb;
            b.tensile_strength = b.shear_strength = 1e12;
            s.bonds = b;
            return s;
          },
          [=](Simulation& sim) {
            double previous = 0, measured = 0;
            for (int k = 0; k < 10000000 && measured == 0; ++k) {
              sim.step();
              const double x = sim.particles().x[1].x() - 2 * r * 1.00005;
              if (k > 3 && previous < 0 && x >= 0) measured = sim.time() - sim.dt() * x / (x - previous);
              previous = x;
            }
            return Quantities{{kNormal, measured, period}};
          }};
}

// A free asymmetric three-sphere clump spinning: its energy over 0.5 s (torque-free motion).
Scenario clump_rotation() {
  const std::string json = R"({"materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}],
    "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5}],
    "clumpShapes": [{"name": "odd", "spheres": [{"center": {"x": -0.008}, "radius": 0.01},
      {"center": {"x": 0.006, "y": 0.004}, "radius": 0.008}, {"center": {"z": 0.007}, "radius": 0.006}]}],
    "clumps": [{"shape": "odd", "material": "rock", "angularVelocity": {"x": 3, "y": 40, "z": 1}}],
    "time": {"steps": 100000000}})";
  const Scene scene = spec::to_scene(spec::parse_json(json));
  // the body's fastest turn sets the step: 1 / |w| s per radian
  const double t_c = 1.0 / 40;
  return {"clump-rotation", t_c, [=](int) { return scene; },
          [=](Simulation& sim) {
            const double e0 = sim.kinetic_energy();
            while (sim.time() < 0.5) sim.step();
            // the energy (exact: e0) and the orientation's turn, whose reference is the run at N = 3200
            const Eigen::AngleAxisd turn(sim.state().bodies.rotation[0].orientation);
            return Quantities{{kRotational, sim.kinetic_energy(), e0}, {kRotational, turn.angle(), 0}};
          }};
}

// The many-body scenes: quantities at the end, as ensembles against the same ensemble at N = 800.
// 2,000 spheres on a 10 x 10 x 20 cubic lattice fall and spread on a floor (SCENARIOS.md, 6).
Scenario collapse(double duration) {
  const double r = 0.002, rho = 2500, kn = 1e4;
  const double m = sphere_mass(rho, r), t_c = kPi * std::sqrt(m / 2 / kn);
  Scenario s{
      "collapse", t_c,
      [=](int seed) {
        Scene s = base(LinearNormal::kName, rho, 0, 0, 0.5, 0.5, kn);
        s.gravity = {0, 0, -9.81};
        // nudged sideways by 10 um (a perfect lattice never spreads), in a pattern the seed shifts
        const double a = 1.37 * seed, b = 2.11 * seed;
        for (int k = 0; k < 20; ++k)
          for (int j = 0; j < 10; ++j)
            for (int i = 0; i < 10; ++i)
              s.particles.push_back(sphere(
                  {(i - 4.5) * 2.02 * r + 1e-5 * std::sin(1.7 * i + 2.3 * j + 3.1 * k + a),
                   (j - 4.5) * 2.02 * r + 1e-5 * std::cos(2.9 * i + 1.3 * j + 0.7 * k + b), r + 2e-5 + k * 2.02 * r},
                  r));
        s.walls = {plane()};
        s.numerics.threads = 1;
        return s;
      },
      [=](Simulation& sim) {
        while (sim.time() < duration) sim.step();
        const Particles& p = sim.particles();
        double z = 0, spread = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
          z += p.x[i].z();
          spread += p.x[i].x() * p.x[i].x() + p.x[i].y() * p.x[i].y();
        }
        return Quantities{{kNormal, z / p.size(), 0}, {kTangential, std::sqrt(spread / p.size()), 0}};
      },
      true};
  return s;
}

// 2,197 bonded spheres thrown at a plane (tests/validation/test_bonded_block.cpp, 1.5e5 Pa).
Scenario bonded_block() {
  const double r = 0.005, rho = 2600, kn = 1e5;
  const double m = sphere_mass(rho, r), t_c = kPi * std::sqrt(m / 2 / kn);
  return {"bonded-block", t_c,
          [=](int seed) {
            Scene s = base(LinearNormal::kName, rho, 0, 0, 0.5, 0.5, kn);
            for (int k = 0; k < 13; ++k)
              for (int j = 0; j < 13; ++j)
                for (int i = 0; i < 13; ++i)
                  s.particles.push_back(sphere(Vec3(i, j, k) * 2 * r + Vec3(0, 0, r + 1e-4), r, {0, 0, -2}));
            s.walls = {plane()};
            BondSettings b;
            b.youngs_modulus = 2e7;
            b.tensile_strength = b.shear_strength = 1.5e5;
            b.strength_spread = 0.3;
            b.seed = 11 + seed;  // the bonds' strengths
            s.bonds = b;
            s.numerics.threads = 1;
            return s;
          },
          [=](Simulation& sim) {
            while (sim.time() < 0.02) sim.step();
            const BondCounts c = sim.bonds().counts();
            const std::vector<int> parts = sim.fragments();
            const std::set<int> distinct(parts.begin(), parts.end());
            return Quantities{{kNormal, static_cast<double>(c.tension + c.shear), 0},
                              {kTangential, static_cast<double>(distinct.size()), 0}};
          },
          true};
}

// ------------------------------------------------------------------------------------------------

struct Timed {
  Quantities q;
  double seconds = 0;
  double dt = 0;
};

// One run at dt (0: the engine's automatic step). A many-body run is measured and timed at once
// (its measurement is a pass at the end). A single-body run's measurement looks at every step, so
// it is timed apart, as the peers' are: fresh runs of the same number of steps with nothing but
// the steps, repeated until 20 ms have passed.
Timed timed_run(const Scenario& sc, double dt, int seed = 0) {
  using Clock = std::chrono::steady_clock;
  auto make = [&] {
    Scene s = sc.scene(seed);
    if (dt > 0) {
      s.time.dt = dt;
      s.time.allow_unstable_dt = true;
    }
    return Simulation(std::move(s));
  };
  Timed out;
  Simulation measured = make();
  out.dt = measured.dt();
  auto start = Clock::now();
  out.q = sc.measure(measured);
  out.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (sc.many_body) return out;
  const std::int64_t steps = measured.step_count();
  int repeats = 0;
  double total = 0;
  do {
    Simulation sim = make();
    start = Clock::now();
    for (std::int64_t k = 0; k < steps; ++k) sim.step();
    total += std::chrono::duration<double>(Clock::now() - start).count();
    ++repeats;
  } while (total < 0.02);
  out.seconds = total / repeats;
  return out;
}

// The errors by kind: against each quantity's reference, or (`against`) another run's values.
Errors errors_of(const Quantities& q, const Quantities* against) {
  Errors e;
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (!against && q[k].reference == 0) continue;  // no closed form: measured against a run only
    const double want = against ? (*against)[k].value : q[k].reference;
    const double err = want != 0 ? rel(q[k].value, want) : std::abs(q[k].value);
    double& slot = q[k].kind == kNormal ? e.normal : q[k].kind == kTangential ? e.tangential : e.rotational;
    slot = std::max(slot, err);
  }
  return e;
}

std::string cell(double e) {
  if (e < 0) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6e", e);
  return buf;
}

// `code` dem: the error against the closed form; dem-self: against this engine's own run at
// N = 3200 (the discretisation error alone, for the orders of convergence); dem-default: the
// automatic step.
void print_row(const std::string& code, const Scenario& sc, const Timed& t, const Errors& e) {
  const double worst = std::max({e.normal, e.tangential, e.rotational});
  std::printf("%s,%s,%.6e,%.4g,%.6e,%s,%s,%s,%s\n", sc.name.c_str(), code.c_str(), t.dt, sc.contact_time / t.dt,
              t.seconds, cell(e.normal).c_str(), cell(e.tangential).c_str(), cell(e.rotational).c_str(),
              cell(worst).c_str());
  std::fflush(stdout);
}

// A many-body run's row for --runs: the values themselves, by kind (one quantity of each kind).
void print_run(std::FILE* out, const std::string& code, const Scenario& sc, int seed, const Timed& t) {
  std::string values[3];
  for (const Q& q : t.q) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10e", q.value);
    values[q.kind] = buf;
  }
  std::fprintf(out, "%s,%s,%d,%.6e,%.4g,%.6e,%s,%s,%s\n", sc.name.c_str(), code.c_str(), seed, t.dt,
               sc.contact_time / t.dt, t.seconds, values[0].c_str(), values[1].c_str(), values[2].c_str());
  std::fflush(out);
}

int main(int argc, char** argv) {
  bool quick = false;
  int seeds = 6;
  std::string runs_path;
  std::set<std::string> only;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--quick")
      quick = true;
    else if (arg == "--only" && a + 1 < argc) {
      std::stringstream list(argv[++a]);
      for (std::string name; std::getline(list, name, ',');) only.insert(name);
    } else if (arg == "--seeds" && a + 1 < argc) {
      seeds = std::max(1, std::atoi(argv[++a]));
    } else if (arg == "--runs" && a + 1 < argc) {
      runs_path = argv[++a];
    } else {
      std::fprintf(stderr, "usage: bench_accuracy [--quick] [--only NAME,...] [--seeds K] [--runs FILE]\n");
      return 2;
    }
  }
  std::vector<Scenario> all = {normal_pair(), normal_plane()};
  for (std::string_view law : {HertzNormal::kName, LinearNormal::kName}) {
    all.push_back(restitution(law));
    all.push_back(oblique(law));
    all.push_back(sliding(law, false));
    all.push_back(sliding(law, true));
  }
  all.push_back(rolling(CdtRolling::kName));
  all.push_back(rolling(EpsdRolling::kName));
  all.push_back(incline_mesh());
  all.push_back(bond_pair());
  all.push_back(clump_rotation());
  all.push_back(collapse(quick ? 0.02 : 0.15));
  all.push_back(bonded_block());
  const std::vector<double> sweep =
      quick ? std::vector<double>{20, 50} : std::vector<double>{10, 20, 50, 100, 200, 400};
  std::FILE* runs = nullptr;
  if (!runs_path.empty() && !(runs = std::fopen(runs_path.c_str(), "w"))) {
    std::fprintf(stderr, "bench_accuracy: cannot write %s\n", runs_path.c_str());
    return 1;
  }
  if (runs)
    std::fprintf(runs,
                 "scenario,code,seed,dt,steps_per_contact,seconds,value_normal,value_tangential,value_rotational\n");
  std::printf("scenario,code,dt,steps_per_contact,seconds,error_normal,error_tangential,error_rotational,error\n");
  for (const Scenario& sc : all) {
    if (!only.empty() && !only.count(sc.name)) continue;
    std::fprintf(stderr, "%s\n", sc.name.c_str());
    if (sc.many_body) {
      if (!runs) continue;  // their rows are runs, not errors
      std::vector<double> steps_per_contact = sweep;
      steps_per_contact.push_back(quick ? 100 : 800);  // the reference ensemble
      steps_per_contact.push_back(0);                  // the automatic step
      for (double n : steps_per_contact)
        for (int seed = 0; seed < seeds; ++seed)
          print_run(runs, n > 0 ? "dem" : "dem-default", sc, seed,
                    timed_run(sc, n > 0 ? sc.contact_time / n : 0, seed));
      continue;
    }
    const Timed self = timed_run(sc, sc.contact_time / (quick ? 200 : 3200));
    for (double n : sweep) {
      const Timed t = timed_run(sc, sc.contact_time / n);
      print_row("dem", sc, t, errors_of(t.q, nullptr));
      print_row("dem-self", sc, t, errors_of(t.q, &self.q));
    }
    const Timed d = timed_run(sc, 0);
    print_row("dem-default", sc, d, errors_of(d.q, nullptr));
  }
  if (runs) std::fclose(runs);
  return 0;
}

}  // namespace
}  // namespace dem::bench

int main(int argc, char** argv) { return dem::bench::main(argc, argv); }
