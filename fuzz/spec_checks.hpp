// What the spec targets share: parse, load with limits small enough for a fuzzer's memory, and set
// the simulation up as `dem validate` does (which once segfaulted on a radius of 1e308 beside a
// mesh wall). Only the errors a bad spec is meant to raise are caught.
#pragma once

#include <cstdint>
#include <string>

#include "core/errors.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"

namespace dem::fuzz {

template <class Parse>
void check_spec(Parse&& parse) {
  spec::SpecLimits limits;
  limits.max_particles = 2000;
  limits.max_triangles = 2000;
  limits.max_threads = 2;
  try {
    Scene scene = spec::to_scene(parse(), "/nonexistent-fuzz-dir", limits);
    scene.numerics.threads = 1;
    const Simulation sim(std::move(scene));
  } catch (const spec::SpecError&) {
  } catch (const SceneError&) {
  }
}

}  // namespace dem::fuzz
