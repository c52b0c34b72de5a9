// Constant directional torque (Ai et al. 2011, model A): M = -mu_r R* F_n w_r / |w_r|. The torque is
// capped at the one that stops the relative rolling within this step, so a body at rest does not
// chatter (the model itself is undefined at w_r = 0).
#pragma once

#include <array>

#include "contact/contact_input.hpp"
#include "contact/model_traits.hpp"
#include "core/scene.hpp"

namespace dem {

struct CdtRolling {
  static constexpr std::string_view kName = "CDT";
  static constexpr std::array<MaterialProperty, 0> kRequires{};
  static constexpr std::array<ModelParameter, 0> kParameters{};
  static constexpr bool kActive = true;
  static constexpr bool kHasSpring = false;

  struct Pair {
    double mu_r = 0;
  };
  static Pair mix(const Material&, const Material&, const Interaction& in, const ContactSettings&) {
    return {in.rolling_friction};
  }
  template <class T>
  struct Lanes {
    T mu_r;
    DEM_HOT void set(int l, const Pair& p) { set_lane(mu_r, l, p.mu_r); }
  };

  template <class T>
  DEM_HOT static V3<T> evaluate(const Lanes<T>& p, const NormalResponse<T>&, T fn, const ContactInput<T>& c, V3<T>&) {
    const V3<T> wr = in_plane(c.w_rel, c.n);
    const T w = lane_sqrt(squared_norm(wr));
    const T moment = lane_min(p.mu_r * c.r_eff * lane_max(fn, T{}), c.i_roll * w / c.dt);  // no moment in tension
    return select(w == T{}, V3<T>::zero(), (-moment / w) * wr);
  }
};

}  // namespace dem
