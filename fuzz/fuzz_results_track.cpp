// libFuzzer target: the results' track file (results_track.dat), read back when a run continues from
// a saved state (dem run --restart, a server job resumed): every line and count checked before it
// is used, then the results made from what it held. The job: bonded spheres under a loaded plate.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "output/run_results.hpp"
#include "spec/spec_loader.hpp"

namespace {

const char* kJob = R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.4, "friction": 0.5},
                   {"a": "rock", "b": "steel", "restitution": 0.4, "friction": 0.5}],
  "contact": {"normal": "LINEAR"},
  "lattices": [{"kind": "CUBIC", "min": {"x": 0, "y": 0, "z": 0.0052}, "max": {"x": 0.02, "y": 0.02, "z": 0.02},
                "radius": 0.005, "spacing": 1.0, "material": "rock"}],
  "bonds": {"youngsModulus": 1e7, "tensileStrength": 2e4, "shearStrength": 2e4},
  "walls": [
    {"name": "floor", "material": "steel", "plane": {"point": {"z": 0}, "normal": {"z": 1}}},
    {"name": "press", "material": "steel",
     "plate": {"c1": {"x": -0.01, "y": -0.01, "z": 0.03}, "c2": {"x": 0.03, "y": -0.01, "z": 0.03},
               "c3": {"x": 0.03, "y": 0.03, "z": 0.03}, "c4": {"x": -0.01, "y": 0.03, "z": 0.03}},
     "load": {"direction": {"z": -1}, "mass": 1, "cyclic": {"fMin": 1, "fMax": 10, "frequency": 50, "cycles": 3}}}],
  "gravity": {"z": -9.81},
  "time": {"steps": 20}
})";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static dem::Simulation* sim = [] {
    auto* s = new dem::Simulation(dem::spec::to_scene(dem::spec::parse_json(kJob)));
    for (int k = 0; k < 10; ++k) s->step();
    return s;
  }();
  static const std::string path =
      (std::filesystem::temp_directory_path() / ("fuzz_results_track_" + std::to_string(getpid()) + ".dat")).string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    dem::ResultsRecorder recorder(*sim, path, true);
    dem::RunOutcome outcome;
    recorder.finish(*sim, outcome);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
