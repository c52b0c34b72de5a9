// Hertz-Mindlin (the legacy TContact 2): F_n = 4/3 E* sqrt(R* d) d, tangential stiffness
// k_t = 8 G* sqrt(R* d) (Mindlin & Deresiewicz 1953, no-slip limit), damping proportional to d^(1/4)
// (Tsuji et al. 1992) with the damping number eta solved for the requested restitution exactly.
#pragma once

#include <array>
#include <cmath>

#include "contact/contact_input.hpp"
#include "contact/model_traits.hpp"
#include "core/scene.hpp"

namespace dem {

struct HertzNormal {
  static constexpr std::string_view kName = "HERTZ";
  static constexpr std::array kRequires{MaterialProperty::Density, MaterialProperty::YoungsModulus,
                                        MaterialProperty::PoissonRatio};
  static constexpr std::array<ModelParameter, 0> kParameters{};
  static constexpr bool kNeedsEffectiveRadius = true;
  static constexpr bool kContactTimeNeedsSpeed = true;

  struct Pair {
    double e_star = 0;    // 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2
    double g_star = 0;    // 1/G* = 2(2-nu1)(1+nu1)/E1 + 2(2-nu2)(1+nu2)/E2
    double eta = 0;       // damping number of the dimensionless Hertz impact (restitution_damping.hpp)
    double hertz_cn = 0;  // eta sqrt(4/3 E*):  C_n = this * (R* d)^(1/4) * sqrt(m*)
    double hertz_ct = 0;  // eta sqrt(16/3 G*): C_t = this * (R* d)^(1/4) * sqrt(m*)
  };
  static Pair mix(const Material& a, const Material& b, const Interaction& in, const ContactSettings& c);

  template <class T>
  struct Lanes {
    T e_star, g_star, hertz_cn, hertz_ct;
    DEM_HOT void set(int l, const Pair& p) {
      set_lane(e_star, l, p.e_star);
      set_lane(g_star, l, p.g_star);
      set_lane(hertz_cn, l, p.hertz_cn);
      set_lane(hertz_ct, l, p.hertz_ct);
    }
  };

  template <class T>
  DEM_HOT static NormalResponse<T> evaluate(const Lanes<T>& p, const ContactInput<T>& c) {
    const T sqrt_rd = lane_sqrt(c.r_eff * c.delta);
    const T f_elastic = spring_with_first_touch((4.0 / 3.0) * p.e_star * sqrt_rd * c.delta, c.delta, c.first_touch,
                                                [&](T x) { return spring_energy(p.e_star, c.r_eff, x); },
                                                [&](T x) { return spring_force(p.e_star, c.r_eff, x); });
    // C_n = eta sqrt(m* 4/3 E* sqrt(R* d)); C_t = eta sqrt(2/3 k_t m*) (LIGGGHTS' gamma_t, beta -> eta)
    const T quarter = lane_sqrt(sqrt_rd);  // (R* d)^(1/4)
    const T scale = quarter * c.sqrt_m_eff;
    const T kt = 8.0 * p.g_star * sqrt_rd;
    // At a contact boundary (see boundary_share) the dashpot, which rises as d^(1/4), acts over the
    // part of the window inside the contact, (s + 1/2) dt with s = d / travel: its exact impulse there
    // is that of (R* travel)^(1/4) (s + 1/2)^(5/4) / (5/4) in place of (R* d)^(1/4). The linear law's
    // share (s + 1/2), right for a dashpot that jumps, left a boundary error of order dt^(5/4).
    T damping_quarter = quarter;
    const auto boundary = c.delta < c.travel;
    if (any_lane(boundary)) {
      const T reach = c.delta / c.travel + 0.5;
      const T window = lane_sqrt(lane_sqrt(c.r_eff * c.travel)) * reach * lane_sqrt(lane_sqrt(reach)) * 0.8;
      damping_quarter = select(boundary, window, quarter);
    }
    const T cn = p.hertz_cn * damping_quarter * c.sqrt_m_eff;
    NormalResponse<T> out{f_elastic - cn * c.vn_now, 2.0 * p.e_star * sqrt_rd, kt, p.hertz_ct * scale};
    out.cn = cn;
    stiffness_change(c, out);
    return out;
  }

  // Over the drift (NormalResponse): k(before) / k(now) = r = sqrt(d_before / d), d_before the
  // overlap before the drift from the half-step normal velocity that made it; and the mean of
  // sqrt(d) over d's straight path, over sqrt(d): 2/3 (1 + r + r^2) / (1 + r). (The mean of the two
  // ends, (1 + r) / 2, is 1/2 where the contact begins, against 2/3: a glancing stuck impact kept
  // that first step's error, order dt^1.5.)
  template <class T>
  DEM_HOT static void stiffness_change(const ContactInput<T>& c, NormalResponse<T>& out) {
    const auto touching = c.delta > T{};
    const T before = lane_max(c.delta + dot(c.v_rel, c.n) * c.dt, T{});
    const T r = select(touching, lane_sqrt(before / select(touching, c.delta, splat<T>(1.0))), splat<T>(1.0));
    out.stiffness_ratio = r;
    out.stiffness_mean = (2.0 / 3.0) * (1.0 + r + r * r) / (1.0 + r);
  }

  template <class T>
  DEM_HOT static T spring_energy(T e_star, T r_eff, T delta) {
    return (8.0 / 15.0) * e_star * lane_sqrt(r_eff * delta) * delta * delta;
  }
  template <class T>
  DEM_HOT static T spring_force(T e_star, T r_eff, T delta) {
    return (4.0 / 3.0) * e_star * lane_sqrt(r_eff * delta) * delta;
  }
  static double elastic_energy(const Pair& p, double delta, double r_eff) {
    return spring_energy(p.e_star, r_eff, delta);
  }
  static double spring_force(const Pair& p, double delta, double r_eff) { return spring_force(p.e_star, r_eff, delta); }
  // The stiffnesses evaluate() gives at this overlap: dF_n/d(delta) and the tangential spring's.
  static double normal_stiffness(const Pair& p, double delta, double r_eff) {
    return 2.0 * p.e_star * std::sqrt(r_eff * delta);
  }
  static double tangential_stiffness(const Pair& p, double delta, double r_eff) {
    return 8.0 * p.g_star * std::sqrt(r_eff * delta);
  }

  // t_c = 2.9432 alpha_max / V, alpha_max = (15 m* V^2 / (16 sqrt(R*) E*))^(2/5) (docs/validation.md).
  // A damping number eta > 1 (e < 0.4 without tension) makes the dashpot the faster process: the
  // time scale shrinks by eta, as the linear one does by 2 zeta.
  static double contact_time(const Pair& p, double m_eff, double r_eff, double speed);
  // The Rayleigh time pi R sqrt(rho/G) / (0.1631 nu + 0.8766) of the smallest sphere.
  static double wave_time(const Material& m, double r_min);
};

}  // namespace dem
