// What one spec may cost: particles and triangles in all, threads, the name, the list of problems,
// and particles piled on each other. Each is refused with the field and the limit before anything
// large is allocated (a 1.1 MB spec of coincident particles once needed memory growing with the
// square of their count; numerics.threads 100000 killed the server; a 30 MB name made every job list
// 30 MB; 20,000 bad particles gave a 121 MB list of problems).
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "core/errors.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"

namespace dem::test {
namespace {

std::string spec_with(const std::string& particles, const std::string& extra = "") {
  return R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}, {"name": "floor", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5}, {"a": "rock", "b": "floor", "restitution": 0.5}],
  )" + particles +
         extra + R"(,
  "time": {"steps": 10}
})";
}

std::string many_particles(int n, double spacing, double radius = 0.01) {
  std::string out = R"("particles": [)";
  for (int k = 0; k < n; ++k)
    out += std::string(k ? "," : "") + R"({"position": {"x": )" + std::to_string(spacing * k) + R"(}, "radius": )" +
           std::to_string(radius) + R"(, "material": "rock"})";
  return out + "]";
}

std::vector<std::string> problems(const std::string& json, const spec::SpecLimits& limits = {}) {
  try {
    spec::to_scene(spec::parse_json(json), "", limits);
  } catch (const spec::SpecError& e) {
    return e.problems();
  }
  return {};
}

TEST(SpecLimits, TheNameIsAtMost200Bytes) {
  const std::vector<std::string> p = problems(spec_with(many_particles(1, 0)) + "", {});
  EXPECT_TRUE(p.empty());
  std::string json = spec_with(many_particles(1, 0));
  json.replace(json.find('{') + 1, 0, "\"name\": \"" + std::string(201, 'x') + "\",");
  const std::vector<std::string> named = problems(json);
  ASSERT_EQ(named.size(), 1u);
  EXPECT_EQ(named[0], "name: must be at most 200 bytes (got 201)");
}

// Every pair of materials has its coefficients (a table of M x M): 12,000 unused materials in a
// 1 MB spec took the server 12.5 GB and 30 s to check (an independent tester's finding).
TEST(SpecLimits, MaterialsAreAtMost256AndRefusedBeforeTheirPairTable) {
  std::string json = spec_with(many_particles(1, 0));
  std::string extra;
  for (int k = 0; k < 20000; ++k)
    extra += R"({"name": "m)" + std::to_string(k) + R"(", "density": 2650, "normalStiffness": 1e5},)";
  json.replace(json.find("\"materials\": [") + 14, 0, extra);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::string> p = problems(json);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0], "materials: at most 256 materials (got 20002)");
  EXPECT_LT(seconds, 5.0);  // parsing the 1.3 MB only (the pair table took minutes)
}

TEST(SpecLimits, WallsAreAtMost10000AndRefusedBeforeTheyAreBuilt) {
  std::string walls = R"(, "walls": [)";
  for (int k = 0; k < 10001; ++k)
    walls += std::string(k ? "," : "") + R"({"material": "floor", "plane": {"point": {"z": -1}, "normal": {"z": 1}}})";
  const std::vector<std::string> p = problems(spec_with(many_particles(1, 0), walls + "]"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].rfind("walls: at most 10000 walls (got 10001)", 0), 0u) << p[0];
}

TEST(SpecLimits, ThreadsAreAtMost256) {
  const std::vector<std::string> p = problems(spec_with(many_particles(1, 0), R"(, "numerics": {"threads": 100000})"));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0], "numerics.threads: must be in [0, 256] (0 = all cores; got 100000)");
}

TEST(SpecLimits, TheListOfProblemsIsCappedAndSaysHowManyMore) {
  const std::vector<std::string> p = problems(spec_with(many_particles(2000, 0.1, -0.01)));
  ASSERT_EQ(p.size(), 101u);
  EXPECT_EQ(p[0].rfind("particles[0].radius: must be a positive number", 0), 0u) << p[0];
  EXPECT_EQ(p.back(), "(1900 more problems not listed)");
}

