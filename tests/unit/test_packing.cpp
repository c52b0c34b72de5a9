// Size distributions and random loose packings: the samples have the requested mean and spread,
// the spheres do not overlap and stay in their box, and a seed gives the same packing again.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "spec/lattice.hpp"
#include "spec/packing.hpp"
#include "spec/spec_loader.hpp"

namespace dem::spec {
namespace {

struct Moments {
  double mean = 0, spread = 0;
};

Moments moments(const std::vector<double>& x) {
  Moments m;
  m.mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
  for (double v : x) m.spread += (v - m.mean) * (v - m.mean);
  m.spread = std::sqrt(m.spread / static_cast<double>(x.size() - 1));
  return m;
}

class Distribution : public ::testing::TestWithParam<SizeKind> {};

// 10,000 diameters of mean 10 mm and spread 3 mm (bounds far out: 1 mm and 50 mm)
TEST_P(Distribution, SampleHasTheRequestedMeanAndSpread) {
  SizeDistribution d;
  d.kind = GetParam();
  d.mean = 0.010;
  d.spread = 0.003;
  d.d_min = 0.001;
  d.d_max = 0.050;
  std::mt19937_64 rng(42);
  const std::vector<double> x = sample_diameters(d, 10000, rng);
  const Moments m = moments(x);
  EXPECT_NEAR(m.mean, d.mean, 0.02 * d.mean);
  EXPECT_NEAR(m.spread, d.spread, 0.02 * d.spread);
  for (double v : x) {
    ASSERT_GE(v, d.d_min);
    ASSERT_LE(v, d.d_max);
  }
}

INSTANTIATE_TEST_SUITE_P(NormalAndLognormal, Distribution, ::testing::Values(SizeKind::Normal, SizeKind::Lognormal),
                         [](const auto& info) {
                           return std::string(info.param == SizeKind::Normal ? "normal" : "lognormal");
                         });

TEST(SizeSamples, TruncationDrawsAgainInsideTheBounds) {
  SizeDistribution d{SizeKind::Normal, 0.010, 0.005, 0.008, 0.012, 0.5};
  std::mt19937_64 rng(1);
  for (double v : sample_diameters(d, 5000, rng)) {
    ASSERT_GE(v, 0.008);
    ASSERT_LE(v, 0.012);
  }
}

// Found by the spec fuzzer: a lognormal spread of 6.7e209 overflowed to NaN diameters, which passed
// the truncation's test and reached the packing's cell index (undefined behaviour). A spread that
// leaves hardly a draw between the bounds ends with a clear error instead of drawing on.
TEST(SizeSamples, ASpreadThatLeavesNothingBetweenTheBoundsIsAnError) {
  SizeDistribution d;
  d.kind = SizeKind::Lognormal;
  d.mean = 0.04;
  d.spread = 6.7329739539819182e+209;
  d.d_min = 0.0224;
  d.d_max = 0.063;
  std::mt19937_64 rng(3);
  try {
    sample_diameters(d, 100, rng);
    FAIL() << "drew diameters from a distribution that gives NaN";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("between dMin and dMax"), std::string::npos) << e.what();
  }
  d.spread = 1e9;  // finite, but 1.6e-4 of the draws land between the bounds
  EXPECT_THROW(sample_diameters(d, 100, rng), std::runtime_error);
}

TEST(SizeSamples, TwoSizesKeepTheirShares) {
  SizeDistribution d{SizeKind::Two, 0, 0, 0.005, 0.02, 0.8};
  std::mt19937_64 rng(3);
  const std::vector<double> x = sample_diameters(d, 10000, rng);
  const auto small = std::count(x.begin(), x.end(), 0.005);
  EXPECT_NEAR(static_cast<double>(small) / 10000, 0.8, 0.015);
  EXPECT_EQ(small + std::count(x.begin(), x.end(), 0.02), 10000);
}

TEST(RandomPacking, SpheresAreInsideAndApart) {
  SizeDistribution d{SizeKind::Uniform, 0, 0, 0.004, 0.012, 0.5};
  std::mt19937_64 rng(9);
  std::vector<double> dia = sample_diameters(d, 2000, rng);
  const Vec3 lo(0, 0, 0), hi(0.2, 0.2, 0.2);
  const std::vector<Vec3> x = random_packing(lo, hi, dia, rng);
  ASSERT_EQ(x.size(), 2000u);
  for (std::size_t a = 0; a < x.size(); ++a) {
    const double r = dia[a] / 2;
    ASSERT_TRUE(((x[a].array() - r) >= lo.array()).all() && ((x[a].array() + r) <= hi.array()).all()) << a;
    for (std::size_t b = a + 1; b < x.size(); ++b) ASSERT_GE((x[a] - x[b]).norm(), r + dia[b] / 2) << a << " " << b;
  }
}

TEST(RandomPacking, TooFullABoxIsAnError) {
  std::vector<double> dia(1000, 0.01);
  std::mt19937_64 rng(1);
  // 1000 spheres of 1 cm in a 6 cm cube: a solid fraction of 2.4
  EXPECT_THROW(random_packing(Vec3::Zero(), Vec3::Constant(0.06), dia, rng), std::runtime_error);
}

const char* kPackingSpec = R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5}],
  "packings": [{"min": {}, "max": {"x": 0.1, "y": 0.1, "z": 0.1}, "material": "rock", "seed": SEED,
                "solidFraction": 0.2, "sizes": {"kind": "LOGNORMAL", "mean": 0.01, "spread": 0.002, "dMin": 0.005, "dMax": 0.02}}],
  "time": {"steps": 1}
})";

