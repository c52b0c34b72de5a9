// Coulomb friction: a tangential spring with history and the Mohr-Coulomb limit |F_s| <= mu F_n
// (PDEM-EGD manual eqs. 2-3). The normal model gives the spring's stiffness and dashpot.
//
// Sliding is decided on the spring alone, as LIGGGHTS does: when k_t |xi| exceeds mu F_n the spring
// is shortened to mu F_n / k_t. (Taking the dashpot into the spring, as LAMMPS'
// xi = -(F_s + c_t v_t)/k_t does, can point the spring against the slip when c_t |v_t| > mu F_n and
// make the friction force flip sign.) The force is spring plus dashpot, capped at mu F_n, sliding or
// not: in gross sliding both oppose the slip and the cap gives mu F_n; where the slip reverses
// while the spring is held at the limit (the normal force falling at the end of an impact), the
// dashpot opposes the spring. Turning the dashpot off when sliding began, as LIGGGHTS does, made the
// force jump there (from +0.36 mu F_n to -mu F_n in a partial-slip impact, linear law, e = 0.5), at
// a moment known only to a step: the spin came out first order in the step.
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
  static Pair mix(const Material&, const Material&, const Interaction& in, const ContactSettings&) {
    return {in.friction};
  }

  template <class T>
  struct Lanes {
    T mu;
    DEM_HOT void set(int l, const Pair& p) { set_lane(mu, l, p.mu); }
  };

  // fn: the compressive normal force (>= 0); shear: the spring, updated in place.
  //
  // The spring moves with the half-step tangential velocity, over the part of the drift in contact:
  // on a contact's first sample only delta / first_touch of it. The dashpot resists the full step's
  // velocity (contact_input.hpp), with the window share of a contact boundary, as the normal
  // dashpot does. Without either, a partial-slip impact's spin (linear law, e = 0.5) converged at
  // first order: a whole step's travel on the first sample left the spring up to v_t dt long, which
  // moved the end of the slip phase that the dashpot holds at mu F_n by up to a step.
  template <class T>
  DEM_HOT static V3<T> evaluate(const Lanes<T>& p, const NormalResponse<T>& nr, T fn, const ContactInput<T>& c,
                                V3<T>& shear) {
    const V3<T>& n = c.n;
    const V3<T> v_t = c.v_rel - dot(c.v_rel, n) * n;
    T moved_for = c.dt;
    const auto fresh = c.first_touch > T{};
    if (any_lane(fresh))  // rare: skip the division
      moved_for =
          select(fresh, c.dt * lane_min(c.delta / select(fresh, c.first_touch, splat<T>(1.0)), splat<T>(1.0)), c.dt);
    // Passive where k_t changes with the load (Hertz-Mindlin's k_t = 8 G* a): loaded, the force is
    // carried over, F = k_t(before) xi + k_t(mean) dxi (Mindlin & Deresiewicz 1953's incremental
    // loading, the travel's stiffness the step's mean for second order), so the stored energy
    // |F|^2 / 2 k_t falls; unloaded, the displacement is kept and the force falls with a (LAMMPS'
    // mindlin_rescale/force). A displacement held while k_t grew gained energy no force paid for:
    // an elastic oblique impact (e = 1, mu = 0.4, v_t / v_n = 0.5) gained 1.4% of its energy in
    // mid-contact, at every step. (The linear law's ratios are 1: no cost.)
    const auto loaded = nr.stiffness_ratio < splat<T>(1.0);
    const T kept = select(loaded, nr.stiffness_ratio, splat<T>(1.0));
    const T travel_stiffness = select(loaded, nr.stiffness_mean, splat<T>(1.0));
    shear = kept * in_plane(shear, n) + travel_stiffness * v_t * moved_for;
    const T limit = p.mu * fn;
    const T limit2 = limit * limit;
    V3<T> elastic = -nr.kt * shear;
    const T elastic2 = squared_norm(elastic);
    const auto sliding = elastic2 > limit2;
    const V3<T> damping = (c.onset * nr.ct) * c.vt_now;
    // Most contacts stick below the limit: the square roots and divisions only when a lane needs them.
    if (any_lane(sliding)) {
      const T slide_scale = limit / lane_sqrt(select(sliding, elastic2, splat<T>(1.0)));
      shear = select(sliding, shear * slide_scale, shear);
      elastic = select(sliding, elastic * slide_scale, elastic);
    }
    const V3<T> fs = elastic - damping;
    const T fs2 = squared_norm(fs);
    const auto capped = fs2 > limit2;
    if (!any_lane(capped)) return fs;
    return select(capped, fs * (limit / lane_sqrt(select(capped, fs2, splat<T>(1.0)))), fs);
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
