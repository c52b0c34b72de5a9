#include "walls/wall_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace dem {

double LoadControl::force_at(double t) const {
  if (kind == Kind::Servo) return target;
  if (frequency <= 0 || t >= cycles / frequency) return f_min;
  return f_min + (f_max - f_min) * 0.5 * (1 - std::cos(2 * std::numbers::pi * frequency * t));
}

WallDriver::WallDriver(const WallInit& init, const Vec3& centroid, const Vec3& gravity)
    : motion_(init.motion), load_(init.load) {
  pose_.center0 = motion_ && motion_->center ? *motion_->center : centroid;
  if (load_) {
    load_->direction.normalize();
    gravity_along_ = gravity.dot(load_->direction);
  }
}

void WallDriver::begin_step(double t_new, double dt) {
  if (motion_) {
    // exact integral of v(t) = v0 + A sin(w t + phi), t counted from the motion's start
    const PrescribedMotion& m = *motion_;
    const double t = t_new - motion_start_;
    const double w = 2 * std::numbers::pi * m.frequency;
    Vec3 shift = m.velocity * t;
    Vec3 velocity = m.velocity;
    if (w > 0) {
      shift += m.amplitude * ((std::cos(m.phase) - std::cos(w * t + m.phase)) / w);
      velocity += m.amplitude * std::sin(w * t + m.phase);
    }
    pose_.displacement = origin_displacement_ + shift;
    pose_.velocity = velocity;
    const double spin = m.angular_velocity.norm();
    if (spin > 0)
      pose_.rotation = Eigen::AngleAxisd(spin * t, m.angular_velocity / spin).toRotationMatrix() * origin_rotation_;
    pose_.angular_velocity = m.angular_velocity;
  } else if (load_) {
    const Vec3& d = load_->direction;
    if (load_->kind == LoadControl::Kind::Cyclic) {
      speed_ += 0.5 * dt * accel_;  // first half kick with the last step's acceleration
    }
    pose_.displacement += (speed_ * dt) * d;
    pose_.velocity = speed_ * d;
  }
}

// A servo sets its speed from the force of the last step, v(k+1) = g (target - F(k)), and its
// contacts answer with F(k+1) - F(k) = K dt v(k+1) + C (v(k+1) - v(k)) (K: the contacts' normal
// stiffness, C: their dashpots). The force gap then follows
// e(k+1) = (1 - g K dt - g C) e(k) + g C e(k-1), which decays only while g C < 1 and
// g (K dt + 2 C) < 2 (Jury's test of the second-order characteristic polynomial). Near that the
// plate's force alternates step by step: under a bed of 5,000 clumped stones, a 250 kN servo at
// g = 1e-5 m/(N s) had g K dt = 0.26 and g C = 0.8, and its force swung between 160 and 300 kN
// from one step to the next. So the gain is at most kServoMargin / (K dt / 2 + C): both conditions
// then hold with a factor 2 to spare (K changes within a step, and Hertz contacts stiffen as they
// load), and undamped contacts close the gap in one step. This is Itasca PFC's wall servo, whose
// gain is alpha / (k_n N_c dt) for a force target, with the contacts' dashpots added. K and C are
// summed over the wall's contacts whatever their normal, an upper bound of their share along the
// load.
//
// That analysis holds the particles still. They are not: pushed through a dashpot that relaxes a
// good part of their speed in one step (C dt / m of 0.36 for a sphere between a floor and the
// plate, restitution 0.05, dt at the stable limit), they answer within the step and feed the mode
// of a two-step period, which then grew at 0.85 of the cap (an independent tester found it; a
// model of that sphere under this integrator agrees). So the servo closes the gap of the mean of
// this step's force and the last, a filter whose zero is at that mode's frequency: the same model
// then stays stable to 3.8-4.2 times the cap for C dt / m from 0.008 to 0.36.
double WallDriver::servo_gain(const LoadControl& load, double dt, const ContactResponse& response) {
  constexpr double kServoMargin = 0.5;
  const double answer = 0.5 * response.stiffness * dt + response.damping;
  if (!(answer > 0)) return load.gain;
  return std::min(load.gain, kServoMargin / answer);
}

void WallDriver::end_step(double t_new, double dt, const Vec3& reaction, const ContactResponse& response) {
  if (!load_) return;
  const Vec3& d = load_->direction;
  // The particles push the wall with `reaction`; the wall pushes them with its opposite.
  const double previous_force = applied_force_;
  applied_force_ = -reaction.dot(d);
  if (load_->kind == LoadControl::Kind::Cyclic) {
    const double force = load_->force_at(t_new - load_start_) - applied_force_;
    accel_ = force / load_->mass + gravity_along_;
    speed_ += 0.5 * dt * accel_;  // second half kick
  } else {
    // servo (as PFC's wall servo): the speed that would close the force gap, capped; the gap of the
    // two last steps' mean force (above), of this one's alone where the load starts (dt = 0)
    const double measured = dt > 0 ? 0.5 * (applied_force_ + previous_force) : applied_force_;
    speed_ =
        std::clamp(servo_gain(*load_, dt, response) * (load_->target - measured), -load_->max_speed, load_->max_speed);
  }
  pose_.velocity = speed_ * d;
}

double WallDriver::load_displacement() const { return load_ ? pose_.displacement.dot(load_->direction) : 0.0; }

double WallDriver::prescribed_force(double t) const { return load_ ? load_->force_at(t - load_start_) : 0.0; }

