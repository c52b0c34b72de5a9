// Elastic-plastic spring-dashpot (Ai et al. 2011, model C, eqs. 11-16): k_r = 2.25 k_n mu_r^2 R*^2,
// spring moment limited to mu_r R* F_n, viscous part C_r = 2 eta_r sqrt(I_r k_r) while not sliding
// (f = 0), at most I_r / dt, and the whole moment within mu_r R* F_n.
#pragma once

#include <array>

#include "contact/contact_input.hpp"
#include "contact/model_traits.hpp"
#include "core/scene.hpp"

namespace dem {

struct EpsdRolling {
  static constexpr std::string_view kName = "EPSD";
  static constexpr std::array<MaterialProperty, 0> kRequires{};
  static constexpr ModelParameter kDampingRatio{"rolling_damping_ratio", 0.3, 0, kUnbounded,
                                                "eta_r, the rolling dashpot's damping ratio"};
  static constexpr std::array kParameters{kDampingRatio};
  static constexpr bool kActive = true;
  static constexpr bool kHasSpring = true;

  struct Pair {
    double mu_r = 0;
    double damping = 0;
  };
  static Pair mix(const Material&, const Material&, const Interaction& in, const ContactSettings& c) {
    return {in.rolling_friction, c.parameters.value(kDampingRatio)};
  }
  template <class T>
  struct Lanes {
    T mu_r, damping;
    DEM_HOT void set(int l, const Pair& p) {
      set_lane(mu_r, l, p.mu_r);
      set_lane(damping, l, p.damping);
    }
  };

  // The energy the rolling spring (its moment mk) holds: |mk|^2 / (2 k_r).
  static double spring_energy(const Pair& p, double kn_tangent, double r_eff, const Vec3& mk) {
    const double kr = 2.25 * kn_tangent * p.mu_r * p.mu_r * r_eff * r_eff;
    return kr > 0 ? 0.5 * mk.squaredNorm() / kr : 0.0;
  }

  // mk: the contact's rolling spring, updated in place.
  template <class T>
  DEM_HOT static V3<T> evaluate(const Lanes<T>& p, const NormalResponse<T>& nr, T fn, const ContactInput<T>& c,
                                V3<T>& mk) {
    const V3<T> wr = in_plane(c.w_rel, c.n);
    const T r_eff = c.r_eff;
    const T kr = 2.25 * nr.kn_tangent * p.mu_r * p.mu_r * r_eff * r_eff;
    // Passive where k_r changes with the load (with Hertz's k_n it goes as a = sqrt(R* d)): loaded,
    // the moment is kept and the turn's stiffness is the step's mean (second order), so the energy
    // |M|^2 / 2 k_r falls; unloaded, the moment falls with k_r (an angle held, not a moment). A
    // moment held while k_r fell gained energy: a sphere spinning at 0.5 rad/s, dropped elastically
    // on a plane with no rolling dashpot, gained 0.9% of its energy.
    const T ratio = nr.stiffness_ratio;  // k_r before the drift / now
    // The square roots and divisions below are made only where a lane needs them: the same bits, and
    // in a dense pack most groups need none (two rescalings were 13% of a Hertz-EPSD pack's pair loop).
    const auto unloading = ratio > splat<T>(1.0);
    const T kept = any_lane(unloading) ? select(unloading, 1.0 / ratio, splat<T>(1.0)) : splat<T>(1.0);
    const T turn_stiffness = select(ratio < splat<T>(1.0), kr * (0.5 + 0.5 * ratio), kr);
    mk = kept * in_plane(mk, c.n) - (turn_stiffness * c.dt) * wr;
    const T limit = p.mu_r * r_eff * lane_max(fn, T{});
    const T m2 = squared_norm(mk);
    const auto mobilised = m2 >= limit * limit;  // fully mobilised: no damping (f = 0 of Ai et al.)
    const auto capped = lane_and(mobilised, m2 > T{});
    if (any_lane(capped)) mk = select(capped, mk * (limit / lane_sqrt(m2)), mk);
    // The dashpot, while the spring is below its limit: at most I_s / dt, which stops the relative
    // spin within one step (explicitly integrated, a stiffer one overshoots and makes energy:
    // eta_r 100 once made 3e4 times a settling pile's energy); and spring and dashpot together
    // within mu_r R* F_n (the dashpot on top of a spring near its limit took 1.4 times the spin
    // that limit allows at touch-down, and stopped a rolling sphere 2.8% short). I_s is the pair's
    // spin inertia, 1/I_s = 1/I_i + 1/I_j with I = 2/5 m r^2: 2/7 of the rolling inertia I_r, whose
    // m r^2 is the translation a rolling sphere drags along, which the tangential spring couples
    // in only over several steps. Capped at I_r / dt, a step reversed the spin 2.5 times over: a
    // clumped dumbbell at eta_r 1000 rolled on at 8e-6 m/s for ever with its springs at the limit.
    constexpr double kSpinOverRollingInertia = 0.4 / 1.4;
    const T cr = any_lane(p.damping > T{})
                     ? lane_min(2.0 * p.damping * lane_sqrt(c.i_roll * kr), (kSpinOverRollingInertia / c.dt) * c.i_roll)
                     : T{};  // what the expression gives for no damping: +0
    const V3<T> moment = select(mobilised, mk, mk - cr * wr);
    const T total2 = squared_norm(moment);
    const auto over = lane_and(total2 > limit * limit, total2 > T{});
    if (!any_lane(over)) return moment;
    return select(over, moment * (limit / lane_sqrt(select(over, total2, splat<T>(1)))), moment);
  }
};

}  // namespace dem
