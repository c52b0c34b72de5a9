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

#include <type_traits>

#include "contact/pair_params.hpp"
#include "core/lanes.hpp"
#include "neighbor/neighbor_list.hpp"

// The laws run once per contact per step: keep them inlined into the force loop whatever the
// compiler's size heuristics say (measured: 30% of the loop went to calls otherwise).
#define DEM_HOT [[gnu::always_inline]] inline

namespace dem {

// One contact, or one per lane (T = Lanes<W>: core/lanes.hpp).
template <class T>
struct ContactInput {
  V3<T> n;
  T delta;
  V3<T> v_rel;      // contact-point relative velocity at the half step (moves the springs)
  T vn_now;         // normal relative velocity predicted at the full step (normal damping)
  T onset;          // share of the step's force window inside the contact (boundary_share)
  V3<T> w_rel;      // w_i - w_j
  T sqrt_m_eff;     // sqrt of the reduced mass
  T r_eff;          // reduced radius (Hertz and rolling laws)
  T i_roll;         // rolling inertia (rolling laws)
  T dt;
};

template <class T>
struct ContactOutput {
  V3<T> force;       // on i
  V3<T> shear_force; // tangential part of force (lever torque: -r_i n x fs on i, -r_j n x fs on j)
  V3<T> roll_moment; // on i (j gets the opposite)
  T fn;              // normal force magnitude (>= 0 unless tension is allowed)
};

// The coefficients of each lane's material pair.
template <class T>
struct LawParams {
  T kn, kt_ratio, ct_ratio, cn_per_sqrt_mass, e_star, g_star, hertz_cn, hertz_ct, mu, mu_r, rolling_damping;

