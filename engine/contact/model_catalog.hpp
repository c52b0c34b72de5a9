// The contact models of each kind by name, as the spec loader and the docs need them: made from
// the lists of contact/models.hpp (or from any other lists, for a test's own model).
#pragma once

#include <string_view>
#include <vector>

#include "contact/model_traits.hpp"

namespace dem {

struct ModelCatalog {
  std::vector<ModelInfo> normal, tangential, rolling;

  // The model of that name in `kind`, or nullptr.
  static const ModelInfo* find(const std::vector<ModelInfo>& kind, std::string_view name);
};

template <class... Models>
std::vector<ModelInfo> infos_of(ModelList<Models...>) {
  return {info_of<Models>()...};
}

template <class Normals, class Tangentials, class Rollings>
ModelCatalog catalog_of() {
  return {infos_of(Normals{}), infos_of(Tangentials{}), infos_of(Rollings{})};
}

// The engine's own models.
const ModelCatalog& contact_models();

}  // namespace dem
