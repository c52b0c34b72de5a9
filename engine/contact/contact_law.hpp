// The contact laws as small evaluator types, combined at compile time into one ContactLaw that the
// force loops inline (the scene picks the combination once: sim/kernel_select.cpp).
//
// Conventions: body i and body j (j may be a wall), n the unit normal pointing from j to i,
// delta > 0 the overlap, v the velocity of i's contact point relative to j's, force = on body i.
//
// Velocities: velocity Verlet evaluates forces at the full step but only knows the half-step
// velocity there. Springs move with the half-step velocity (exact for the displacement); the normal
// dashpot uses the velocity predicted at the full step, v(n+1/2) + dt/2 a(n), because the half-step
// lag adds dissipation of relative size zeta*omega*dt (3.5% of e at e = 0.1 with 50 steps per
// contact, against 0.1% with the prediction; see docs/physics.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "contact/pair_params.hpp"
#include "core/vec.hpp"
#include "neighbor/neighbor_list.hpp"

// The laws run once per contact per step: keep them inlined into the force loop whatever the
// compiler's size heuristics say (measured: 30% of the loop went to calls otherwise).
#define DEM_HOT [[gnu::always_inline]] inline

namespace dem {

struct ContactInput {
  Vec3 n;
  double delta;
  Vec3 v_rel;       // contact-point relative velocity at the half step (moves the springs)
  double vn_now;    // normal relative velocity predicted at the full step (normal damping)
  double onset;     // share of the step's force window inside the contact (boundary_share)
  Vec3 w_rel;       // w_i - w_j
  PairConstants pair;  // sqrt(m*), and R* and I_r where the law uses them
  double dt;
};

struct ContactHistory {
  Vec3* shear;      // tangential spring displacement (Mindlin or linear)
  Vec3* roll;       // rolling spring moment (EPSD only)
};

struct ContactOutput {
  Vec3 force;       // on i
  Vec3 shear_force; // tangential part of force (lever torque: -r_i n x fs on i, -r_j n x fs on j)
  Vec3 roll_moment; // on i (j gets the opposite)
  double fn;        // normal force magnitude (>= 0 unless tension is allowed)
};

// Contact boundaries: a dashpot force jumps at first touch (from 0 to C_n v) and, when tension is
// allowed, at parting. The force of a step acts over the window [t - dt/2, t + dt/2] of its two
// half kicks. When the overlap is smaller than one step of relative motion, the contact began within
// the last step or ends within the next one, s*dt from t with s = delta / (|v_n| dt); it then covers
// 1/2 + s of the window, and the dashpot force is scaled by that share. Without it a first-order
// impulse error C_n |v_n| dt (1/2 - s) remains at each boundary (up to 2% in e at 50 steps per
// contact, depending on where the steps fall).
DEM_HOT double boundary_share(double delta, double vn, double dt) {
  const double travel = std::abs(vn) * dt;
  return delta < travel ? 0.5 + delta / travel : 1.0;
}

struct NormalResponse {
  double fn;         // normal force, positive = repulsive
  double kn_tangent; // dFn/d(delta), for the rolling spring
  double kt;         // tangential stiffness
  double ct;         // tangential damping
};

// Linear spring-dashpot: F_n = K_n x_n - C_n xdot_n, K_s = rns K_n, C_s = rzs C_n
// (PDEM-EGD manual eqs. 1-7; C_n = 2 zeta sqrt(m* K_n) with m* the reduced mass).
struct LinearNormal {
  DEM_HOT static NormalResponse evaluate(const PairParams& p, double delta, double vn, double onset,
                                         const PairConstants& pc) {
    const double cn = p.cn_per_sqrt_mass * pc.sqrt_m_eff;
    return {p.kn * delta - onset * cn * vn, p.kn, p.kt_ratio * p.kn, p.ct_ratio * cn};
  }
  static double elastic_energy(const PairParams& p, double delta, double) { return 0.5 * p.kn * delta * delta; }
};

// Hertz-Mindlin: F_n = 4/3 E* sqrt(R* d) d, k_t = 8 G* sqrt(R* d) (Mindlin & Deresiewicz 1953, no-slip
// limit), damping proportional to d^(1/4) (Tsuji et al. 1992) with the number eta solved for e exactly.
struct HertzNormal {
  DEM_HOT static NormalResponse evaluate(const PairParams& p, double delta, double vn, double onset,
                                         const PairConstants& pc) {
    const double sqrt_rd = std::sqrt(pc.r_eff * delta);
    const double f_elastic = (4.0 / 3.0) * p.e_star * sqrt_rd * delta;
    // C_n = eta sqrt(m* 4/3 E* sqrt(R* d)); C_t = eta sqrt(2/3 k_t m*) (LIGGGHTS' gamma_t, beta -> eta)
    const double scale = std::sqrt(sqrt_rd) * pc.sqrt_m_eff;
    const double kt = 8 * p.g_star * sqrt_rd;
    return {f_elastic - onset * p.hertz_cn * scale * vn, 2 * p.e_star * sqrt_rd, kt, p.hertz_ct * scale};
  }
  static double elastic_energy(const PairParams& p, double delta, double r_eff) {
    return (8.0 / 15.0) * p.e_star * std::sqrt(r_eff) * delta * delta * std::sqrt(delta);
  }
};

// Keeps a stored vector in the current tangent plane as the contact turns: the normal part is
// removed (LIGGGHTS' practice). LAMMPS also restores the old length; the loss is (turn angle)^2 / 2
// per step, ~1e-10 here, and the rescaling would cost a division and a square root per contact.
DEM_HOT void rotate_into_plane(Vec3& stored, const Vec3& n) { stored -= n.dot(stored) * n; }

// Tangential spring with history and the Mohr-Coulomb limit |F_s| <= mu F_n (the seeds' eqs. 2-3).
// Sliding is decided on the spring alone, as LIGGGHTS does: when k_t |xi| exceeds mu F_n the spring
// is shortened to the sliding force and the dashpot is off; otherwise spring plus dashpot, capped.
// (Taking the dashpot into the spring, as LAMMPS' xi = -(F_s + c_t v_t)/k_t does, can point the
// spring against the slip when c_t |v_t| > mu F_n and make the friction force flip sign.)
struct FrictionalTangent {
  DEM_HOT static Vec3 evaluate(const PairParams& p, const NormalResponse& nr, double fn, const Vec3& n,
                       const Vec3& v_t, double dt, Vec3& shear) {
    rotate_into_plane(shear, n);
    shear += v_t * dt;
    const double limit = p.mu * fn;
    const Vec3 elastic = -nr.kt * shear;
    const double elastic2 = elastic.squaredNorm();
    if (elastic2 > limit * limit) {
      const double scale = limit / std::sqrt(elastic2);
      shear *= scale;
      return scale * elastic;
    }
    Vec3 fs = elastic - nr.ct * v_t;
    const double fs2 = fs.squaredNorm();
    if (fs2 > limit * limit) fs *= limit / std::sqrt(fs2);
    return fs;
  }
};

struct NoRolling {
  DEM_HOT static Vec3 evaluate(const PairParams&, const NormalResponse&, double, const ContactInput&, Vec3*) {
    return Vec3::Zero();
  }
};

// Constant directional torque (Ai et al. 2011, model A): M = -mu_r R* F_n w_r / |w_r|. The torque is
// capped at the one that stops the relative rolling within this step, so a body at rest does not
// chatter (the model itself is undefined at w_r = 0).
struct CdtRolling {
  DEM_HOT static Vec3 evaluate(const PairParams& p, const NormalResponse&, double fn, const ContactInput& c, Vec3*) {
    Vec3 wr = c.w_rel - c.n.dot(c.w_rel) * c.n;
    const double w = wr.norm();
    if (w == 0) return Vec3::Zero();
    const double moment = std::min(p.mu_r * c.pair.r_eff * fn, c.pair.i_roll * w / c.dt);
    return -moment / w * wr;
  }
};

// Elastic-plastic spring-dashpot (Ai et al. 2011, model C, eqs. 11-16): k_r = 2.25 k_n mu_r^2 R*^2,
// spring moment limited to mu_r R* F_n, viscous part C_r = 2 eta_r sqrt(I_r k_r) while not sliding.
struct EpsdRolling {
  DEM_HOT static Vec3 evaluate(const PairParams& p, const NormalResponse& nr, double fn, const ContactInput& c,
                       Vec3* spring) {
    Vec3& mk = *spring;
    const Vec3 wr = c.w_rel - c.n.dot(c.w_rel) * c.n;
    const double r_eff = c.pair.r_eff;
    const double kr = 2.25 * nr.kn_tangent * p.mu_r * p.mu_r * r_eff * r_eff;
    rotate_into_plane(mk, c.n);
    mk -= kr * c.dt * wr;
    const double limit = p.mu_r * r_eff * std::max(fn, 0.0);
    const double m2 = mk.squaredNorm();
    if (m2 >= limit * limit) {
      if (m2 > 0) mk *= limit / std::sqrt(m2);
      return mk;  // fully mobilised: no damping (f = 0 of Ai et al.)
    }
    const double cr = 2 * p.rolling_damping * std::sqrt(c.pair.i_roll * kr);
    return mk - cr * wr;
  }
};

template <class Normal, bool NoTensile, bool Friction, class Rolling>
struct ContactLaw {
  static constexpr bool kRolling = !std::is_same_v<Rolling, NoRolling>;
  static constexpr bool kRollingSpring = std::is_same_v<Rolling, EpsdRolling>;
  static constexpr bool kNeedsEffectiveRadius = kRolling || std::is_same_v<Normal, HertzNormal>;
  using NormalLaw = Normal;

  DEM_HOT static ContactOutput evaluate(const PairParams& p, const ContactInput& c, const ContactHistory& h) {
    const double vn = c.v_rel.dot(c.n);
    const NormalResponse nr = Normal::evaluate(p, c.delta, c.vn_now, c.onset, c.pair);
    const double fn = NoTensile ? std::max(nr.fn, 0.0) : nr.fn;
    ContactOutput out;
    out.fn = fn;
    if constexpr (Friction) {
      const Vec3 v_t = c.v_rel - vn * c.n;
      out.shear_force = FrictionalTangent::evaluate(p, nr, std::max(fn, 0.0), c.n, v_t, c.dt, *h.shear);
    } else {
      out.shear_force.setZero();
    }
    out.force = fn * c.n + out.shear_force;
    if constexpr (kRolling) out.roll_moment = Rolling::evaluate(p, nr, fn, c, h.roll);
    else out.roll_moment.setZero();
    return out;
  }
};

}  // namespace dem
