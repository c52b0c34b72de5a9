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

  // shear and roll: the contact's springs, updated in place.
  template <class T>
  DEM_HOT static ContactOutput<T> evaluate(const Lanes<T>& p, const ContactInput<T>& c, V3<T>& shear, V3<T>& roll) {
    const NormalResponse<T> nr = Normal::evaluate(p.normal, c);
    const T fn = NoTensile ? lane_max(nr.fn, T{}) : nr.fn;
    ContactOutput<T> out;
    out.fn = fn;
    if constexpr (kFriction) {
      const T vn = dot(c.v_rel, c.n);
      const V3<T> v_t = c.v_rel - vn * c.n;
      out.shear_force = Tangential::evaluate(p.tangential, nr, lane_max(fn, T{}), c.n, v_t, c.dt, shear);
    } else {
      out.shear_force = V3<T>::zero();
    }
    out.force = fn * c.n + out.shear_force;
    if constexpr (kRolling) out.roll_moment = Rolling::evaluate(p.rolling, nr, fn, c, roll);
    else out.roll_moment = V3<T>::zero();
    return out;
  }
};

}  // namespace dem
