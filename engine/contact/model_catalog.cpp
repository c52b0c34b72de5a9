#include "contact/model_catalog.hpp"

#include "contact/models.hpp"

namespace dem {

std::string_view material_property_name(MaterialProperty p) {
  switch (p) {
    case MaterialProperty::Density:
      return "density";
    case MaterialProperty::YoungsModulus:
      return "youngsModulus";
    case MaterialProperty::PoissonRatio:
      return "poissonRatio";
    case MaterialProperty::NormalStiffness:
      return "normalStiffness";
  }
  return "?";
}

const ModelInfo* ModelCatalog::find(const std::vector<ModelInfo>& kind, std::string_view name) {
  for (const ModelInfo& m : kind)
    if (m.name == name) return &m;
  return nullptr;
}

const ModelCatalog& contact_models() {
  static const ModelCatalog catalog = catalog_of<NormalModels, TangentialModels, RollingModels>();
  return catalog;
}

}  // namespace dem
