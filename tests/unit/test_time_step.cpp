// Tests of the time-step choice (engine/sim/time_step.hpp) against the closed forms of
// /work/shared/spec/validation.md: the linear contact time (section 2), the Hertz contact time
// (section 1) and the Rayleigh time (section 6).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "sim/kernel_select.hpp"
#include "core/errors.hpp"
#include "sim/time_step.hpp"
#include "spec/spec_loader.hpp"

namespace dem {
namespace {

constexpr double kPi = std::numbers::pi;

double sphere_volume(double r) { return 4.0 / 3.0 * kPi * r * r * r; }

// Two equal spheres of one linear material: each of mass 2e-3 kg, so m* = m / 2 = 1e-3 kg, and
// k_n = 1e5 N/m (eq. 4 of two equal springs gives the spring itself), e = 0.5.
Scene linear_pair_scene() {
  const double r = 0.01;
  Scene s;
  Material m;
  m.name = "stuff";
  m.density = 2e-3 / sphere_volume(r);
  m.normal_stiffness = 1e5;
  s.materials = {m};
  s.interactions = {Interaction{0.5, 0.3, 0}};
  s.contact.normal = LinearNormal::kName;
  s.contact.no_tensile_force = false;  // validation.md section 2's zeta(e) is the law with tension
  for (double x : {0.0, 0.03}) {
    ParticleInit p;
    p.position = Vec3(x, 0, 0);
    p.radius = r;
    s.particles.push_back(p);
  }
  s.time.steps = 10;
  return s;
}

// validation.md section 2 from its own formulas: zeta(e), omega0 = sqrt(k / m*), t_c.
double linear_contact_time(double e, double k, double m_eff) {
  const double l = std::log(e);
  const double zeta = -l / std::sqrt(kPi * kPi + l * l);
  return kPi / std::sqrt(k / m_eff * (1 - zeta * zeta));
}

TimeStepReport choose(const Scene& s) { return choose_time_step(s, *select_kernel(s, !s.walls.empty())); }

// The message of the SceneError a scene's time step raises, or "" if it is accepted.
std::string rejection(const Scene& s) {
  try {
    choose(s);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// ---------------------------------------------------------------------------------------------
// Linear law

TEST(TimeStep, LinearContactTimeIsTheValidationExample) {
  const TimeStepReport r = choose(linear_pair_scene());
  EXPECT_NEAR(r.contact_time, 3.2172e-4, 1e-8);  // validation.md section 2, 5 digits
  EXPECT_NEAR(r.contact_time, linear_contact_time(0.5, 1e5, 1e-3), 1e-12 * r.contact_time);
  EXPECT_EQ(r.rayleigh_time, 0.0);  // Hertz only
}

TEST(TimeStep, AutomaticStepIsOneFiftiethOfTheContactTime) {
  const TimeStepReport r = choose(linear_pair_scene());
  EXPECT_TRUE(r.automatic);
  EXPECT_NEAR(r.dt, linear_contact_time(0.5, 1e5, 1e-3) / 50, 1e-12 * r.dt);
}

TEST(TimeStep, DtFractionScalesTheAutomaticStep) {
  Scene s = linear_pair_scene();
  s.time.dt_fraction = 0.01;
  EXPECT_NEAR(choose(s).dt, linear_contact_time(0.5, 1e5, 1e-3) / 100, 1e-12 * 3.2e-6);
}

// One sphere of the pair's and a rigid material for walls (elastic against the sphere).
Scene sphere_and_rigid_material() {
  Scene s = linear_pair_scene();
  s.particles.pop_back();
  Material steel;
  steel.name = "steel";
  steel.rigid = true;
  s.materials.push_back(steel);
  s.interactions = {Interaction{0.5, 0.3, 0}, Interaction{1.0, 0.3, 0}, Interaction{1.0, 0.3, 0}, Interaction{1, 0, 0}};
  return s;
}

TEST(TimeStep, ContactWithARigidWallCounts) {
  // One sphere of 2e-3 kg on a rigid wall: m* = m, and eq. 4 with a rigid partner gives K_n = 2 k:
  // omega0 = 1e4 / s as for the pair. The wall contact is elastic (zeta = 0), so it is shorter than
  // the damped sphere-sphere one: t_c = pi / omega0 = 3.1416e-4 s, not 3.2172e-4 s.
  Scene s = sphere_and_rigid_material();
  WallInit floor;
  floor.material = 1;
  floor.shape = PlaneShape{};
  s.walls = {floor};
  EXPECT_NEAR(choose(s).contact_time, linear_contact_time(1.0, 2e5, 2e-3), 1e-12 * 3.2e-4);
  EXPECT_NEAR(choose(s).contact_time, kPi * 1e-4, 1e-15);
}

// The sphere of 2e-3 kg under a plate of the rigid material, cyclically loaded, of mass `mass`.
Scene sphere_under_loaded_plate(double mass) {
  Scene s = sphere_and_rigid_material();
  WallInit plate;
  plate.material = 1;
  plate.shape =
      PlateShape{{Vec3(-0.1, -0.1, 0.02), Vec3(0.1, -0.1, 0.02), Vec3(0.1, 0.1, 0.02), Vec3(-0.1, 0.1, 0.02)}};
  LoadControl load;
  load.kind = LoadControl::Kind::Cyclic;
  load.mass = mass;
  load.direction = Vec3(0, 0, -1);
  load.f_max = 1;
  load.frequency = 5;
  load.cycles = 1;
  plate.load = load;
  s.walls = {plate};
  return s;
}

// A wall moved by its load (a cyclic load's mass M) is a body of its own: a contact with it moves
// m* = m M / (m + M). A plate of 1e-6 kg on spheres of 2e-3 kg rang on their contacts faster than
// the step resolves, and was stopped after 938 steps (an independent tester): a wall too light for
// the step is refused, naming its mass and the least it needs; a heavy one keeps the particles' step.
TEST(TimeStep, ALoadedWallTooLightForTheStepIsRefused) {
  Scene s = sphere_under_loaded_plate(1e-6);
  const std::string why = rejection(s);
  EXPECT_NE(why.find("walls[0].load.mass: 1e-06 kg is too light for the time step"), std::string::npos) << why;
  // the least mass it names passes: (m* / m)^(1/2) = 10 dt / t_c = 1/5 for the linear law, so m* = m / 25
  EXPECT_NE(why.find("at least 8.3"), std::string::npos) << why;  // 8.333e-05 kg, rounded up
  s.walls[0].load->mass = 8.34e-5;
  EXPECT_EQ(rejection(s), "");
  s.walls[0].load->mass = 40;  // a sleeper: the particles' own step, as without the load
  EXPECT_NEAR(choose(s).dt, kPi * 1e-4 / 50, 1e-15);
  s.time.allow_unstable_dt = true;
  s.walls[0].load->mass = 1e-6;
  EXPECT_EQ(rejection(s), "");
}

// At the largest dtFraction, 0.1, the step gives the particles' contact with a wall held still
// exactly 10 steps, and a loaded wall of any finite mass slightly fewer: a 40 kg sleeper on 2 g
// spheres was refused, and a 2 kg plate on 0.1 g spheres was told to weigh "at least 1 kg" (an
// independent check). A wall within 1e-3 of the held-still contact's time passes; a light one is still
// refused, with a least mass that passes.
TEST(TimeStep, AHeavyLoadedWallPassesAtTheLargestStepFraction) {
  Scene s = sphere_under_loaded_plate(40);
  s.time.dt_fraction = 0.1;
  EXPECT_EQ(rejection(s), "");
  EXPECT_NEAR(choose(s).dt, kPi * 1e-4 / 10, 1e-15);  // the particles' own step
  s.walls[0].load->mass = 2;
  EXPECT_EQ(rejection(s), "");
  s.walls[0].load->mass = 0.1;  // 50 times the sphere: 1% off the held-still contact's time
  const std::string why = rejection(s);
  EXPECT_NE(why.find("walls[0].load.mass: 0.1 kg is too light for the time step"), std::string::npos) << why;
  // (m* / m)^(1/2) >= 1 - 1e-3 for the linear law: m M / (m + M) >= 0.998001 m, so M >= 0.99900 kg
  EXPECT_NE(why.find("at least 0.999 kg"), std::string::npos) << why;
  s.walls[0].load->mass = 1.0;
  EXPECT_EQ(rejection(s), "");
}

// The least mass a refusal names passes when given, whatever the step and the law, and with
// particles of two materials: it was rounded to the nearest of three digits (refused again when
// given), and named for the first material whose particle it failed, so that the next refusal named
// the other's (an independent check). With a given dt the advice is a smaller dt.
TEST(TimeStep, TheLeastMassARefusalNamesPasses) {
  auto scene = [](const std::string& law, const std::string& time) {
    return spec::to_scene(spec::parse_json(R"({"materials": [
        {"name": "g", "density": 2500, "normalStiffness": 1e5, "youngsModulus": 1e7, "poissonRatio": 0.25},
        {"name": "steel", "rigid": true},
        {"name": "h", "density": 7500, "normalStiffness": 4e5, "youngsModulus": 2e7, "poissonRatio": 0.2}],
      "interactions": [{"a": "g", "b": "g", "restitution": 0.5, "friction": 0.3},
                       {"a": "g", "b": "steel", "restitution": 0.5, "friction": 0.3},
                       {"a": "h", "b": "h", "restitution": 0.7, "friction": 0.3},
                       {"a": "g", "b": "h", "restitution": 0.6, "friction": 0.3},
                       {"a": "h", "b": "steel", "restitution": 0.4, "friction": 0.3}],
      "contact": {"normal": ")" + law + R"("},
      "particles": [{"position": {"z": 0.005}, "radius": 0.005, "material": "g"},
                    {"position": {"x": 0.02, "z": 0.005}, "radius": 0.005, "material": "h"}],
      "walls": [{"name": "press", "material": "steel",
                 "plate": {"c1": {"x": -0.01, "y": -0.01, "z": 0.0101}, "c2": {"x": 0.04, "y": -0.01, "z": 0.0101},
                           "c3": {"x": 0.04, "y": 0.04, "z": 0.0101}, "c4": {"x": -0.01, "y": 0.04, "z": 0.0101}},
                 "load": {"mass": 1, "cyclic": {"fMin": 0.1, "fMax": 1, "frequency": 50, "cycles": 2}}}],
      "gravity": {"z": -9.81}, "time": )" + time +
                                           "}"));
  };
  for (const std::string law : {"LINEAR", "HERTZ"})
    for (const std::string time : {R"({"steps": 10, "dtFraction": 0.1})", R"({"steps": 10, "dtFraction": 0.09})",
                                   R"({"steps": 10, "dtFraction": 0.05})", R"({"steps": 10, "dt": 2e-6})"}) {
      Scene s = scene(law, time);
      s.walls[0].load->mass = 1e-9;  // light enough for every case (1e-6 kg passes Hertz at dt 2e-6 s)
      const std::string why = rejection(s);
      const std::size_t at = why.find("give the wall a mass of at least ");
      ASSERT_NE(at, std::string::npos) << law << " " << time << ": " << why;
      const double least = std::stod(why.substr(at + 33));
      EXPECT_NE(why.find(s.time.dt > 0 ? "or a smaller time.dt" : "or a smaller time.dtFraction"), std::string::npos)
          << why;
      EXPECT_EQ(why.find("time.dtFraction") != std::string::npos, s.time.dt == 0) << why;
      s.walls[0].load->mass = least;
      EXPECT_EQ(rejection(s), "") << law << " " << time << ": the " << least << " kg named is refused";
    }
}

TEST(TimeStep, LightestParticlesSetTheContactTime) {
  // Adding a sphere of half the radius (1/8 of the mass) shortens the shortest contact: small-small
  // with m* = m / 16 = 1.25e-4 kg.
  Scene s = linear_pair_scene();
  ParticleInit small = s.particles[0];
  small.position = Vec3(0.1, 0, 0);
  small.radius = 0.005;
  s.particles.push_back(small);
  EXPECT_NEAR(choose(s).contact_time, linear_contact_time(0.5, 1e5, 2e-3 / 16), 1e-12 * 3.2e-4);
}

TEST(TimeStep, GivenDtAboveTheStableLimitNamesTimeDt) {
  Scene s = linear_pair_scene();
  const double t_c = linear_contact_time(0.5, 1e5, 1e-3);
  s.time.dt = t_c / 5;  // 5 steps per contact cannot resolve it
  const std::string message = rejection(s);
  EXPECT_NE(message.find("time.dt"), std::string::npos) << message;
  EXPECT_NE(message.find("allowUnstableDt"), std::string::npos) << message;
}

TEST(TimeStep, GivenDtAboveTheLimitIsAcceptedWhenAllowed) {
  Scene s = linear_pair_scene();
  s.time.dt = linear_contact_time(0.5, 1e5, 1e-3) / 5;
  s.time.allow_unstable_dt = true;
  const TimeStepReport r = choose(s);
  EXPECT_FALSE(r.automatic);
  EXPECT_EQ(r.dt, s.time.dt);
}

TEST(TimeStep, GivenDtBelowTheLimitIsUsedAsGiven) {
  Scene s = linear_pair_scene();
  s.time.dt = linear_contact_time(0.5, 1e5, 1e-3) / 20;
  const TimeStepReport r = choose(s);
  EXPECT_FALSE(r.automatic);
  EXPECT_EQ(r.dt, s.time.dt);
  EXPECT_GE(r.stable_limit, r.dt);
  // ... and the automatic step itself is always accepted when given back.
  Scene again = linear_pair_scene();
  again.time.dt = choose(linear_pair_scene()).dt;
  EXPECT_NO_THROW(choose(again));
}

// ---------------------------------------------------------------------------------------------
// Hertz law

// Two glass spheres of validation.md section 1 test 1: R = 0.01 m, E = 4.8e10 Pa, nu = 0.2,
// rho = 2800 kg/m^3, approaching at 10 m/s each, e = 1.
Scene glass_pair_scene() {
  Scene s;
  Material glass;
  glass.name = "glass";
  glass.density = 2800;
  glass.youngs_modulus = 4.8e10;
  glass.poisson_ratio = 0.2;
  s.materials = {glass};
  s.interactions = {Interaction{1.0, 0, 0}};
  s.contact.normal = HertzNormal::kName;
  for (double side : {-1.0, 1.0}) {
    ParticleInit p;
    p.position = Vec3(side * 0.0105, 0, 0);
    p.velocity = Vec3(-side * 10, 0, 0);
    p.radius = 0.01;
    s.particles.push_back(p);
  }
  s.time.steps = 10;
  return s;
}

TEST(TimeStep, HertzReportsTheRayleighTime) {
  const TimeStepReport r = choose(glass_pair_scene());
  // validation.md section 6: pi R sqrt(rho / G) / (0.1631 nu + 0.8766), G = E / (2 (1 + nu)).
  const double g = 4.8e10 / (2 * 1.2);
  const double expected = kPi * 0.01 * std::sqrt(2800 / g) / (0.1631 * 0.2 + 0.8766);
  EXPECT_NEAR(r.rayleigh_time, expected, 1e-12 * expected);
  EXPECT_NEAR(r.rayleigh_time, 1.293e-5, 0.001e-5);  // the table's 4 digits
}

TEST(TimeStep, HertzContactTimeIsChungOoiTest1AtTheRelativeSpeed) {
  // Approach speed 20 m/s (twice the fastest particle): t_c = 40.34 us (validation.md section 1).
  const TimeStepReport r = choose(glass_pair_scene());
  EXPECT_NEAR(r.reference_speed, 20.0, 1e-12);
  EXPECT_NEAR(r.contact_time, 40.34e-6, 0.01e-6);
  // The same from the closed form: m* = m / 2, R* = R / 2, E* = E / (2 (1 - nu^2)).
  const double m_eff = 2800 * sphere_volume(0.01) / 2, r_eff = 0.005, e_eff = 4.8e10 / (2 * (1 - 0.04));
  const double alpha = std::pow(15 * m_eff * 400 / (16 * std::sqrt(r_eff) * e_eff), 0.4);
  EXPECT_NEAR(r.contact_time, 2.9432 * alpha / 20, 1e-9 * r.contact_time);
  // The step: 1/50 of the contact time, unless a fifth of the Rayleigh time is shorter.
  EXPECT_TRUE(r.automatic);
  EXPECT_NEAR(r.dt, std::min(r.contact_time / 50, 0.2 * r.rayleigh_time), 1e-12 * r.dt);
}

TEST(TimeStep, HertzGivenDtAboveTheRayleighTimeIsRejected) {
  Scene s = glass_pair_scene();
  s.time.dt = 5e-6;  // above t_c / 10 = 4.03e-6 s, below the Rayleigh time
  const std::string message = rejection(s);
  EXPECT_NE(message.find("time.dt"), std::string::npos) << message;
}

TEST(TimeStep, DescribeNamesTheNumbers) {
  const std::string text = choose(glass_pair_scene()).describe();
  EXPECT_NE(text.find("automatic"), std::string::npos) << text;
  EXPECT_NE(text.find("Rayleigh time 1.29"), std::string::npos) << text;
}

// The impact speed the Hertz step is chosen for counts what moves the bodies besides their initial
// velocities: a spinning wall's rim, and constant forces on particles (as gravity does). A plate
// spinning at 100 rad/s met a sphere 0.4 m from its axis at 40 m/s with 15 steps in the contact,
// where the same plate moving at 40 m/s had 58; a force bringing a sphere to 141 m/s left 12.
TEST(TimeStep, HertzReferenceSpeedCountsASpinningWallsRim) {
  Scene s = glass_pair_scene();
  s.particles[0].velocity = s.particles[1].velocity = Vec3::Zero();
  s.particles[1].position = {0.4, 0, 0.05};
  Material steel = s.materials[0];
  steel.name = "steel";
  s.materials.push_back(steel);
  s.interactions.assign(4, Interaction{1.0, 0, 0});
  WallInit paddle;
  paddle.material = 1;
  paddle.shape = PlateShape{{Vec3(-0.5, -0.05, 0), Vec3(0.5, -0.05, 0), Vec3(0.5, 0.05, 0), Vec3(-0.5, 0.05, 0)}};
  PrescribedMotion spin;
  spin.angular_velocity = {0, 0, 100};
  spin.center = Vec3::Zero();
  paddle.motion = spin;
  s.walls = {paddle};
  const TimeStepReport spinning = choose(s);
  // the plate's corner is 0.5025 m from the axis, the far sphere 0.403 m: 50.25 m/s, met at twice that
  EXPECT_NEAR(spinning.reference_speed, 2 * 100 * std::hypot(0.5, 0.05), 1e-9);
  PrescribedMotion slide;
  slide.velocity = {0, 100 * std::hypot(0.5, 0.05), 0};
  s.walls[0].motion = slide;
  EXPECT_NEAR(choose(s).dt, spinning.dt, 1e-12 * spinning.dt);
}

TEST(TimeStep, HertzReferenceSpeedCountsConstantForces) {
  Scene s = glass_pair_scene();
  s.particles[0].velocity = s.particles[1].velocity = Vec3::Zero();
  s.particles[1].position = {0.5, 0, 0};
  const double m = 2800 * sphere_volume(0.01);
  s.particles[1].force = {-m * 2e4, 0, 0};  // 2e4 m/s^2 towards the other sphere, 0.5 m away
  // from rest across the scene's extent L (the diagonal of the box holding the spheres: 0.5305 m by
  // 0.02 by 0.02): sqrt(2 a L)
  const double extent = std::sqrt(0.5305 * 0.5305 + 2 * 0.02 * 0.02);
  const double reach = std::sqrt(2 * 2e4 * extent);
  EXPECT_NEAR(choose(s).reference_speed, reach, 1e-9 * reach);
}

}  // namespace
}  // namespace dem
