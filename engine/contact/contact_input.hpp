// What every contact model sees and returns: one contact, or one per lane (T = Lanes<W>,
// core/lanes.hpp), so that the same model code runs in the one-lane and the four-lane force loop.
//
// Conventions: body i and body j (j may be a wall), n the unit normal pointing from j to i,
// delta > 0 the overlap, v the velocity of i's contact point relative to j's, force = on body i.
//
// Velocities: velocity Verlet evaluates forces at the full step but only knows the half-step
// velocity there. Springs move with the half-step velocity (exact for the displacement); the
// dashpots use the velocity predicted at the full step, v(n+1/2) + dt/2 a(n) (and the spin's
// likewise), because the half-step lag adds dissipation of relative size zeta*omega*dt: 3.5% of e
// at e = 0.1 with 50 steps per contact, against 0.1% with the prediction (docs/physics.md); in the
// tangential direction, where a sphere's contact point is 3.5 times easier to move than its centre,
// a partial-slip impact's spin was 3% off and first order in the step.
#pragma once

#include "core/lanes.hpp"

// The models run once per contact per step: keep them inlined into the force loop whatever the
// compiler's size heuristics say (measured: 30% of the loop went to calls otherwise).
#define DEM_HOT [[gnu::always_inline]] inline

namespace dem {

template <class T>
struct ContactInput {
  V3<T> n;
  T delta;
  V3<T> v_rel;      // contact-point relative velocity at the half step (moves the springs)
  T vn_now;         // normal relative velocity predicted at the full step (normal damping)
  V3<T> vt_now;     // tangential relative velocity predicted at the full step (tangential damping)
  T onset;          // share of the step's force window inside the contact (boundary_share)
  T travel;         // |v_n| dt: the overlap gained or lost in a step (a contact boundary is nearer)
  T first_touch{};  // on the first sample of a new contact, the overlap gained since the last sample
                    // (> 0; spring_boundary_correction); else 0
  V3<T> w_rel;      // w_i - w_j
  T sqrt_m_eff;     // sqrt of the reduced mass
  T r_eff;          // reduced radius (Hertz and rolling laws)
  T i_roll;         // rolling inertia (rolling laws)
  T dt;
};

template <class T>
struct ContactOutput {
  V3<T> force;        // on i
  V3<T> shear_force;  // tangential part of force (its lever torque is the force loop's)
  V3<T> roll_moment;  // on i (j gets the opposite)
  T fn;               // normal force magnitude (>= 0 unless tension is allowed)
  // How fn answers an approach: dF_n/d(delta) (N/m) and the dashpot's coefficient of the normal
  // speed (N s/m). A servo wall sums them over its contacts to keep its loop stable (wall_motion.hpp).
  T kn = T{};
  T cn = T{};
};

// What a normal model tells the tangential and rolling models.
template <class T>
struct NormalResponse {
  T fn;          // normal force, positive = repulsive
  T kn_tangent;  // dFn/d(delta), for the rolling spring
  T kt;          // tangential stiffness
  T ct;          // tangential damping
  T cn = T{};    // the normal dashpot's coefficient of the normal speed in fn (N s/m)
  // For a law whose stiffnesses change with the overlap (Hertz's k_t and dF_n/d(delta) both go as
  // a = sqrt(R* delta)), over the drift: the stiffness before over now, and the mean over now (the
  // stiffness of the step's travel); 1 and 1 where they do not change. The tangential and rolling
  // springs use them to stay passive.
  T stiffness_ratio = splat<T>(1.0);
  T stiffness_mean = splat<T>(1.0);
};

// Contact boundaries: a dashpot force jumps at first touch (from 0 to C_n v) and, when tension is
// allowed, at parting. The force of a step acts over the window [t - dt/2, t + dt/2] of its two
// half kicks. When the overlap is smaller than one step of relative motion, the contact began within
// the last step or ends within the next one, s*dt from t with s = delta / (|v_n| dt); it then covers
// 1/2 + s of the window, and the dashpot force is scaled by that share. Without it a first-order
// impulse error C_n |v_n| dt (1/2 - s) remains at each boundary (up to 2% in e at 50 steps per
// contact, depending on where the steps fall).
//
// A contact that began in the last window but after its evaluation (1/2 <= s < 1) was missed there:
// this step takes that part too (a share up to 3/2). Not so at parting (v_n > 0, i moving away from
// j): a parting predicted within the next window, past its evaluation, is a guess from this step's
// velocity, which the pull of a tensile dashpot slows; when the next evaluation still found the
// contact, the part was counted twice (linear law with tension, e = 0.2: rebounds 3.7% short at two
// of every twenty positions of the steps). Parting takes at most the whole window.
template <class T>
DEM_HOT T boundary_share(T delta, T vn, T dt) {
  const T travel = lane_abs(vn) * dt;
  const auto boundary = delta < travel;
  if (!any_lane(boundary)) return splat<T>(1.0);  // nearly always: skip the division
  const T share = 0.5 + delta / travel;
  return select(boundary, select(vn > T{}, lane_min(share, splat<T>(1.0)), share), splat<T>(1.0));
}

// The spring's impulse at a contact boundary. A spring force that rises from zero at first touch
// has a kink there, and the one sample per step of velocity Verlet misses part of the impulse of the
// window in which the contact starts or ends. With `gained` the overlap the boundary's step gained
// or lost and `delta` the overlap at the sample inside the contact (0 <= delta <= gained), the
// exact impulse of the step is U(delta + gained/2) / |v_n| with U the spring's stored energy (its
// force integrated over the overlap), against dt F(delta) sampled; wherever the boundary falls
// (this window or the neighbouring one past or before its sample) the difference is the same, and
// it is counted once: at the first sample of a new contact, and at the first sample after a
// parting (the kernel's). For the linear law it is K_n gained (s - 1/2)^2 / 2 with s = delta /
// gained, an energy error of (omega dt)^2 / 4 (s - 1/2)^2 per boundary without it, of either sign:
// 5e-4 of a collision's energy at 50 steps per contact, and a random walk over a gas
// (docs/validation.md, "Energy"). Returns the force to add over the step.
template <class T, class Energy, class Force>
DEM_HOT T spring_boundary_correction(T delta, T gained, Energy&& energy_at, Force&& force_at) {
  const T safe = select(gained > T{}, gained, splat<T>(1.0));
  const T d = lane_min(lane_max(delta, T{}), safe);
  return energy_at(d + 0.5 * safe) / safe - force_at(d);
}

// The spring force `f` sampled at `delta`, with the correction on the first sample of a new contact.
template <class T, class Energy, class Force>
DEM_HOT T spring_with_first_touch(T f, T delta, T first_touch, Energy&& energy_at, Force&& force_at) {
  const auto fresh = first_touch > T{};
  if (!any_lane(fresh)) return f;  // nearly always
  return f + select(fresh, spring_boundary_correction(delta, first_touch, energy_at, force_at), T{});
}

// Keeps a stored vector in the current tangent plane as the contact turns: the normal part is
// removed (LIGGGHTS' practice). LAMMPS also restores the old length; the loss is (turn angle)^2 / 2
// per step, ~1e-10 here, and the rescaling would cost a division and a square root per contact.
template <class T>
DEM_HOT V3<T> in_plane(const V3<T>& stored, const V3<T>& n) {
  return stored - dot(n, stored) * n;
}

}  // namespace dem
