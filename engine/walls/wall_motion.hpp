// How a wall (plane, plate or mesh) moves: where it is relative to its start, how fast each of its
// points moves, and what drives it (a prescribed motion, a cyclic load, a servo).
#pragma once

#include <cstdint>
#include <optional>

#include "core/scene.hpp"

namespace dem {

// A rigid displacement from the wall's start: x = R (x0 - c0) + c0 + displacement.
struct WallPose {
  Vec3 center0 = Vec3::Zero();  // rotation centre at the start
  Vec3 displacement = Vec3::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 velocity = Vec3::Zero();          // of the centre
  Vec3 angular_velocity = Vec3::Zero();  // about the centre

  Vec3 place(const Vec3& x0) const { return rotation * (x0 - center0) + center0 + displacement; }
  Vec3 turn(const Vec3& direction0) const { return rotation * direction0; }
  Vec3 velocity_at(const Vec3& x) const { return velocity + angular_velocity.cross(x - (center0 + displacement)); }
  bool moving() const { return !velocity.isZero(0) || !angular_velocity.isZero(0); }
};

// Advances one wall's pose through a step. Velocity Verlet like the particles: begin_step moves the
// wall to t + dt (a load-controlled wall with the force of the last step), end_step takes the
// particles' new reaction on the wall (the force the wall receives, N) and completes its velocity.
// A prescribed motion without its optional centre (that is PrescribedMotion::center, a flag apart).
struct PlainMotion {
  Vec3 velocity = Vec3::Zero();
  Vec3 amplitude = Vec3::Zero();
  double frequency = 0;
  double phase = 0;
  Vec3 angular_velocity = Vec3::Zero();
  Vec3 center = Vec3::Zero();
};

// How the particles' push on a wall answers the wall's motion, summed over its contacts: the
// normal stiffness dF_n/d(delta) (N/m) and the normal dashpots' coefficient (N s/m).
struct ContactResponse {
  double stiffness = 0;
  double damping = 0;
};

class WallDriver {
 public:
  WallDriver() = default;
  WallDriver(const WallInit& init, const Vec3& centroid, const Vec3& gravity);

  bool moves() const { return motion_.has_value() || load_.has_value(); }
  bool load_controlled() const { return load_.has_value(); }
  const std::optional<LoadControl>& load() const { return load_; }
  double load_start() const { return load_start_; }  // the time the load began (its cyclic clock's zero)
  const WallPose& pose() const { return pose_; }

  void begin_step(double t_new, double dt);
  // `response`: how the reaction answers the wall's motion; a servo caps its gain with it.
  void end_step(double t_new, double dt, const Vec3& reaction, const ContactResponse& response);

  // The gain a servo uses: its own, at most what keeps its loop stable at step dt with contacts
  // that answer with `response` (wall_motion.cpp).
  static double servo_gain(const LoadControl& load, double dt, const ContactResponse& response);

  // Displacement along the load direction, and the force the wall applies to the particles along
  // it (the reaction's component against the direction); both 0 for walls without a load.
  double load_displacement() const;
  double applied_force() const { return applied_force_; }
  // The force the load prescribes at time t (the servo's target), N.
  double prescribed_force(double t) const;

  // A continued run: this driver (from the continued run's spec) takes over from `saved` (the
  // saved run's) at time `now`. The wall stays where the saved run left it. An unchanged load goes
  // on as if never interrupted; a load added or changed starts now (a cyclic load's clock at zero
  // now), keeping the wall's speed along its direction; a dropped load leaves the wall at rest
  // where it is: a bed settled, then loaded (BallastDEM's two stages). Prescribed motions are
  // functions of the time since the start, so they cannot change: throws std::runtime_error.
  // Returns true when a load starts now: the caller then gives it the particles' reaction with
  // end_step(now, 0, reaction), as a fresh run does at t = 0.
  bool continue_from(const WallDriver& saved, double now);

  // A stage's start (Scene::stages): from `now` the wall follows `motion` or `load` (neither: it
  // stops where it is). A motion's time counts from now, and it turns about the wall's centre
  // where it is; a load keeps the wall's speed along its direction, and its cyclic clock starts
  // now. Returns true when a load starts now (the caller gives it the particles' reaction with
  // end_step(now, 0, ...), as continue_from's caller does).
  bool change(const std::optional<PrescribedMotion>& motion, const std::optional<LoadControl>& load, double now,
              const Vec3& gravity);
  // A wall that appears at a stage's start: its motion's time and its load's cyclic clock count from `now`.
  void start_clock(double now);
  // A stage changes gravity: a loaded wall's weight follows.
  void set_gravity(const Vec3& gravity);

  // What a saved state holds of a driver: numbers, and flags as whole bytes. A state read from a
  // file may hold any bytes, and an optional's flag (a bool) copied from one that is neither 0 nor 1
  // is undefined behaviour (the saved-state fuzzer found it), so the flags are bytes and checked.
  struct Record {
    std::uint8_t has_motion = 0, has_center = 0, has_load = 0;
    std::uint8_t padding[5] = {};  // saved with the state: its bytes are set, not whatever the memory held
    PlainMotion motion;
    LoadControl load;
    WallPose pose;
    double gravity_along = 0, speed = 0, accel = 0, applied_force = 0, load_start = 0;
    double motion_start = 0;
    Vec3 origin_displacement = Vec3::Zero();
    Eigen::Matrix3d origin_rotation = Eigen::Matrix3d::Identity();
  };
  Record record() const;
  // Throws std::runtime_error for a flag other than 0 or 1.
  static WallDriver from_record(const Record& r);

 private:
  std::optional<PrescribedMotion> motion_;
  std::optional<LoadControl> load_;
  WallPose pose_;
  double gravity_along_ = 0;  // g . direction
  double speed_ = 0;          // along the load direction
  double accel_ = 0;
  double applied_force_ = 0;
  double load_start_ = 0;  // the time the load began (its cyclic clock's zero)
  // The prescribed motion's clock starts at motion_start_ with the wall at the origin pose (the
  // start of the run, or of the stage that gave the motion).
  double motion_start_ = 0;
  Vec3 origin_displacement_ = Vec3::Zero();
  Eigen::Matrix3d origin_rotation_ = Eigen::Matrix3d::Identity();
};

}  // namespace dem
