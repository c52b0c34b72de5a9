// The contact models as units: a normal law written in this file alone (the model and its list)
// runs in the engine's force loop, sets the time step and is known to the catalogue; and every
// model of the schema has a model in the engine's lists, and every model of the lists a name there.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "contact/model_catalog.hpp"
#include "dem.pb.h"
#include "sim/kernel_factory_impl.hpp"
#include "sim/kernel_select.hpp"
#include "support/scenes.hpp"

namespace dem::test {
namespace {

// Place 1 of 2: the model. A frictionless quadratic spring F_n = c delta^2 with c = k_n / R* (a
// law of no use but this test's): its own coefficient, mixing, contact time and stored energy.
struct ToyNormal {
  static constexpr std::string_view kName = "TOY";
  static constexpr std::array kRequires{MaterialProperty::Density, MaterialProperty::NormalStiffness};
  static constexpr ModelParameter kScale{"toy_scale", 1.0, 0, kUnbounded, "multiplies c"};
  static constexpr std::array kParameters{kScale};
  static constexpr bool kNeedsEffectiveRadius = true;
  static constexpr bool kContactTimeNeedsSpeed = true;

  struct Pair {
    double k = 0;  // c = k / R*
  };
  static Pair mix(const Material& a, const Material& b, const Interaction&, const ContactSettings& c) {
    const double ca = a.rigid ? 0 : 1 / a.normal_stiffness, cb = b.rigid ? 0 : 1 / b.normal_stiffness;
    return {c.parameters.value(kScale) / (ca + cb)};
  }
  template <class T>
  struct Lanes {
    T k;
    DEM_HOT void set(int l, const Pair& p) { set_lane(k, l, p.k); }
  };
  template <class T>
  DEM_HOT static NormalResponse<T> evaluate(const Lanes<T>& p, const ContactInput<T>& c) {
    const T stiffness = p.k / c.r_eff;
    return {stiffness * c.delta * c.delta, 2.0 * stiffness * c.delta, T{}, T{}};
  }
  static double elastic_energy(const Pair& p, double delta, double r_eff) {
    return p.k / r_eff * delta * delta * delta / 3;
  }
  static double normal_stiffness(const Pair& p, double delta, double r_eff) { return 2 * p.k / r_eff * delta; }
  static double tangential_stiffness(const Pair&, double, double) { return 0; }
  // t_c = 2 (delta_max / V) integral_0^1 du / sqrt(1 - u^3), delta_max = (3 m* V^2 / (2 c))^(1/3)
  static double contact_time(const Pair& p, double m_eff, double r_eff, double v) {
    return 2 * kToyIntegral * std::cbrt(3 * m_eff * v * v * r_eff / (2 * p.k)) / v;
  }
  static double wave_time(const Material&, double) { return kUnbounded; }
  static constexpr double kToyIntegral = 1.4021821053254;  // B(1/3, 1/2) / 3
};

// Place 2 of 2: a list with it (the engine's is contact/models.hpp). The third place, the schema,
// is only needed to name the model in a job spec; this test builds its scene in code.
using NormalsWithToy = ModelList<LinearNormal, HertzNormal, ToyNormal>;

// The force loops of the toy's list: the toy's alone, as each engine model's are made in its own
// .cpp (made here for all three, they took this file 5 minutes to compile under the sanitizers).
std::unique_ptr<ForceKernel> select_with_toy(const Scene& scene, bool walls) {
  return select_kernel_from(ModelList<ToyNormal>{}, scene, walls);
}

Scene toy_impact(double v) {
  Scene s = base_scene("TOY", 2500, 0, 0, 1, 0, 1e6);
  s.particles.push_back(sphere({0, 0, 0.01 * 1.000001}, 0.01, {0, 0, -v}));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  s.time.steps = 1000000;
  return s;
}

TEST(ContactModels, ANormalLawOfATestFileRunsInTheForceLoop) {
  const double v = 0.5;
  Simulation sim(toy_impact(v), select_with_toy);
  const double m = sphere_mass(2500, 0.01), c = 1e6 / 0.01;  // rigid wall: k = kn; R* = r
  const double delta_max = std::cbrt(3 * m * v * v / (2 * c));
  const double t_c = 2 * ToyNormal::kToyIntegral * delta_max / v;
  // the time step comes from the model's own contact time, taken at the reference speed (2 v here),
  // for the shorter of the two pairs the scene could have: sphere-wall (m, r, k_n) and sphere-sphere
  // (m/2, r/2, k_n/2)
  const double v_ref = sim.time_step().reference_speed;
  EXPECT_EQ(v_ref, 2 * v);
  auto time_at = [&](double m_eff, double c_pair) {
    return 2 * ToyNormal::kToyIntegral * std::cbrt(3 * m_eff * v_ref * v_ref / (2 * c_pair)) / v_ref;
  };
  const double t_ref = std::min(time_at(m, c), time_at(m / 2, 0.5e6 / 0.005));
  EXPECT_NEAR(sim.time_step().contact_time, t_ref, 1e-9 * t_ref);
  double peak = 0, touched = -1, parted = -1;
  for (int k = 0; k < 100000 && parted < 0; ++k) {
    sim.step();
    const double overlap = 0.01 - sim.particles().x[0].z();
    peak = std::max(peak, overlap);
    if (overlap > 0 && touched < 0) touched = sim.time();
    if (overlap <= 0 && touched >= 0) parted = sim.time();
  }
  EXPECT_NEAR(peak, delta_max, 2e-3 * delta_max);
  EXPECT_NEAR(parted - touched, t_c, 0.03 * t_c);      // to a step: 1/50 of t_c
  EXPECT_NEAR(sim.particles().v[0].z(), v, 1e-3 * v);  // elastic: the model has no dashpot
}

TEST(ContactModels, AModelParameterReachesTheModel) {
  Scene s = toy_impact(0.5);
  s.contact.parameters.set(ToyNormal::kScale.field, 8.0);  // 8 c: delta_max / 2, t_c / 2
  const Simulation plain(toy_impact(0.5), select_with_toy), stiff(s, select_with_toy);
  EXPECT_NEAR(stiff.time_step().contact_time, plain.time_step().contact_time / 2, 1e-12);
}

TEST(ContactModels, TheCatalogueOfAListKnowsTheModel) {
  const ModelCatalog catalog = catalog_of<NormalsWithToy, TangentialModels, RollingModels>();
  const ModelInfo* toy = ModelCatalog::find(catalog.normal, "TOY");
  ASSERT_NE(toy, nullptr);
  EXPECT_EQ(toy->required.size(), 2u);
  EXPECT_EQ(toy->parameters[0].field, "toy_scale");
  EXPECT_EQ(ModelCatalog::find(contact_models().normal, "TOY"), nullptr);  // not one of the engine's
}

TEST(ContactModels, ANameOutsideTheListIsASceneError) {
  EXPECT_THROW(Simulation(toy_impact(0.5)), SceneError);  // the engine's own list has no TOY
}

// Every enum value of the schema names a model of the engine's lists, and every model has one.
template <class Enum>
std::set<std::string> schema_names(const Enum* descriptor) {
  std::set<std::string> names;
  for (int k = 0; k < descriptor->value_count(); ++k)
    if (descriptor->value(k)->name().find("UNSPECIFIED") == std::string::npos)
      names.insert(descriptor->value(k)->name());
  return names;
}

std::set<std::string> model_names(const std::vector<ModelInfo>& kind) {
  std::set<std::string> names;
  for (const ModelInfo& m : kind) names.insert(std::string(m.name));
  return names;
}

TEST(ContactModels, TheSchemaAndTheListsNameTheSameModels) {
  EXPECT_EQ(schema_names(api::ContactModel::Normal_descriptor()), model_names(contact_models().normal));
  EXPECT_EQ(schema_names(api::ContactModel::Rolling_descriptor()), model_names(contact_models().rolling));
}

// Every parameter a model declares is an optional double of the schema's ContactModel.
TEST(ContactModels, EveryModelParameterIsASchemaField) {
  const auto* descriptor = api::ContactModel::descriptor();
  for (const auto* kind : {&contact_models().normal, &contact_models().tangential, &contact_models().rolling})
    for (const ModelInfo& m : *kind)
      for (const ModelParameter& p : m.parameters) {
        const auto* field = descriptor->FindFieldByName(std::string(p.field));
        ASSERT_NE(field, nullptr) << m.name << ": " << p.field;
        EXPECT_EQ(field->type(), google::protobuf::FieldDescriptor::TYPE_DOUBLE) << p.field;
        EXPECT_TRUE(field->has_presence()) << p.field << " must be optional (its default is the model's)";
      }
}

}  // namespace
}  // namespace dem::test
