// No rolling resistance. The rolling models (Ai et al. 2011, Powder Technol. 206:269-282:
// rolling_cdt.hpp, rolling_epsd.hpp) give the rolling moment on i (j gets the opposite) from the
// relative rolling velocity, the tangential part of w_i - w_j; this one is chosen when no pair has
// rollingFriction > 0, whatever contact.rolling says.
#pragma once

#include <array>

#include "contact/contact_input.hpp"
#include "contact/model_traits.hpp"
#include "core/scene.hpp"

namespace dem {

struct NoRolling {
  static constexpr std::string_view kName = "NONE";
  static constexpr std::array<MaterialProperty, 0> kRequires{};
  static constexpr std::array<ModelParameter, 0> kParameters{};
  static constexpr bool kActive = false;
  static constexpr bool kHasSpring = false;

  struct Pair {};
  static Pair mix(const Material&, const Material&, const Interaction&, const ContactSettings&) { return {}; }
  template <class T>
  struct Lanes {
    DEM_HOT void set(int, const Pair&) {}
  };
  template <class T>
  DEM_HOT static V3<T> evaluate(const Lanes<T>&, const NormalResponse<T>&, T, const ContactInput<T>&, V3<T>&) {
    return V3<T>::zero();
  }
};

}  // namespace dem
