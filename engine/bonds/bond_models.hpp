// The bond models, each a type: the parallel bond (forces and moments) and the contact bond
// (forces only), both the elastic disc of bond_law.hpp. A model owns how a bond's stiffness and
// strength follow from the two particles it glues, and its springs' shortest period for the time
// step. BondModels lists them; a model's kName is the schema's Bonds.Model value.
#pragma once

#include <array>
#include <string_view>

#include "bonds/bond_law.hpp"
#include "contact/model_traits.hpp"
#include "core/scene.hpp"

namespace dem {

template <bool Moments>
struct DiscBond {
  static constexpr bool kMoments = Moments;
  static constexpr std::array<MaterialProperty, 0> kRequires{};
  static constexpr std::array<ModelParameter, 0> kParameters{};  // its fields are the schema's Bonds

  // A bond between spheres of radii ri and rj: Rb = lambda min(ri, rj), kn = Eb / (ri + rj), ks =
  // ratio kn, the strengths scaled by `strength_scale` (zones, spread). Not yet glued.
  static Bond between(const BondSettings& s, double ri, double rj, double strength_scale);
  // The shortest half-period of the springs of a bond between two spheres of radius r and mass m
  // (the smallest of the scene): pi sqrt(m*/k) for the axial and shear springs (m* = m/2), and for
  // the parallel bond also pi sqrt(I*/k) for bending and twist (I* = 0.4 m r^2 / 2).
  static double shortest_time(const BondSettings& s, double r, double m);
};

struct ParallelBond : DiscBond<true> {
  static constexpr std::string_view kName = "PARALLEL";
};
struct ContactBond : DiscBond<false> {
  static constexpr std::string_view kName = "CONTACT";
};

using BondModels = ModelList<ParallelBond, ContactBond>;

// The same for the model a scene's bonds name (settings.model); throws SceneError for a name not
// in BondModels.
Bond bond_between(const BondSettings& s, double ri, double rj, double strength_scale);
double bond_shortest_time(const BondSettings& s, double r, double m);

}  // namespace dem
