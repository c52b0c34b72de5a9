// Picks the force loop once from what the scene contains, so that a scene without walls, friction,
// rolling resistance or tension clamping does not pay for them inside the loop.
#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "sim/kernel_factory.hpp"

namespace dem {
namespace {

int supported_lanes() {
#if DEM_HAS_AVX2_LANES
  return __builtin_cpu_supports("avx2") ? 4 : 1;
#else
  return 1;
#endif
}

std::atomic<int> chosen_lanes{0};  // 0: not chosen yet

}  // namespace

int pair_lanes() {
  int lanes = chosen_lanes.load(std::memory_order_relaxed);
  if (lanes == 0) {
    // DEM_PAIR_LANES=1 runs the one-at-a-time loop, to compare the two
    const char* forced = std::getenv("DEM_PAIR_LANES");
    lanes = forced != nullptr && std::string(forced) == "1" ? 1 : supported_lanes();
    chosen_lanes.store(lanes, std::memory_order_relaxed);
  }
  return lanes;
}

void set_pair_lanes(int lanes) {
  if (lanes != 1 && lanes != supported_lanes())
    throw std::invalid_argument("pair lanes: " + std::to_string(lanes) + " not available (use 1 or " +
                                std::to_string(supported_lanes()) + ")");
  chosen_lanes.store(lanes, std::memory_order_relaxed);
}

std::unique_ptr<ForceKernel> select_kernel(const Scene& scene, bool has_walls) {
  bool friction = false, rolling = false;
  for (const Interaction& in : scene.interactions) {
    friction = friction || in.friction > 0;
    rolling = rolling || in.rolling_friction > 0;
  }
  const RollingModel model = rolling ? scene.contact.rolling : RollingModel::None;
  const bool no_tensile = scene.contact.no_tensile_force;
  if (scene.contact.normal == NormalModel::Linear)
    return kernels::linear(no_tensile, friction, model, has_walls);
  return kernels::hertz(no_tensile, friction, model, has_walls);
}

}  // namespace dem