std::string with_seed(int seed) {
  std::string text = kPackingSpec;
  return text.replace(text.find("SEED"), 4, std::to_string(seed));
}

TEST(PackingSpec, ASeedGivesTheSamePackingAgain) {
  const Scene a = to_scene(parse_json(with_seed(7))), b = to_scene(parse_json(with_seed(7))),
              c = to_scene(parse_json(with_seed(8)));
  ASSERT_GT(a.particles.size(), 300u);
  ASSERT_EQ(a.particles.size(), b.particles.size());
  for (std::size_t k = 0; k < a.particles.size(); ++k) ASSERT_EQ(a.particles[k].position, b.particles[k].position);
  EXPECT_NE(a.particles[0].position, c.particles[0].position);
  double volume = 0;
  for (const ParticleInit& p : a.particles) volume += 4.0 / 3.0 * M_PI * std::pow(p.radius, 3);
  EXPECT_NEAR(volume / 1e-3, 0.2, 0.01);  // the requested solid fraction, to one sphere
}

TEST(PackingSpec, BadPackingsAreNamed) {
  std::string text = with_seed(1);
  text.replace(text.find("\"solidFraction\": 0.2"), 20, "\"solidFraction\": 0.6");
  try {
    to_scene(parse_json(text));
    ADD_FAILURE() << "a solid fraction of 0.6 was placed at random";
  } catch (const SpecError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].rfind("packings[0]: placed only ", 0), 0u) << e.problems()[0];
  }
  text = with_seed(1);
  text.replace(text.find("\"dMin\": 0.005"), 13, "\"dMin\": 0.015");
  try {
    to_scene(parse_json(text));
    ADD_FAILURE() << "a mean below dMin was accepted";
  } catch (const SpecError& e) {
    EXPECT_NE(e.what(), std::string());
    EXPECT_EQ(e.problems()[0], "packings[0].sizes.mean: must lie in [dMin, dMax] (got 0.01)");
  }
}

// Filling to a solid fraction draws one diameter at a time: the draw budget must be the packing's,
// not each diameter's. A spread that leaves 1.6e-4 of the draws between the bounds was refused for
// a count and drawn on for a solid fraction (about 2.4 million draws here; a fuzzed one could ask
// for 1e7 diameters of 1e5 draws each).
TEST(PackingSpec, ASolidFractionIsRefusedTheSpreadACountIs) {
  std::string text = with_seed(1);
  text.replace(text.find("\"spread\": 0.002"), 15, "\"spread\": 1e9");
  try {
    to_scene(parse_json(text));
    ADD_FAILURE() << "a spread leaving 1.6e-4 of the draws inside the bounds filled a solid fraction";
  } catch (const SpecError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_NE(e.problems()[0].find("between dMin and dMax"), std::string::npos) << e.problems()[0];
  }
}

// A packing fills around the particles listed before it (here a 3 cm boulder in the middle of the
// box and a lattice row along its floor): none overlaps them. It once put spheres 2.4 radii into a
// listed particle, and the first step threw them apart.
TEST(PackingSpec, FillsAroundTheParticlesAlreadyThere) {
  std::string text = with_seed(3);
  text.replace(text.find("\"packings\""), 0,
               R"("particles": [{"position": {"x": 0.05, "y": 0.05, "z": 0.05}, "radius": 0.03, "material": "rock"}],
  "lattices": [{"kind": "CUBIC", "min": {}, "max": {"x": 0.1, "y": 0.02, "z": 0.02}, "radius": 0.005, "material": "rock"}],
  )");
  const Scene s = to_scene(parse_json(text));
  const std::size_t listed = 1 + 10 * 2 * 2;
  ASSERT_GT(s.particles.size(), listed + 100);
  for (std::size_t k = listed; k < s.particles.size(); ++k)
    for (std::size_t o = 0; o < listed; ++o) {
      const double reach = s.particles[k].radius + s.particles[o].radius;
      ASSERT_GE((s.particles[k].position - s.particles[o].position).norm(), reach * (1 - 1e-12)) << k << " on " << o;
    }
}

