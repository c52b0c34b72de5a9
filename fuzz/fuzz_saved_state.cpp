// libFuzzer target: the saved-state reader (restart.dat, the server's checkpoints), which once
// segfaulted on a partner index out of range. A state ends in a CRC-32 that refuses any change made
// without resealing it, so the fuzzer's bytes are sealed here: what is tested is every check the
// reader makes against the job before it follows an index or a count, then a few steps from the
// state it accepted. The job: bonded spheres with rolling springs on a mesh floor under a loaded
// plate, in two stages (the bonds glued, the plate's load changed and grit poured in from a source at
// the second, where the state is written), so that every section of the state has something in it. With
// DEM_FUZZ_WRITE_SEED=PATH set, writes a real state of that job (the seed of the corpus) and stops.
#include <boost/crc.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "sim/simulation.hpp"
#include "sim/state_io.hpp"
#include "spec/spec_loader.hpp"

namespace {

const char* kJob = R"({
  "materials": [{"name": "rock", "density": 2600, "youngsModulus": 1e7, "poissonRatio": 0.25},
                {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.4, "friction": 0.5, "rollingFriction": 0.05},
                   {"a": "rock", "b": "steel", "restitution": 0.4, "friction": 0.5, "rollingFriction": 0.05}],
  "contact": {"normal": "HERTZ", "rolling": "EPSD"},
  "lattices": [{"kind": "FCC", "min": {"x": 0, "y": 0, "z": 0.0052}, "max": {"x": 0.03, "y": 0.03, "z": 0.03},
                "radius": 0.005, "spacing": 1.0, "material": "rock"}],
  "bonds": {"youngsModulus": 1e7, "tensileStrength": 2e4, "shearStrength": 2e4},
  "walls": [
    {"name": "floor", "material": "steel", "mesh": {
      "vertices": [{"x": -0.05, "y": -0.05}, {"x": 0.1, "y": -0.05}, {"x": 0.1, "y": 0.1}, {"x": -0.05, "y": 0.1},
                   {"x": 0.025, "y": 0.025, "z": -0.002}],
      "triangles": [{"i": 1, "j": 2, "k": 5}, {"i": 2, "j": 3, "k": 5}, {"i": 3, "j": 4, "k": 5}, {"i": 4, "j": 1, "k": 5}]}},
    {"name": "press", "material": "steel",
     "plate": {"c1": {"x": -0.02, "y": -0.02, "z": 0.045}, "c2": {"x": 0.06, "y": -0.02, "z": 0.045},
               "c3": {"x": 0.06, "y": 0.06, "z": 0.045}, "c4": {"x": -0.02, "y": 0.06, "z": 0.045}},
     "load": {"mass": 0.05, "cyclic": {"fMin": 1, "fMax": 10, "frequency": 20, "cycles": 2}}}],
  "gravity": {"z": -9.81},
  "numerics": {"threads": 1},
  "stages": [{"name": "settle", "steps": 150},
             {"name": "bond", "steps": 250, "bond": true, "gravity": {"z": -5},
              "wallChanges": [{"wall": "press", "load": {"servo": {"target": 2, "gain": 1e-3, "maxSpeed": 0.01}}}]}],
  "sources": [{"name": "grit", "min": {"x": 0, "y": 0, "z": 0.032}, "max": {"x": 0.03, "y": 0.03, "z": 0.044},
               "material": "rock", "sizes": {"kind": "UNIFORM", "dMin": 0.003, "dMax": 0.004}, "countRate": 2e5,
               "velocity": {"z": -0.1}, "stage": "bond"}],
  "outputs": {"everySteps": 400}
})";

const dem::Scene& job() {
  static const dem::Scene scene = dem::spec::to_scene(dem::spec::parse_json(kJob));
  return scene;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* path = std::getenv("DEM_FUZZ_WRITE_SEED")) {
    dem::Simulation sim(job());
    for (int k = 0; k < 200; ++k) sim.step();
    std::fprintf(stderr, "the seed: step %lld, %zu particles (%zu given)\n", static_cast<long long>(sim.step_count()),
                 sim.particles().size(), sim.given_particles());
    std::ostringstream state;
    dem::StateIO::write(sim, state);
    const std::string bytes = state.str();
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() - 4));
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  boost::crc_32_type crc;
  crc.process_bytes(bytes.data(), bytes.size());
  const std::uint32_t sum = crc.checksum();
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  dem::Simulation sim(job());
  std::istringstream in(bytes);
  try {
    dem::StateIO::read(sim, in);
    dem::StateIO::require_within_run(sim);
  } catch (const std::runtime_error&) {
    return 0;  // refused, with a reason: what the reader is for
  }
  for (int k = 0; k < 3; ++k) sim.step();
  return 0;
}
