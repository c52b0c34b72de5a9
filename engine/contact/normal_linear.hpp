// The linear spring-dashpot normal law (the legacy TContact 1): F_n = K_n x_n - C_n xdot_n, with a
// tangential spring K_s = rns K_n and dashpot C_s = rzs C_n (PDEM-EGD manual eqs. 1-7).
#pragma once

#include <array>
#include <cmath>

#include "contact/contact_input.hpp"
#include "contact/model_traits.hpp"
#include "core/scene.hpp"

namespace dem {

struct LinearNormal {
  static constexpr std::string_view kName = "LINEAR";
  static constexpr std::array kRequires{MaterialProperty::Density, MaterialProperty::NormalStiffness};
  static constexpr ModelParameter kStiffnessRatio{"tangential_stiffness_ratio", 0.5, 0, kUnbounded,
                                                  "K_s / K_n (the manuals' rns)"};
  // C_s = C_n by default (LIGGGHTS' hooke; the manuals use 0): the normal dashpot makes F_n jump to
  // C_n v_n at first touch, and with C_s = 0 the spring alone cannot follow mu F_n at once, so each
  // sliding impact began with a stick phase that cost 2% of the friction impulse (Chung & Ooi tests
  // 5-8; docs/validation.md).
  static constexpr ModelParameter kDampingRatio{"tangential_damping_ratio", 1.0, 0, kUnbounded,
                                                "C_s / C_n (the manuals' rzs)"};
  static constexpr std::array kParameters{kStiffnessRatio, kDampingRatio};
  static constexpr bool kNeedsEffectiveRadius = false;
  // The contact time does not depend on the impact speed.
  static constexpr bool kContactTimeNeedsSpeed = false;

  struct Pair {
    double kn = 0;                // K_n = 2 kA kB / (kA + kB)   (eq. 4)
    double kt_ratio = 0;          // K_s / K_n (rns)
    double ct_ratio = 0;          // C_s / C_n (rzs)
    double zeta = 0;              // C_n = 2 zeta sqrt(m* K_n)   (eqs. 5-6; corrected for no tension)
    double cn_per_sqrt_mass = 0;  // 2 zeta sqrt(K_n): C_n = this * sqrt(m*)
  };
  static Pair mix(const Material& a, const Material& b, const Interaction& in, const ContactSettings& c);

  template <class T>
  struct Lanes {
    T kn, kt_ratio, ct_ratio, cn_per_sqrt_mass;
    DEM_HOT void set(int l, const Pair& p) {
      set_lane(kn, l, p.kn);
      set_lane(kt_ratio, l, p.kt_ratio);
      set_lane(ct_ratio, l, p.ct_ratio);
      set_lane(cn_per_sqrt_mass, l, p.cn_per_sqrt_mass);
    }
  };

  // C_n = 2 zeta sqrt(m* K_n) with m* the reduced mass (the manuals' zeta sqrt(2 M K_n) for two
  // equal spheres of mass M).
  template <class T>
  DEM_HOT static NormalResponse<T> evaluate(const Lanes<T>& p, const ContactInput<T>& c) {
    const T cn = p.cn_per_sqrt_mass * c.sqrt_m_eff;
    const T spring = spring_with_first_touch(
        p.kn * c.delta, c.delta, c.first_touch, [&](T x) { return spring_energy(p.kn, x); },
        [&](T x) { return p.kn * x; });
    NormalResponse<T> out{spring - c.onset * cn * c.vn_now, p.kn, p.kt_ratio * p.kn, p.ct_ratio * cn};
    out.cn = c.onset * cn;
    return out;
  }

  template <class T>
  DEM_HOT static T spring_energy(T kn, T delta) {
    return 0.5 * kn * delta * delta;
  }
  static double elastic_energy(const Pair& p, double delta, double /*r_eff*/) { return spring_energy(p.kn, delta); }
  static double spring_force(const Pair& p, double delta, double /*r_eff*/) { return p.kn * delta; }
  // The stiffnesses evaluate() gives at this overlap: dF_n/d(delta) and the tangential spring's.
  static double normal_stiffness(const Pair& p, double /*delta*/, double /*r_eff*/) { return p.kn; }
  static double tangential_stiffness(const Pair& p, double /*delta*/, double /*r_eff*/) { return p.kt_ratio * p.kn; }

  // T = pi / sqrt(K_n/m* (1 - zeta^2)) (eq. 7 with m* the reduced mass). Past zeta = 0.5 (e < 0.2
  // with tension; the no-tension fit reaches zeta > 1) the dashpot, not the spring, sets the time
  // scale: T = pi / (omega sqrt(3/4) 2 zeta), which joins eq. 7 at zeta = 0.5.
  static double contact_time(const Pair& p, double m_eff, double /*r_eff*/, double /*speed*/);
  // The time of an elastic wave across the smallest sphere: not a limit of this law.
  static double wave_time(const Material&, double /*r_min*/) { return kUnbounded; }
};

}  // namespace dem
