// The engine enters an OpenMP parallel region only where a loop is long enough to gain from it: a
// region costs a team's start and its barrier even with nothing to share (core/parallel.hpp). An
// empty scene (a source's before its first particle) started one for its pair loop every step, 145 us
// a step on two threads. The regions are counted by wrapping libgomp's entry, GOMP_parallel (GCC's
// OpenMP; the clang builds use LLVM's runtime, whose entry differs: skipped there).
#include <gtest/gtest.h>

#include <dlfcn.h>
#include <omp.h>

#include <atomic>

#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"

namespace {
std::atomic<int> regions{0};
}  // namespace

#if !defined(__clang__)
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned threads, unsigned flags) {
  using Entry = void (*)(void (*)(void*), void*, unsigned, unsigned);
  static const auto real = reinterpret_cast<Entry>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  regions.fetch_add(1, std::memory_order_relaxed);
  real(fn, data, threads, flags);
}
#endif

namespace dem {
namespace {

int regions_in_steps(const char* spec, int steps) {
  Simulation sim(spec::to_scene(spec::parse_json(spec)));
  const int before = regions.load();
  for (int k = 0; k < steps; ++k) sim.step();
  return regions.load() - before;
}

TEST(ParallelRegions, AnEmptySceneOnTwoThreadsEntersNone) {
#if defined(__clang__)
  GTEST_SKIP() << "counts libgomp's regions (GCC builds)";
#endif
  // Empty until its source's first particle, due at 0.5 s: 100 steps with nothing to do.
  const char* empty = R"({
    "materials": [{"name": "sand", "density": 2650, "normalStiffness": 1e5}],
    "interactions": [{"a": "sand", "b": "sand", "restitution": 0.5, "friction": 0.5}],
    "sources": [{"min": {"x": 0, "y": 0, "z": 0}, "max": {"x": 0.1, "y": 0.1, "z": 0.1}, "material": "sand",
                 "sizes": {"kind": "UNIFORM", "dMin": 0.01, "dMax": 0.01}, "countRate": 10, "start": 0.5}],
    "time": {"dt": 1e-5, "steps": 100},
    "numerics": {"threads": 2}
  })";
  EXPECT_EQ(regions_in_steps(empty, 100), 0);
}

// The counting itself: a scene past the parallel threshold (4,096 particles) on two threads does
// enter regions, so the count above cannot pass for want of counting.
TEST(ParallelRegions, ALargeSceneOnTwoThreadsEntersThem) {
#if defined(__clang__)
  GTEST_SKIP() << "counts libgomp's regions (GCC builds)";
#endif
  const char* large = R"({
    "materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e3}],
    "interactions": [{"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.5}],
    "lattices": [{"kind": "CUBIC", "min": {"x": 0, "y": 0, "z": 0}, "max": {"x": 0.0175, "y": 0.0175, "z": 0.0175},
                  "radius": 0.0005, "spacing": 1.0, "material": "glass"}],
    "time": {"dt": 1e-6, "steps": 10},
    "numerics": {"threads": 2}
  })";
  EXPECT_GT(regions_in_steps(large, 10), 0);
}

}  // namespace
}  // namespace dem
