// Run time against error for our engine (bench/accuracy/SCENARIOS.md): every validation scenario at
// a sweep of time steps dt = t_c / N, and once at the engine's automatic step (code "dem-default").
// Writes the CSV rows of SCENARIOS.md to stdout. The stepping loop is timed in-process; a short
// scenario is repeated until it has run for 20 ms, and its time divided.
//
// usage: bench_accuracy [--quick] [--only NAME,...]
#include <chrono>
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

// One measured quantity of a run, of a kind, with its closed-form value (0 for the many-body
// scenes, which compare with their own run at N = 800).
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
  double contact_time;                          // the reference t_c of the sweep, s
  std::function<Scene()> scene;                 // at the engine's automatic step
  std::function<Quantities(Simulation&)> measure;  // runs the simulation and measures
  bool many_body = false;                       // against its own run at N = 800
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
          [=] {
            Scene s = base(HertzNormal::kName, rho, e, nu, 1.0, 0.0);
            s.particles = {sphere({-r * 1.0001, 0, 0}, r, {10, 0, 0}), sphere({r * 1.0001, 0, 0}, r, {-10, 0, 0})};
            return s;
          },
          [=](Simulation& sim) {
            const Impact i = impact(sim);
            return Quantities{{kNormal, i.contact_time, t_c}, {kNormal, i.max_overlap, alpha}, {kNormal, i.max_force, force}};
          }};
}

Scenario normal_plane() {
  const double r = 0.1, rho = 2699, e = 7.0e10, nu = 0.3, v = 0.2;
  const double m = sphere_mass(rho, r), e_star = e / (1 - nu * nu);
  const double alpha = std::pow(15 * m * v * v / (16 * std::sqrt(r) * e_star), 0.4);
  const double force = 4.0 / 3.0 * e_star * std::sqrt(r) * std::pow(alpha, 1.5), t_c = 2.9432 * alpha / v;
  return {"normal-plane", t_c,
          [=] {
            Scene s = base(HertzNormal::kName, rho, e, nu, 1.0, 0.0);
            s.particles = {sphere({0, 0, r * 1.00001}, r, {0, 0, -v})};
            s.walls = {plane()};
            return s;
          },
          [=](Simulation& sim) {
            const Impact i = impact(sim);
            return Quantities{{kNormal, i.contact_time, t_c}, {kNormal, i.max_overlap, alpha}, {kNormal, i.max_force, force}};
          }};
}