// The key block: a tetrahedron (inline mesh) filled at a solid fraction of 0.2; every sphere lies
// wholly inside (checked against the four face planes) and the volume matches.
TEST(PackingSpec, FillsAClosedMesh) {
  const char* spec = R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5}],
  "packings": [{"material": "rock", "solidFraction": 0.2, "sizes": {"kind": "UNIFORM", "dMin": 0.008, "dMax": 0.012},
                "inside": {"vertices": [{}, {"x": 0.3}, {"y": 0.3}, {"z": 0.3}],
                           "triangles": [{"i": 1, "j": 3, "k": 2}, {"i": 1, "j": 2, "k": 4}, {"i": 1, "j": 4, "k": 3}, {"i": 2, "j": 3, "k": 4}]}}],
  "time": {"steps": 1}
})";
  const Scene s = to_scene(parse_json(spec));
  ASSERT_GT(s.particles.size(), 500u);
  double volume = 0;
  for (const ParticleInit& p : s.particles) {
    const Vec3& x = p.position;
    const double r = p.radius;
    ASSERT_GE(x.x(), r);
    ASSERT_GE(x.y(), r);
    ASSERT_GE(x.z(), r);
    ASSERT_LE((x.sum() - 0.3) / std::sqrt(3.0), -r);  // below the slanted face
    volume += 4.0 / 3.0 * M_PI * r * r * r;
  }
  EXPECT_NEAR(volume / (0.3 * 0.3 * 0.3 / 6), 0.2, 0.005);
}

// A closed mesh (the tetrahedron above) filled with a lattice: every site whose sphere lies wholly
// inside, and no other (counted against the box's lattice and the four face planes).
std::string lattice_in_tetrahedron(const std::string& kind, const std::string& extra) {
  return R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5}],
  "lattices": [{"kind": ")" +
         kind + R"(", "material": "rock", )" + extra + R"(
                "inside": {"vertices": [{}, {"x": 0.3}, {"y": 0.3}, {"z": 0.3}],
                           "triangles": [{"i": 1, "j": 3, "k": 2}, {"i": 1, "j": 2, "k": 4}, {"i": 1, "j": 4, "k": 3}, {"i": 2, "j": 3, "k": 4}]}}],
  "time": {"steps": 1}
})";
}

bool in_tetrahedron(const Vec3& x, double r) {
  return x.x() >= r && x.y() >= r && x.z() >= r && (x.sum() - 0.3) / std::sqrt(3.0) <= -r;
}

TEST(LatticeSpec, HexAndFccFillAClosedMeshWithEverySiteThatFits) {
  for (const auto& [name, kind] : {std::pair{"HEX", LatticeKind::Hex}, std::pair{"FCC", LatticeKind::Fcc}}) {
    const Scene s = to_scene(parse_json(lattice_in_tetrahedron(name, R"("radius": 0.01,)")));
    std::size_t expected = 0;
    for (const Vec3& x : lattice_sites(kind, Vec3::Zero(), Vec3::Constant(0.3), 0.01, 1.0))
      expected += in_tetrahedron(x, 0.01 * (1 - 1e-9));  // touching a face is inside
    EXPECT_EQ(s.particles.size(), expected) << name;
    EXPECT_GT(expected, 300u) << name;
    for (const ParticleInit& p : s.particles) ASSERT_TRUE(in_tetrahedron(p.position, 0.01 * (1 - 1e-9))) << name;
  }
}

TEST(LatticeSpec, SizesAreDrawnIntoSitesSpacedForTheLargest) {
  // the manual's IPATTERN 2 (uniform) with Dmax/D 1.05 and Dmin/D 0.95, D = 15 mm
  const Scene s = to_scene(parse_json(
      lattice_in_tetrahedron("HEX", R"("sizes": {"kind": "UNIFORM", "dMin": 0.01425, "dMax": 0.01575}, "seed": 7,)")));
  ASSERT_GT(s.particles.size(), 100u);
  double sum = 0;
  for (const ParticleInit& p : s.particles) {
    ASSERT_GE(p.radius, 0.01425 / 2);
    ASSERT_LE(p.radius, 0.01575 / 2);
    ASSERT_TRUE(in_tetrahedron(p.position, p.radius));
    sum += 2 * p.radius;
  }
  EXPECT_NEAR(sum / static_cast<double>(s.particles.size()), 0.015, 0.0003);
  // no two overlap: the sites are a largest diameter apart
  for (std::size_t a = 0; a < s.particles.size(); ++a)
    for (std::size_t b = a + 1; b < s.particles.size(); ++b)
      ASSERT_GE((s.particles[a].position - s.particles[b].position).norm(),
                s.particles[a].radius + s.particles[b].radius);
}

