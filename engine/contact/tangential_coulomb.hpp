// Coulomb friction: a tangential spring with history and the Mohr-Coulomb limit |F_s| <= mu F_n
// (PDEM-EGD manual eqs. 2-3). The normal model gives the spring's stiffness and dashpot.
//
// Sliding is decided on the spring alone, as LIGGGHTS does: when k_t |xi| exceeds mu F_n the spring
// is shortened to the sliding force and the dashpot is off; otherwise spring plus dashpot, capped.
// (Taking the dashpot into the spring, as LAMMPS' xi = -(F_s + c_t v_t)/k_t does, can point the
// spring against the slip when c_t |v_t| > mu F_n and make the friction force flip sign.)
#pragma once

#include <array>

#include "contact/contact_input.hpp"
#include "contact/model_traits.hpp"
#include "core/scene.hpp"

namespace dem {

struct CoulombFriction {
  static constexpr std::string_view kName = "COULOMB";
  static constexpr std::array<MaterialProperty, 0> kRequires{};
  static constexpr std::array<ModelParameter, 0> kParameters{};
  static constexpr bool kActive = true;

  // Chosen when any pair of materials has friction (a scene without it runs Frictionless).
  static bool wanted(const Scene& s) {
    for (const Interaction& in : s.interactions)
      if (in.friction > 0) return true;
    return false;
  }

  struct Pair {
    double mu = 0;
  };
  static Pair mix(const Material&, const Material&, const Interaction& in, const ContactSettings&) { return {in.friction}; }

  template <class T>
  struct Lanes {
    T mu;
    DEM_HOT void set(int l, const Pair& p) { set_lane(mu, l, p.mu); }
  };

  // fn: the compressive normal force (>= 0); shear: the spring, updated in place.
  template <class T>
  DEM_HOT static V3<T> evaluate(const Lanes<T>& p, const NormalResponse<T>& nr, T fn, const V3<T>& n,
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

// No friction anywhere in the scene: no tangential force and no spring history to keep.
struct Frictionless {
  static constexpr std::string_view kName = "NONE";
  static constexpr std::array<MaterialProperty, 0> kRequires{};
  static constexpr std::array<ModelParameter, 0> kParameters{};
  static constexpr bool kActive = false;
  static bool wanted(const Scene&) { return true; }

  struct Pair {};
  static Pair mix(const Material&, const Material&, const Interaction&, const ContactSettings&) { return {}; }
  template <class T>
  struct Lanes {
    DEM_HOT void set(int, const Pair&) {}
  };
};

}  // namespace dem
