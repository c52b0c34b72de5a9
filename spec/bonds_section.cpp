// Bonds between touching particles (JobSpec.bonds) and radius growth (JobSpec.growth).
#include "spec/defaults.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {

void load_bonds(const api::JobSpec& spec, SpecContext& ctx) {
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
  if (spec.has_bonds()) {
    const auto& in = spec.bonds();
    BondSettings b;
    if (!api::Bonds::Model_IsValid(in.model()))
      check.fail("bonds.model", "must be PARALLEL or CONTACT (got " + std::to_string(in.model()) + ")");
    b.model = api::Bonds::Model_Name(in.model());  // the enum's names are the bond models' (bonds/bond_models.hpp)
    b.radius_multiplier = in.radius_multiplier() == 0 ? defaults::kBondRadiusMultiplier : in.radius_multiplier();
    check.positive("bonds.radiusMultiplier", b.radius_multiplier, kRatio);
    check.positive("bonds.youngsModulus", in.youngs_modulus(), kModulus);
    b.youngs_modulus = in.youngs_modulus();
    b.shear_stiffness_ratio =
        in.shear_stiffness_ratio() == 0 ? defaults::kBondShearStiffnessRatio : in.shear_stiffness_ratio();
    check.positive("bonds.shearStiffnessRatio", b.shear_stiffness_ratio, kCoefficient);
    check.non_negative("bonds.tensileStrength", in.tensile_strength(), kModulus);
    check.non_negative("bonds.shearStrength", in.shear_strength(), kModulus);
    check.non_negative("bonds.strengthSpread", in.strength_spread(), kCoefficient);
    b.tensile_strength = in.tensile_strength();
    b.shear_strength = in.shear_strength();
    b.strength_spread = in.strength_spread();
    b.seed = in.seed() == 0 ? defaults::kSeed : in.seed();
    b.gap_tolerance = in.gap_tolerance() == 0 ? defaults::kBondGapTolerance : in.gap_tolerance();
    check.positive("bonds.gapTolerance", b.gap_tolerance, kCoefficient);
    if (in.has_region()) {
      check.vector("bonds.region.min", in.region().min(), kLength);
      check.vector("bonds.region.max", in.region().max(), kLength);
      b.region = Box{vec(in.region().min()), vec(in.region().max())};
      if ((b.region->max.array() < b.region->min.array()).any()) check.fail("bonds.region", "max is below min");
    }
    for (int k = 0; k < in.zones_size(); ++k) {
      const auto& z = in.zones(k);
      const std::string path = at("bonds.zones", k);
      check.vector(path + ".min", z.min(), kLength);
      check.vector(path + ".max", z.max(), kLength);
      check.non_negative(path + ".strengthRatio", z.strength_ratio(), kCoefficient);
      b.zones.push_back({Box{vec(z.min()), vec(z.max())}, z.strength_ratio()});
    }
    scene.bonds = b;
  }
}

void load_growth(const api::JobSpec& spec, SpecContext& ctx) {
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
  if (spec.has_growth()) {
    check.in_range("growth.factor", spec.growth().factor(), 1, 3, false, false);
    if (spec.growth().steps() < 1)
      check.fail("growth.steps", "must be >= 1 (got " + std::to_string(spec.growth().steps()) + ")");
    scene.growth = Scene::Growth{spec.growth().factor(), spec.growth().steps()};
  }
}

}  // namespace dem::spec
