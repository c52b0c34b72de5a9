#include "walls/wall_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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
    // exact integral of v(t) = v0 + A sin(w t + phi)
    const PrescribedMotion& m = *motion_;
    const double w = 2 * std::numbers::pi * m.frequency;
    Vec3 shift = m.velocity * t_new;
    Vec3 velocity = m.velocity;
    if (w > 0) {
      shift += m.amplitude * ((std::cos(m.phase) - std::cos(w * t_new + m.phase)) / w);
      velocity += m.amplitude * std::sin(w * t_new + m.phase);
    }
    pose_.displacement = shift;
    pose_.velocity = velocity;
    const double spin = m.angular_velocity.norm();
    if (spin > 0) pose_.rotation = Eigen::AngleAxisd(spin * t_new, m.angular_velocity / spin).toRotationMatrix();
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

void WallDriver::end_step(double t_new, double dt, const Vec3& reaction) {
  if (!load_) return;
  const Vec3& d = load_->direction;
  // The particles push the wall with `reaction`; the wall pushes them with its opposite.
  applied_force_ = -reaction.dot(d);
  if (load_->kind == LoadControl::Kind::Cyclic) {
    const double force = load_->force_at(t_new) - applied_force_;
    accel_ = force / load_->mass + gravity_along_;
    speed_ += 0.5 * dt * accel_;  // second half kick
  } else {
    // servo (as PFC's wall servo): the speed that would close the force gap, capped
    speed_ = std::clamp(load_->gain * (load_->target - applied_force_), -load_->max_speed, load_->max_speed);
  }
  pose_.velocity = speed_ * d;
}

double WallDriver::load_displacement() const { return load_ ? pose_.displacement.dot(load_->direction) : 0.0; }

double WallDriver::prescribed_force(double t) const { return load_ ? load_->force_at(t) : 0.0; }

}  // namespace dem
