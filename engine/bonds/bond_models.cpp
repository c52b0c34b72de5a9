#include "bonds/bond_models.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/errors.hpp"

namespace dem {

template <bool Moments>
Bond DiscBond<Moments>::between(const BondSettings& s, double ri, double rj, double strength_scale) {
  Bond b;
  b.geometry = BondGeometry::of(s.radius_multiplier * std::min(ri, rj));
  b.kn = s.youngs_modulus / (ri + rj);
  b.ks = s.shear_stiffness_ratio * b.kn;
  b.tensile_strength = s.tensile_strength * strength_scale;
  b.shear_strength = s.shear_strength * strength_scale;
  b.moments = Moments;
  return b;
}

template <bool Moments>
double DiscBond<Moments>::shortest_time(const BondSettings& s, double r, double m) {
  const double m_eff = m / 2, i_eff = 0.4 * m * r * r / 2;
  const double rb = s.radius_multiplier * r, kn = s.youngs_modulus / (2 * r), ks = s.shear_stiffness_ratio * kn;
  const double area = std::numbers::pi * rb * rb, inertia = area * rb * rb / 4;
  const double stiffest = std::max(kn, ks);
  double t = std::numbers::pi * std::sqrt(m_eff / (stiffest * area));
  if (Moments) t = std::min(t, std::numbers::pi * std::sqrt(i_eff / (stiffest * 2 * inertia)));
  return t;
}

template struct DiscBond<true>;
template struct DiscBond<false>;

namespace {

template <class F, class... Models>
auto with_model(std::string_view name, ModelList<Models...>, F&& f) {
  using Result = decltype(f(DiscBond<true>{}));
  Result out{};
  const bool found = ((Models::kName == name && (out = f(Models{}), true)) || ...);
  if (!found) throw SceneError("bonds.model: no bond model named \"" + std::string(name) + "\"");
  return out;
}

}  // namespace

Bond bond_between(const BondSettings& s, double ri, double rj, double strength_scale) {
  return with_model(s.model, BondModels{},
                    [&](auto model) { return decltype(model)::between(s, ri, rj, strength_scale); });
}

double bond_shortest_time(const BondSettings& s, double r, double m) {
  return with_model(s.model, BondModels{}, [&](auto model) { return decltype(model)::shortest_time(s, r, m); });
}

}  // namespace dem
