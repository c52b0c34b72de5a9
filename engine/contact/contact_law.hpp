// One contact law: a normal model, the tension clamp, a tangential model and a rolling model,
// combined at compile time into the type the force loops inline (sim/kernel_factory_impl.hpp makes
// one loop per combination; contact/models.hpp lists the models).
#pragma once

#include <type_traits>

#include "contact/contact_input.hpp"
#include "core/scene.hpp"

namespace dem {

template <class Normal, bool NoTensile, class Tangential, class Rolling>
struct ContactLaw {
  using NormalModel = Normal;
  using TangentialModel = Tangential;
  using RollingModel = Rolling;
  static constexpr bool kNoTensile = NoTensile;
  static constexpr bool kFriction = Tangential::kActive;
  static constexpr bool kRolling = Rolling::kActive;
  static constexpr bool kRollingSpring = Rolling::kHasSpring;
  static constexpr bool kNeedsEffectiveRadius = kRolling || Normal::kNeedsEffectiveRadius;

  // The coefficients of one pair of materials, each model's own.
  struct Pair {
    typename Normal::Pair normal;
    typename Tangential::Pair tangential;
    typename Rolling::Pair rolling;
  };
  static Pair mix(const Material& a, const Material& b, const Interaction& in, const ContactSettings& c) {
    return {Normal::mix(a, b, in, c), Tangential::mix(a, b, in, c), Rolling::mix(a, b, in, c)};
  }

  // The energy a contact holds: its normal spring's, and its tangential spring's (displacement
  // `shear`: k_t |shear|^2 / 2) and rolling spring's (moment `roll`), where the law has them.
  static double stored_energy(const Pair& p, double delta, double r_eff, const Vec3& shear, const Vec3& roll) {
    double e = Normal::elastic_energy(p.normal, delta, r_eff);
    if constexpr (kFriction) e += 0.5 * Normal::tangential_stiffness(p.normal, delta, r_eff) * shear.squaredNorm();
    if constexpr (kRollingSpring)
      e += Rolling::spring_energy(p.rolling, Normal::normal_stiffness(p.normal, delta, r_eff), r_eff, roll);
    return e;
  }

  // The same, one material pair per lane.
  template <class T>
  struct Lanes {
    typename Normal::template Lanes<T> normal;
    typename Tangential::template Lanes<T> tangential;
    typename Rolling::template Lanes<T> rolling;
    DEM_HOT void set(int l, const Pair& p) {
      normal.set(l, p.normal);
      tangential.set(l, p.tangential);
      rolling.set(l, p.rolling);
    }
    DEM_HOT static Lanes all(const Pair& p) {
      Lanes out;
      for (int l = 0; l < lane_count<T>(); ++l) out.set(l, p);
      return out;
    }
  };

