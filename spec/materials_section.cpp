// The contact models, the materials and their interactions (JobSpec.contact, .materials, .interactions).
#include <google/protobuf/descriptor.h>

#include <span>

#include "contact/model_catalog.hpp"
#include "contact/models.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {
namespace {

// The models the spec's contact block names (contact/models.hpp), with their parameters: each
// parameter field given must belong to one of the chosen models and lie in its range.
struct ContactChoice {
  ContactSettings settings;
  const ModelInfo* normal = nullptr;  // nullptr: an unknown name (already reported)
};

ContactChoice contact_models_of(const api::ContactModel& in, Checker& check) {
  const ModelCatalog& catalog = contact_models();
  ContactChoice out;
  // An unset enum (its *_UNSPECIFIED value) is the default model.
  const std::string normal = in.normal() == api::ContactModel::NORMAL_UNSPECIFIED
                                 ? std::string(LinearNormal::kName)
                                 : api::ContactModel::Normal_Name(in.normal());
  const std::string rolling = in.rolling() == api::ContactModel::ROLLING_UNSPECIFIED
                                  ? std::string(NoRolling::kName)
                                  : api::ContactModel::Rolling_Name(in.rolling());
  out.normal = ModelCatalog::find(catalog.normal, normal);
  const ModelInfo* rolling_model = ModelCatalog::find(catalog.rolling, rolling);
  if (!out.normal) check.fail("contact.normal", "no normal model \"" + normal + "\" in this build");
  if (!rolling_model) check.fail("contact.rolling", "no rolling model \"" + rolling + "\" in this build");
  out.settings.normal = normal;
  out.settings.rolling = rolling;
  out.settings.no_tensile_force = in.has_no_tensile_force() ? in.no_tensile_force() : true;

  std::vector<const ModelInfo*> chosen{out.normal, rolling_model};
  for (const ModelInfo& m : catalog.tangential) chosen.push_back(&m);
  const google::protobuf::Descriptor* descriptor = in.GetDescriptor();
  const google::protobuf::Reflection* reflection = in.GetReflection();
  for (int f = 0; f < descriptor->field_count(); ++f) {
    const google::protobuf::FieldDescriptor* field = descriptor->field(f);
    if (field->type() != google::protobuf::FieldDescriptor::TYPE_DOUBLE || !reflection->HasField(in, field)) continue;
    const std::string path = "contact." + field->json_name();
    const double value = reflection->GetDouble(in, field);
    const ModelParameter* parameter = nullptr;
    for (const ModelInfo* m : chosen)
      for (const ModelParameter& p : m ? m->parameters : std::span<const ModelParameter>{})
        if (p.field == field->name()) parameter = &p;
    if (!parameter) {
      std::string owners;
      for (const auto* kind : {&catalog.normal, &catalog.rolling})
        for (const ModelInfo& m : *kind)
          for (const ModelParameter& p : m.parameters)
            if (p.field == field->name()) owners += (owners.empty() ? "" : " or ") + std::string(m.name);
      check.fail(path, "is not used by the chosen models (normal " + normal + ", rolling " + rolling + ")" +
                           (owners.empty() ? std::string() : "; it is a parameter of " + owners));
      continue;
    }
    if (!std::isfinite(value) || value < parameter->min || value > parameter->max) {
      // an unbounded range is open at infinity: "[0, inf)", which an infinite value is not in
      const std::string upper = std::isfinite(parameter->max) ? num(parameter->max) + "]" : std::string("inf)");
      check.fail(path, "must be in [" + num(parameter->min) + ", " + upper + " (got " + num(value) +
                           "): " + std::string(parameter->meaning));
      continue;
    }
    out.settings.parameters.set(parameter->field, value);
  }
  return out;
}

void check_required_properties(const ModelInfo& model, const Material& m, const std::string& path, Checker& check) {
  for (MaterialProperty property : model.required) {
    const std::string field = path + "." + std::string(material_property_name(property));
    switch (property) {
      case MaterialProperty::Density:
        break;  // checked for every particle material
      case MaterialProperty::YoungsModulus:
        check.positive(field, m.youngs_modulus, kModulus);
        break;
      case MaterialProperty::PoissonRatio:
        break;  // checked for every material
      case MaterialProperty::NormalStiffness:
        check.positive(field, m.normal_stiffness, kStiffness);
        break;
    }
  }
}

}  // namespace

int SpecContext::material(const std::string& name, const std::string& path) {
  auto it = material_index.find(name);
  if (it == material_index.end()) {
    check.fail(path, "unknown material \"" + name + "\"");
    return -1;
  }
  return it->second;
}