namespace {

bool same_motion(const std::optional<PrescribedMotion>& a, const std::optional<PrescribedMotion>& b) {
  if (!a || !b) return !a && !b;
  return a->velocity == b->velocity && a->amplitude == b->amplitude && a->frequency == b->frequency &&
         a->phase == b->phase && a->angular_velocity == b->angular_velocity && a->center == b->center;
}

bool same_load(const std::optional<LoadControl>& a, const std::optional<LoadControl>& b) {
  if (!a || !b) return !a && !b;
  return a->kind == b->kind && a->direction == b->direction && a->mass == b->mass && a->f_min == b->f_min &&
         a->f_max == b->f_max && a->frequency == b->frequency && a->cycles == b->cycles && a->target == b->target &&
         a->gain == b->gain && a->max_speed == b->max_speed;
}

}  // namespace

WallDriver::Record WallDriver::record() const {
  Record r;
  r.has_motion = motion_.has_value();
  if (motion_) {
    const PrescribedMotion& m = *motion_;
    r.motion = {m.velocity, m.amplitude, m.frequency, m.phase, m.angular_velocity, m.center.value_or(Vec3::Zero())};
    r.has_center = m.center.has_value();
  }
  r.has_load = load_.has_value();
  if (load_) r.load = *load_;
  r.pose = pose_;
  r.gravity_along = gravity_along_;
  r.speed = speed_;
  r.accel = accel_;
  r.applied_force = applied_force_;
  r.load_start = load_start_;
  r.motion_start = motion_start_;
  r.origin_displacement = origin_displacement_;
  r.origin_rotation = origin_rotation_;
  return r;
}

WallDriver WallDriver::from_record(const Record& r) {
  if (r.has_motion > 1 || r.has_center > 1 || r.has_load > 1)
    throw std::runtime_error("a wall's flags are not 0 or 1 (" + std::to_string(r.has_motion) + ", " +
                             std::to_string(r.has_center) + ", " + std::to_string(r.has_load) + ")");
  if (r.load.kind != LoadControl::Kind::Cyclic && r.load.kind != LoadControl::Kind::Servo)
    throw std::runtime_error("a wall's load is of no known kind (" + std::to_string(static_cast<int>(r.load.kind)) +
                             ")");
  WallDriver d;
  if (r.has_motion) {
    const PlainMotion& m = r.motion;
    d.motion_ = PrescribedMotion{m.velocity, m.amplitude, m.frequency, m.phase, m.angular_velocity, std::nullopt};
    if (r.has_center) d.motion_->center = m.center;
  }
  if (r.has_load) d.load_ = r.load;
  d.pose_ = r.pose;
  d.gravity_along_ = r.gravity_along;
  d.speed_ = r.speed;
  d.accel_ = r.accel;
  d.applied_force_ = r.applied_force;
  d.load_start_ = r.load_start;
  d.motion_start_ = r.motion_start;
  d.origin_displacement_ = r.origin_displacement;
  d.origin_rotation_ = r.origin_rotation;
  return d;
}

bool WallDriver::continue_from(const WallDriver& saved, double now) {
  if (!same_motion(motion_, saved.motion_))
    throw std::runtime_error(
        "its prescribed motion differs from the saved run's: a continued run may change a wall's "
        "load, not its motion (a motion is a function of the time since the start)");
  if (same_load(load_, saved.load_)) {
    const double gravity_along = gravity_along_;  // this spec's gravity
    *this = saved;
    gravity_along_ = gravity_along;
    return false;
  }
  pose_ = saved.pose_;
  pose_.angular_velocity = Vec3::Zero();
  if (!load_) {  // dropped: the wall stays where it is
    pose_.velocity = Vec3::Zero();
    return false;
  }
  const bool same_direction = saved.load_ && saved.load_->direction == load_->direction;
  speed_ = saved.pose_.velocity.dot(load_->direction);
  accel_ = same_direction ? saved.accel_ : 0.0;
  applied_force_ = same_direction ? saved.applied_force_ : 0.0;
  pose_.velocity = speed_ * load_->direction;
  load_start_ = now;
  return true;
}

bool WallDriver::change(const std::optional<PrescribedMotion>& motion, const std::optional<LoadControl>& load,
                        double now, const Vec3& gravity) {
  const std::optional<LoadControl> old_load = load_;
  const Vec3 velocity = pose_.velocity;
  motion_ = motion;
  load_ = load;
  if (load_) load_->direction.normalize();
  set_gravity(gravity);
  pose_.velocity = Vec3::Zero();
  pose_.angular_velocity = Vec3::Zero();
  if (motion_) {
    start_clock(now);
    return false;
  }
  if (!load_) return false;
  const bool same_direction = old_load && old_load->direction == load_->direction;
  speed_ = velocity.dot(load_->direction);
  accel_ = same_direction ? accel_ : 0.0;
  applied_force_ = same_direction ? applied_force_ : 0.0;
  pose_.velocity = speed_ * load_->direction;
  load_start_ = now;
  return true;
}

void WallDriver::start_clock(double now) {
  motion_start_ = now;
  load_start_ = now;  // a wall that comes with a load starts its cyclic clock when it comes
  origin_displacement_ = pose_.displacement;
  origin_rotation_ = pose_.rotation;
}

void WallDriver::set_gravity(const Vec3& gravity) { gravity_along_ = load_ ? gravity.dot(load_->direction) : 0.0; }

}  // namespace dem