  // With tension the dashpot still pulls at parting, and the part of the next step's window before
  // the parting is counted now when the next force evaluation will find the bodies apart
  // (boundary_share counts only this window's). Whether it will depends on this step's pull, which
  // that count increases: the share is settled against the separation speed of the next drift,
  // v_n + dt F_n / m* (velocity Verlet's). Where counting the next window's part would itself keep
  // the contact to the next evaluation, and not counting it would not, the bodies are made to part at
  // that evaluation (below). Guessed from this step's speed alone, the count was sometimes
  // made and the contact then found again (linear law, e = 0.2: rebounds 3.7% short at two of every
  // twenty positions of the steps); never made, up to 2.9% long. (Hertz's dashpot fades at parting
  // as d^(1/4) and takes no share.)
  template <class T>
  DEM_HOT static NormalResponse<T> settle_parting(const typename Normal::template Lanes<T>& p, ContactInput<T> c,
                                                  NormalResponse<T> nr) {
    const T vn = dot(c.v_rel, c.n);
    const auto parting = lane_and(c.delta<c.travel, vn> T{});
    if (!any_lane(parting)) return nr;
    const T mass = c.sqrt_m_eff * c.sqrt_m_eff;
    const T gap = c.delta / c.dt;  // the separation speed that parts the bodies at the next evaluation
    // the whole window (nothing of the next one counted)
    c.onset = select(parting, splat<T>(1.0), c.onset);
    const NormalResponse<T> whole = Normal::evaluate(p, c);
    const T next_whole = vn + c.dt * whole.fn / mass;
    const auto parts = lane_and(parting, next_whole > gap);
    if (!any_lane(parts)) return whole;
    // they part before the next evaluation: count up to the parting
    const T first = 0.5 + gap / select(parts, next_whole, splat<T>(1.0));
    c.onset = select(parts, first, c.onset);
    const NormalResponse<T> counted = Normal::evaluate(p, c);
    const T next_counted = vn + c.dt * counted.fn / mass;
    const auto still_parts = lane_and(parts, next_counted > gap);
    // The share at which the next drift ends the contact exactly (the speed is affine in the share):
    // the truth, parting at the next evaluation, counts 1/2 of the next window now. Far below that
    // (under 1.25), the drift is made to end just short of parting and the next evaluation counts
    // its half; else just past it, and the half is this share's.
    const T slope = (next_counted - next_whole) / select(parts, first - 1.0, splat<T>(1.0));
    const T safe_slope = select(lane_and(parts, slope != T{}), slope, splat<T>(1.0));
    const T exact = 1.0 + (gap - next_whole) / safe_slope;
    const T nudge = select(exact < 1.25, splat<T>(-1e-6), splat<T>(1e-6));
    const T settled = 1.0 + ((1.0 + nudge) * gap - next_whole) / safe_slope;
    // (still parting with the count made: the count stays; counting more would pull them together)
    c.onset = select(parts, select(still_parts, first, settled), c.onset);
    return Normal::evaluate(p, c);
  }

  // The force to add over the step after a contact parted: the spring's impulse the last sample
  // could not see (spring_boundary_correction), with `before` the overlap at that sample and `lost`
  // the overlap lost since. A normal model without spring_force takes none. With the no-tension
  // clamp a damped contact's force reached zero before the overlap did: no kink at delta = 0.
  static double parting_correction(const Pair& p, double before, double lost, double r_eff, double vn,
                                   double sqrt_m_eff) {
    if constexpr (requires { Normal::spring_force(p.normal, before, r_eff); }) {
      if constexpr (NoTensile) {
        ContactInput<double> c{};
        c.delta = before;
        c.vn_now = vn;
        c.onset = 1;
        c.sqrt_m_eff = sqrt_m_eff;
        c.r_eff = r_eff;
        typename Normal::template Lanes<double> lanes{};
        lanes.set(0, p.normal);
        if (Normal::evaluate(lanes, c).fn <= 0) return 0;
      }
      return spring_boundary_correction(
          before, lost, [&](double x) { return Normal::elastic_energy(p.normal, x, r_eff); },
          [&](double x) { return Normal::spring_force(p.normal, x, r_eff); });
    } else {
      return 0;
    }
  }

  // shear and roll: the contact's springs, updated in place.
  template <class T>
  DEM_HOT static ContactOutput<T> evaluate(const Lanes<T>& p, const ContactInput<T>& c, V3<T>& shear, V3<T>& roll) {
    NormalResponse<T> nr = Normal::evaluate(p.normal, c);
    if constexpr (!NoTensile) nr = settle_parting(p.normal, c, nr);
    const T fn = NoTensile ? lane_max(nr.fn, T{}) : nr.fn;
    ContactOutput<T> out;
    out.fn = fn;
    out.kn = nr.kn_tangent;
    out.cn = nr.cn;
    if constexpr (kFriction) {
      out.shear_force = Tangential::evaluate(p.tangential, nr, lane_max(fn, T{}), c, shear);
    } else {
      out.shear_force = V3<T>::zero();
    }
    out.force = fn * c.n + out.shear_force;
    if constexpr (kRolling)
      out.roll_moment = Rolling::evaluate(p.rolling, nr, fn, c, roll);
    else
      out.roll_moment = V3<T>::zero();
    return out;
  }
};

}  // namespace dem