// Test 3: Al oxide onto a plane at e = 0.5 (the validation suite sweeps e).
Scenario restitution(std::string_view law) {
  const double r = 0.0025, rho = 4000, e = 3.8e11, nu = 0.23, v = 3.9, kn = 1e7;
  const double m = sphere_mass(rho, r);
  const double t_c = law == HertzNormal::kName ? hertz_time(m, r, e / (1 - nu * nu), v) : kPi * std::sqrt(m / (2 * kn));
  return {"restitution-" + std::string(law == HertzNormal::kName ? "hertz" : "linear"), t_c,
          [=] {
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
  const double t_c = law == HertzNormal::kName ? hertz_time(m, r, e_mod / (1 - nu * nu), v) : kPi * std::sqrt(m / (2 * kn));
  const double vt_after = vt - mu * (1 + e) * vn, spin = 5 * mu * (1 + e) * vn / (2 * r);
  const double angle = std::atan((std::tan(th) - 3.5 * mu * (1 + e)) / e);
  return {"oblique-" + std::string(law == HertzNormal::kName ? "hertz" : "linear"), t_c,
          [=] {
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
  const double t_c = law == HertzNormal::kName ? hertz_time(m_eff, r_eff, e_star, vn) : kPi * std::sqrt(m_eff / (pair ? kn : 2 * kn));
  const double pn = (1 + e) * m_eff * vn;
  return {std::string(pair ? "sliding-pair-" : "sliding-plane-") + (law == HertzNormal::kName ? "hertz" : "linear"), t_c,
          [=] {
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
            return Quantities{{kNormal, dv.z(), dvn}, {kTangential, dv.x(), dvt}, {kRotational, std::abs(dw.y()), std::abs(dwy)}};
          }};
}

// Ai et al. (2011): a sphere rolling on a plane stops after 7 v0^2 / (10 mu_r g).
Scenario rolling(std::string_view model) {
  const double r = 0.005, rho = 2500, v0 = 0.5, mu_r = 0.1, g = 9.81;
  const double m = sphere_mass(rho, r);
  const double t_c = hertz_time(m, r, 5e9 / (1 - 0.25 * 0.25), 0.1);
  const double want = 7 * v0 * v0 / (10 * mu_r * g);
  return {"rolling-" + std::string(model == CdtRolling::kName ? "cdt" : "epsd"), t_c,
          [=] {
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
          [=] {
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
          [=] {
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
  return {"clump-rotation", t_c, [=] { return scene; },
          [=](Simulation& sim) {
            const double e0 = sim.kinetic_energy();
            while (sim.time() < 0.5) sim.step();
            // the energy (exact: e0) and the orientation's turn, whose reference is the run at N = 3200
            const Eigen::AngleAxisd turn(sim.state().bodies.rotation[0].orientation);
            return Quantities{{kRotational, sim.kinetic_energy(), e0}, {kRotational, turn.angle(), 0}};
          }};
}

// The many-body scenes: quantities at the end, against the same scene at N = 800.
// 2,000 spheres on a 10 x 10 x 20 cubic lattice fall and spread on a floor (SCENARIOS.md, 6).
Scenario collapse(double duration) {
  const double r = 0.002, rho = 2500, kn = 1e4;
  const double m = sphere_mass(rho, r), t_c = kPi * std::sqrt(m / 2 / kn);
  Scenario s{"collapse", t_c,
             [=] {
               Scene s = base(LinearNormal::kName, rho, 0, 0, 0.5, 0.5, kn);
               s.gravity = {0, 0, -9.81};
               for (int k = 0; k < 20; ++k)
                 for (int j = 0; j < 10; ++j)
                     for (int i = 0; i < 10; ++i)  // nudged sideways by 10 um: a perfect lattice never spreads
                     s.particles.push_back(sphere({(i - 4.5) * 2.02 * r + 1e-5 * std::sin(1.7 * i + 2.3 * j + 3.1 * k),
                                                   (j - 4.5) * 2.02 * r + 1e-5 * std::cos(2.9 * i + 1.3 * j + 0.7 * k),
                                                   r + 2e-5 + k * 2.02 * r},
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
          [=] {
            Scene s = base(LinearNormal::kName, rho, 0, 0, 0.5, 0.5, kn);
            for (int k = 0; k < 13; ++k)
              for (int j = 0; j < 13; ++j)
                for (int i = 0; i < 13; ++i) s.particles.push_back(sphere(Vec3(i, j, k) * 2 * r + Vec3(0, 0, r + 1e-4), r, {0, 0, -2}));
            s.walls = {plane()};
            BondSettings b;
            b.youngs_modulus = 2e7;
            b.tensile_strength = b.shear_strength = 1.5e5;
            b.strength_spread = 0.3;
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

// One run at dt (0: the engine's automatic step), repeated until 20 ms have passed.
Timed timed_run(const Scenario& sc, double dt) {
  using Clock = std::chrono::steady_clock;
  Timed out;
  int repeats = 0;
  double total = 0;
  do {
    Scene s = sc.scene();
    if (dt > 0) {
      s.time.dt = dt;
      s.time.allow_unstable_dt = true;
    }
    Simulation sim(std::move(s));
    out.dt = sim.dt();
    const auto start = Clock::now();
    out.q = sc.measure(sim);
    total += std::chrono::duration<double>(Clock::now() - start).count();
    ++repeats;
  } while (total < 0.02 && !sc.many_body);
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

// `code` dem: the error against the closed form (the many-body scenes: their run at N = 800);
// dem-self: against this engine's own run at N = 3200 (the discretisation error alone, for the
// orders of convergence); dem-default: the automatic step.
void print_row(const std::string& code, const Scenario& sc, const Timed& t, const Errors& e) {
  const double worst = std::max({e.normal, e.tangential, e.rotational});
  std::printf("%s,%s,%.6e,%.4g,%.6e,%s,%s,%s,%s\n", sc.name.c_str(), code.c_str(), t.dt, sc.contact_time / t.dt,
              t.seconds, cell(e.normal).c_str(), cell(e.tangential).c_str(), cell(e.rotational).c_str(), cell(worst).c_str());
  std::fflush(stdout);
}

int main(int argc, char** argv) {
  bool quick = false;
  std::set<std::string> only;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--quick") quick = true;
    else if (arg == "--only" && a + 1 < argc) {
      std::stringstream list(argv[++a]);
      for (std::string name; std::getline(list, name, ',');) only.insert(name);
    } else {
      std::fprintf(stderr, "usage: bench_accuracy [--quick] [--only NAME,...]\n");
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
  const std::vector<double> sweep = quick ? std::vector<double>{20, 50} : std::vector<double>{10, 20, 50, 100, 200, 400};
  std::printf("scenario,code,dt,steps_per_contact,seconds,error_normal,error_tangential,error_rotational,error\n");
  for (const Scenario& sc : all) {
    if (!only.empty() && !only.count(sc.name)) continue;
    std::fprintf(stderr, "%s\n", sc.name.c_str());
    const Timed self = timed_run(sc, sc.contact_time / (sc.many_body ? (quick ? 100 : 800) : (quick ? 200 : 3200)));
    for (double n : sweep) {
      const Timed t = timed_run(sc, sc.contact_time / n);
      print_row("dem", sc, t, errors_of(t.q, sc.many_body ? &self.q : nullptr));
      if (!sc.many_body) print_row("dem-self", sc, t, errors_of(t.q, &self.q));
    }
    const Timed d = timed_run(sc, 0);
    print_row("dem-default", sc, d, errors_of(d.q, sc.many_body ? &self.q : nullptr));
  }
  return 0;
}

}  // namespace
}  // namespace dem::bench

int main(int argc, char** argv) { return dem::bench::main(argc, argv); }