TEST(SpecLimits, ParticlesInAllAreCappedBeforeTheyAreMade) {
  spec::SpecLimits small;
  small.max_particles = 1000;
  const std::string lattice =
      R"("lattices": [{"kind": "CUBIC", "min": {}, "max": {"x": 0.4, "y": 0.4, "z": 0.4}, "radius": 0.01, "material": "rock"}])";
  const std::vector<std::string> p = problems(spec_with(lattice), small);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0], "lattices[0]: would make 8000 particles in all, more than the limit of 1000");
  // two lattices of 512 each: under the limit each, over it together
  const std::string two =
      R"("lattices": [{"kind": "CUBIC", "min": {}, "max": {"x": 0.16, "y": 0.16, "z": 0.16}, "radius": 0.01, "material": "rock"},
                                         {"kind": "CUBIC", "min": {"z": 1}, "max": {"x": 0.16, "y": 0.16, "z": 1.16}, "radius": 0.01, "material": "rock"}])";
  const std::vector<std::string> both = problems(spec_with(two), small);
  ASSERT_EQ(both.size(), 1u);
  EXPECT_EQ(both[0].rfind("lattices[1]: would make", 0), 0u) << both[0];
}

// A 45-million-sphere lattice under the 50-million cap took 2.9 GB of the server's memory while it
// was being made, then failed with bad_alloc (an independent tester's finding): the memory a run
// needs is estimated from the count and refused before the first particle is made.
TEST(SpecLimits, MemoryIsEstimatedFromTheCountBeforeTheParticlesAreMade) {
  spec::SpecLimits limits;
  limits.max_memory_bytes = 1e9;
  limits.memory_limit_name = "this server (--max-job-memory-mb)";
  // 400^3 = 64 million sites: past the count too; 300^3 = 27 million: under the count, past memory
  const std::string lattice =
      R"("lattices": [{"kind": "CUBIC", "min": {}, "max": {"x": 6, "y": 6, "z": 6}, "radius": 0.01, "material": "rock"}])";
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::string> p = problems(spec_with(lattice), limits);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(
      p[0].rfind("lattices[0]: would make 27000000 particles in all, which would need about 43.2 GB of memory", 0), 0u)
      << p[0];
  EXPECT_NE(p[0].find("more than this server (--max-job-memory-mb) allows (1.0 GB)"), std::string::npos) << p[0];
  EXPECT_LT(seconds, 1.0);  // nothing was made
  // a packing by count, too, before its spheres are placed
  const std::string packing =
      R"("packings": [{"min": {}, "max": {"x": 10, "y": 10, "z": 10}, "count": 2000000, "material": "rock",
                       "sizes": {"kind": "ONE_SIZE", "mean": 0.02}}])";
  const std::vector<std::string> q = problems(spec_with(packing), limits);
  ASSERT_EQ(q.size(), 1u);
  EXPECT_EQ(q[0].rfind("packings[0]: would make 2000000 particles in all, which would need about 3.2 GB", 0), 0u)
      << q[0];
}

// A name is printed in lists and on terminals: ESC, BEL, CR and LF in it could forge output.
TEST(SpecLimits, TheNameHoldsNoControlCharacters) {
  std::string json = spec_with(many_particles(1, 0));
  json.replace(json.find('{') + 1, 0, R"("name": "ok\u001b]0;title\u0007",)");
  const std::vector<std::string> p = problems(json);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0], "name: must not hold control characters (byte 2 is 0x1B)");
  std::string fine = spec_with(many_particles(1, 0));
  fine.replace(fine.find('{') + 1, 0, R"("name": "Böschung – Fall 3",)");
  EXPECT_TRUE(problems(fine).empty());
}

TEST(SpecLimits, TrianglesInAllAreCapped) {
  spec::SpecLimits small;
  small.max_triangles = 1;
  const std::string mesh = R"(, "walls": [{"material": "floor", "mesh": {
      "vertices": [{"x": 0}, {"x": 1}, {"y": 1}, {"x": 1, "y": 1}], "triangles": [{"i": 1, "j": 2, "k": 3}, {"i": 2, "j": 4, "k": 3}]}}])";
  const std::vector<std::string> p = problems(spec_with(many_particles(1, 0), mesh), small);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0], "walls: 2 mesh triangles in all, more than the limit of 1");
}

// 20,000 particles at one point: refused from the neighbour search after a bounded amount of it,
// with the particle named, instead of asking for 2e8 pairs.
TEST(SpecLimits, ParticlesPiledOnEachOtherAreRefusedWithoutTheMemoryTheyWouldTake) {
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = spec::to_scene(spec::parse_json(spec_with(many_particles(20000, 0))));
  try {
    Simulation sim(scene);
    ADD_FAILURE() << "20,000 coincident particles were accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("neighbours within reach"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("particles: "), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

}  // namespace
}  // namespace dem::test