  DEM_HOT void set(int l, const PairParams& p) {
    set_lane(kn, l, p.kn);
    set_lane(kt_ratio, l, p.kt_ratio);
    set_lane(ct_ratio, l, p.ct_ratio);
    set_lane(cn_per_sqrt_mass, l, p.cn_per_sqrt_mass);
    set_lane(e_star, l, p.e_star);
    set_lane(g_star, l, p.g_star);
    set_lane(hertz_cn, l, p.hertz_cn);
    set_lane(hertz_ct, l, p.hertz_ct);
    set_lane(mu, l, p.mu);
    set_lane(mu_r, l, p.mu_r);
    set_lane(rolling_damping, l, p.rolling_damping);
  }
  DEM_HOT static LawParams all(const PairParams& p) {
    LawParams out;
    for (int l = 0; l < lane_count<T>(); ++l) out.set(l, p);
    return out;
  }
};

// Contact boundaries: a dashpot force jumps at first touch (from 0 to C_n v) and, when tension is
// allowed, at parting. The force of a step acts over the window [t - dt/2, t + dt/2] of its two
// half kicks. When the overlap is smaller than one step of relative motion, the contact began within
// the last step or ends within the next one, s*dt from t with s = delta / (|v_n| dt); it then covers
// 1/2 + s of the window, and the dashpot force is scaled by that share. Without it a first-order
// impulse error C_n |v_n| dt (1/2 - s) remains at each boundary (up to 2% in e at 50 steps per
// contact, depending on where the steps fall).
template <class T>
DEM_HOT T boundary_share(T delta, T vn, T dt) {
  const T travel = lane_abs(vn) * dt;
  const auto boundary = delta < travel;
  if (!any_lane(boundary)) return splat<T>(1.0);  // nearly always: skip the division
  return select(boundary, 0.5 + delta / travel, splat<T>(1.0));
}

template <class T>
struct NormalResponse {
  T fn;         // normal force, positive = repulsive
  T kn_tangent; // dFn/d(delta), for the rolling spring
  T kt;         // tangential stiffness
  T ct;         // tangential damping
};

// Linear spring-dashpot: F_n = K_n x_n - C_n xdot_n, K_s = rns K_n, C_s = rzs C_n
// (PDEM-EGD manual eqs. 1-7; C_n = 2 zeta sqrt(m* K_n) with m* the reduced mass).
struct LinearNormal {
  template <class T>
  DEM_HOT static NormalResponse<T> evaluate(const LawParams<T>& p, const ContactInput<T>& c) {
    const T cn = p.cn_per_sqrt_mass * c.sqrt_m_eff;
    return {p.kn * c.delta - c.onset * cn * c.vn_now, p.kn, p.kt_ratio * p.kn, p.ct_ratio * cn};
  }
  static double elastic_energy(const PairParams& p, double delta, double) { return 0.5 * p.kn * delta * delta; }
};

// Hertz-Mindlin: F_n = 4/3 E* sqrt(R* d) d, k_t = 8 G* sqrt(R* d) (Mindlin & Deresiewicz 1953, no-slip
// limit), damping proportional to d^(1/4) (Tsuji et al. 1992) with the number eta solved for e exactly.
struct HertzNormal {
  template <class T>
  DEM_HOT static NormalResponse<T> evaluate(const LawParams<T>& p, const ContactInput<T>& c) {
    const T sqrt_rd = lane_sqrt(c.r_eff * c.delta);
    const T f_elastic = (4.0 / 3.0) * p.e_star * sqrt_rd * c.delta;
    // C_n = eta sqrt(m* 4/3 E* sqrt(R* d)); C_t = eta sqrt(2/3 k_t m*) (LIGGGHTS' gamma_t, beta -> eta)
    const T scale = lane_sqrt(sqrt_rd) * c.sqrt_m_eff;
    const T kt = 8.0 * p.g_star * sqrt_rd;
    return {f_elastic - c.onset * p.hertz_cn * scale * c.vn_now, 2.0 * p.e_star * sqrt_rd, kt, p.hertz_ct * scale};
  }
  static double elastic_energy(const PairParams& p, double delta, double r_eff) {
    return (8.0 / 15.0) * p.e_star * std::sqrt(r_eff) * delta * delta * std::sqrt(delta);
  }
};

// Keeps a stored vector in the current tangent plane as the contact turns: the normal part is
// removed (LIGGGHTS' practice). LAMMPS also restores the old length; the loss is (turn angle)^2 / 2
// per step, ~1e-10 here, and the rescaling would cost a division and a square root per contact.
template <class T>
DEM_HOT V3<T> in_plane(const V3<T>& stored, const V3<T>& n) {
  return stored - dot(n, stored) * n;
}

// Tangential spring with history and the Mohr-Coulomb limit |F_s| <= mu F_n (the seeds' eqs. 2-3).
// Sliding is decided on the spring alone, as LIGGGHTS does: when k_t |xi| exceeds mu F_n the spring
// is shortened to the sliding force and the dashpot is off; otherwise spring plus dashpot, capped.
// (Taking the dashpot into the spring, as LAMMPS' xi = -(F_s + c_t v_t)/k_t does, can point the
// spring against the slip when c_t |v_t| > mu F_n and make the friction force flip sign.)
struct FrictionalTangent {
  template <class T>
  DEM_HOT static V3<T> evaluate(const LawParams<T>& p, const NormalResponse<T>& nr, T fn, const V3<T>& n,
                                const V3<T>& v_t, T dt, V3<T>& shear) {
    shear = in_plane(shear, n) + v_t * dt;
    const T limit = p.mu * fn;
    const T limit2 = limit * limit;
    const V3<T> elastic = -nr.kt * shear;
    const T elastic2 = squared_norm(elastic);
    const auto sliding = elastic2 > limit2;
    V3<T> fs = elastic - nr.ct * v_t;
    const T fs2 = squared_norm(fs);
    const auto capped = fs2 > limit2;
    // Most contacts stick below the limit: the square roots and divisions only when a lane needs them.
    if (!any_lane(sliding) && !any_lane(capped)) return fs;
    const T slide_scale = limit / lane_sqrt(elastic2);  // only kept where sliding (elastic2 > 0)
    fs = select(capped, fs * (limit / lane_sqrt(fs2)), fs);
    shear = select(sliding, shear * slide_scale, shear);
    return select(sliding, slide_scale * elastic, fs);
  }
};

struct NoRolling {
  template <class T>
  DEM_HOT static V3<T> evaluate(const LawParams<T>&, const NormalResponse<T>&, T, const ContactInput<T>&, V3<T>&) {
    return V3<T>::zero();
  }
};

// Constant directional torque (Ai et al. 2011, model A): M = -mu_r R* F_n w_r / |w_r|. The torque is
// capped at the one that stops the relative rolling within this step, so a body at rest does not
// chatter (the model itself is undefined at w_r = 0).
struct CdtRolling {
  template <class T>
  DEM_HOT static V3<T> evaluate(const LawParams<T>& p, const NormalResponse<T>&, T fn, const ContactInput<T>& c,
                                V3<T>&) {
    const V3<T> wr = in_plane(c.w_rel, c.n);
    const T w = lane_sqrt(squared_norm(wr));
    const T moment = lane_min(p.mu_r * c.r_eff * fn, c.i_roll * w / c.dt);
    return select(w == T{}, V3<T>::zero(), (-moment / w) * wr);
  }
};

// Elastic-plastic spring-dashpot (Ai et al. 2011, model C, eqs. 11-16): k_r = 2.25 k_n mu_r^2 R*^2,
// spring moment limited to mu_r R* F_n, viscous part C_r = 2 eta_r sqrt(I_r k_r) while not sliding.
struct EpsdRolling {
  template <class T>
  DEM_HOT static V3<T> evaluate(const LawParams<T>& p, const NormalResponse<T>& nr, T fn, const ContactInput<T>& c,
                                V3<T>& mk) {
    const V3<T> wr = in_plane(c.w_rel, c.n);
    const T r_eff = c.r_eff;
    const T kr = 2.25 * nr.kn_tangent * p.mu_r * p.mu_r * r_eff * r_eff;
    mk = in_plane(mk, c.n) - (kr * c.dt) * wr;
    const T limit = p.mu_r * r_eff * lane_max(fn, T{});
    const T m2 = squared_norm(mk);
    const auto mobilised = m2 >= limit * limit;  // fully mobilised: no damping (f = 0 of Ai et al.)
    mk = select(mobilised & (m2 > T{}), mk * (limit / lane_sqrt(m2)), mk);
    const T cr = 2.0 * p.rolling_damping * lane_sqrt(c.i_roll * kr);
    return select(mobilised, mk, mk - cr * wr);
  }
};

template <class Normal, bool NoTensile, bool Friction, class Rolling>
struct ContactLaw {
  static constexpr bool kRolling = !std::is_same_v<Rolling, NoRolling>;
  static constexpr bool kRollingSpring = std::is_same_v<Rolling, EpsdRolling>;
  static constexpr bool kNeedsEffectiveRadius = kRolling || std::is_same_v<Normal, HertzNormal>;
  using NormalLaw = Normal;

  // shear and roll: the contact's springs, updated in place.
  template <class T>
  DEM_HOT static ContactOutput<T> evaluate(const LawParams<T>& p, const ContactInput<T>& c, V3<T>& shear,
                                           V3<T>& roll) {
    const NormalResponse<T> nr = Normal::evaluate(p, c);
    const T fn = NoTensile ? lane_max(nr.fn, T{}) : nr.fn;
    ContactOutput<T> out;
    out.fn = fn;
    if constexpr (Friction) {
      const T vn = dot(c.v_rel, c.n);
      const V3<T> v_t = c.v_rel - vn * c.n;
      out.shear_force = FrictionalTangent::evaluate(p, nr, lane_max(fn, T{}), c.n, v_t, c.dt, shear);
    } else {
      out.shear_force = V3<T>::zero();
    }
    out.force = fn * c.n + out.shear_force;
    if constexpr (kRolling) out.roll_moment = Rolling::evaluate(p, nr, fn, c, roll);
    else out.roll_moment = V3<T>::zero();
    return out;
  }
};

}  // namespace dem
