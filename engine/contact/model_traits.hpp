// What a contact or bond model declares about itself, so that the spec loader, the time step and
// the kernel dispatch can ask the model instead of knowing it (contact/models.hpp lists them).
//
// A model is a type with
//   kName          its name in the schema (the enum value of proto/dem.proto, e.g. "HERTZ")
//   kRequires      the material properties it needs (the loader checks them for every material),
//                  a std::array
//   kParameters    its parameters: fields of the schema's ContactModel message, with defaults
//                  (a std::array)
//   Pair           its coefficients for one pair of materials, and `mix` that makes them
//   Lanes<T>       the same coefficients, one per lane of the force loop
//   evaluate       the law itself
// and, by kind: a normal model its contact and wave times, its stored energy and its normal and
// tangential stiffnesses at an overlap (for the energy the tangential and rolling springs hold); a
// rolling model with a spring that spring's energy (see each kind's file).
#pragma once

#include <array>
#include <span>
#include <string_view>

#include "core/model_parameters.hpp"

namespace dem {

// An ordered list of model types (the dispatch and the catalogue walk it).
template <class... Models>
struct ModelList {};

enum class MaterialProperty { Density, YoungsModulus, PoissonRatio, NormalStiffness };

// The schema's name of a material property (a field of proto/dem.proto's Material).
std::string_view material_property_name(MaterialProperty p);

// What the spec loader and the docs need to know of one model, whatever its kind.
struct ModelInfo {
  std::string_view name;
  std::span<const MaterialProperty> required;
  std::span<const ModelParameter> parameters;
};

template <class M>
constexpr ModelInfo info_of() {
  return {M::kName, std::span<const MaterialProperty>(M::kRequires), std::span<const ModelParameter>(M::kParameters)};
}

}  // namespace dem