TEST(LatticeSpec, AKindOutsideTheEnumIsRefused) {
  try {
    to_scene(parse_json(R"({"materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}],
      "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5}],
      "lattices": [{"kind": 9, "material": "rock", "radius": 0.01, "max": {"x": 1, "y": 1, "z": 1}}],
      "outputs": {"numberFormat": 7}, "time": {"steps": 1}})"));
    FAIL() << "accepted";
  } catch (const SpecError& e) {
    // JSON's numbers are named as the JSON reader sees them (the checks' own words, "must be CUBIC, FCC
    // or HEX", are for protobuf's binary form)
    EXPECT_NE(std::string(e.what()).find("lattices[0].kind: expected one of CUBIC, FCC, HEX, got 9"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("outputs.numberFormat: expected one of SCIENTIFIC, LEGACY_FIXED, FULL, got 7"),
              std::string::npos)
        << e.what();
  }
}

TEST(LatticeSpec, AMeshsBoxStandsForTheCornerLeftOut) {
  const Scene s = to_scene(parse_json(lattice_in_tetrahedron("HEX", R"("radius": 0.01, "min": {"x": 0.1},)")));
  ASSERT_FALSE(s.particles.empty());
  for (const ParticleInit& p : s.particles) ASSERT_GE(p.position.x(), 0.1 + 0.01 * (1 - 1e-9));
}

TEST(LatticeSpec, CountsGiveThatManySitesFromMin) {
  const char* spec = R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5}],
  "lattices": [{"kind": "HEX", "material": "rock", "radius": 0.0075, "min": {"x": 1},
                "countX": 11, "countY": 13, "countZ": 42}],
  "time": {"steps": 1}
})";
  const Scene s = to_scene(parse_json(spec));
  EXPECT_EQ(s.particles.size(), 11u * 13u * 42u);
  EXPECT_EQ(s.particles[0].position, Vec3(1.0075, 0.0075, 0.0075));
}

TEST(LatticeSpec, BadLatticesAreNamed) {
  const std::string base = R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5}],
  "lattices": [{"material": "rock", LATTICE, "kind": "HEX"}],
  "time": {"steps": 1}
})";
  auto with = [&](const std::string& lattice) {
    std::string json = base;
    return json.replace(json.find("LATTICE"), 7, lattice);
  };
  const std::pair<std::string, std::string> cases[] = {
      {R"("radius": 0.01, "countX": 3, "countY": 3)",
       "lattices[0].countZ: must be in [1, 1000000] when a count is given (got 0): give all three, or none"},
      {R"("radius": 0.01, "countX": 3, "countY": 3, "countZ": 3, "max": {"x": 1, "y": 1, "z": 1})",
       "lattices[0].max: the counts give the lattice's size: leave max out"},
      {R"("radius": 0.01, "sizes": {"mean": 0.02}, "max": {"x": 1, "y": 1, "z": 1})",
       "lattices[0].radius: give radius or sizes, not both"},
      {R"("sizes": {"kind": "UNIFORM", "dMin": 0.02, "dMax": 0.01}, "max": {"x": 1, "y": 1, "z": 1})",
       "lattices[0].sizes.dMax: must be >= dMin"},
      {R"("radius": 0.01, "inside": {"vertices": [{}, {"x": 0.001}, {"y": 0.001}, {"z": 0.001}], "triangles": [{"i": 1, "j": 3, "k": 2}, {"i": 1, "j": 2, "k": 4}, {"i": 1, "j": 4, "k": 3}, {"i": 2, "j": 3, "k": 4}]})",
       "lattices[0]: the mesh is too small to hold one particle of radius 0.01"},
      {R"("radius": 0.01, "inside": {"vertices": [{}, {"x": 0.3}, {"y": 0.3}, {"z": 0.3}], "triangles": [{"i": 1, "j": 3, "k": 2}, {"i": 1, "j": 2, "k": 4}, {"i": 1, "j": 4, "k": 3}]})",
       "lattices[0].inside: is not a closed surface: the edge between vertices 2 and 3 belongs to 1 triangle(s)"},
      {R"("sizes": {"kind": 7, "mean": 0.01}, "max": {"x": 1, "y": 1, "z": 1})",
       "lattices[0].sizes.kind: expected one of ONE_SIZE, TWO_SIZES, UNIFORM, NORMAL, LOGNORMAL, got 7"},
  };
  for (const auto& [lattice, expected] : cases) {
    std::string problems;
    try {
      to_scene(parse_json(with(lattice)));
    } catch (const SpecError& e) {
      problems = e.what();
    }
    EXPECT_NE(problems.find(expected), std::string::npos) << lattice << "\ngave: " << problems;
  }
}

}  // namespace
}  // namespace dem::spec