int SpecContext::particle_material(const std::string& name, const std::string& path) {
  const int m = material(name, path);
  if (m >= 0 && scene.materials[m].rigid) {
    check.fail(path, "material \"" + name + "\" is rigid: only walls may use it");
    return -1;
  }
  if (m >= 0) particle_materials.insert(m);
  return m;
}

std::optional<PairInteraction> load_interaction(const api::Interaction& in, const std::string& path, SpecContext& ctx) {
  Checker& check = ctx.check;
  const int a = ctx.material(in.a(), path + ".a"), b = ctx.material(in.b(), path + ".b");
  check.in_range(path + ".restitution", in.restitution(), 0, 1, true, false);
  check.non_negative(path + ".friction", in.friction(), kCoefficient);
  // mu_r is the rolling moment's lever over the radius: past 1 it would act outside the sphere
  // (and EPSD's rolling spring, 2.25 k_n mu_r^2 R^2, would outrun the step chosen for k_n)
  check.in_range(path + ".rollingFriction", in.rolling_friction(), 0, 1, false, false);
  if (in.rolling_friction() > 0 && ctx.scene.contact.rolling == NoRolling::kName)
    check.fail(path + ".rollingFriction",
               "is " + num(in.rolling_friction()) + " but contact.rolling is NONE: choose CDT or EPSD, or set it to 0");
  if (a < 0 || b < 0) return std::nullopt;
  return PairInteraction{a, b, Interaction{in.restitution(), in.friction(), in.rolling_friction()}};
}

void load_materials(const api::JobSpec& spec, SpecContext& ctx) {
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
  // contact models, and the material properties and parameters they ask for
  const ContactChoice contact = contact_models_of(spec.contact(), check);
  scene.contact = contact.settings;

  // materials: refused at once past the limit, before anything grows with the square of their count
  if (spec.materials_size() > check.limits.max_materials)
    throw SpecError({"materials: at most " + std::to_string(check.limits.max_materials) + " materials (got " +
                     std::to_string(spec.materials_size()) + ")"});
  if (spec.materials().empty()) check.fail("materials", "at least one material is required");
  for (int m = 0; m < spec.materials_size(); ++m) {
    const auto& in = spec.materials(m);
    const std::string path = at("materials", m);
    Material out;
    out.name = in.name();
    out.density = in.density();
    out.youngs_modulus = in.youngs_modulus();
    out.poisson_ratio = in.poisson_ratio();
    out.normal_stiffness = in.normal_stiffness();
    out.rigid = in.rigid();
    if (in.name().empty())
      check.fail(path + ".name", "a material needs a name");
    else if (!ctx.material_index.emplace(in.name(), m).second)
      check.fail(path + ".name", "duplicate material name \"" + in.name() + "\"");
    if (!out.rigid) {
      // every particle needs a density (its mass); a Poisson ratio, where given, must be one
      check.positive(path + ".density", out.density, kDensity);
      check.in_range(path + ".poissonRatio", out.poisson_ratio, -1, 0.5, true, true);
      if (contact.normal) check_required_properties(*contact.normal, out, path, check);
    }
    scene.materials.push_back(out);
  }

  const int nm = static_cast<int>(scene.materials.size());
  scene.interactions.assign(static_cast<size_t>(nm) * nm, Interaction{});
  ctx.interaction_given.assign(static_cast<size_t>(nm) * nm, 0);
  for (int k = 0; k < spec.interactions_size(); ++k) {
    const std::string path = at("interactions", k);
    const std::optional<PairInteraction> pair = load_interaction(spec.interactions(k), path, ctx);
    if (!pair) continue;
    const auto [a, b, value] = *pair;
    if (ctx.interaction_given[a * nm + b])
      check.fail(path, "a second interaction for \"" + spec.interactions(k).a() + "\" and \"" +
                           spec.interactions(k).b() + "\"");
    scene.interactions[a * nm + b] = scene.interactions[b * nm + a] = value;
    ctx.interaction_given[a * nm + b] = ctx.interaction_given[b * nm + a] = 1;
  }
}

void check_interactions_complete(SpecContext& ctx) {
  const Scene& scene = ctx.scene;
  const int nm = static_cast<int>(scene.materials.size());
  for (int a : ctx.particle_materials) {
    for (int b : ctx.particle_materials)
      if (b >= a && !ctx.interaction_given[a * nm + b])
        ctx.check.fail("interactions", "no interaction between \"" + scene.materials[a].name + "\" and \"" +
                                           scene.materials[b].name + "\" (both are particle materials)");
    for (int w : ctx.wall_materials)
      if (!ctx.interaction_given[a * nm + w])
        ctx.check.fail("interactions", "no interaction between \"" + scene.materials[a].name +
                                           "\" and wall material \"" + scene.materials[w].name + "\"");
  }
}

}  // namespace dem::spec
