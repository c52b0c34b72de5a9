// The engine's kernel dispatch over its own normal models, and the choice of the pair loop's lanes.
#include "sim/kernel_select.hpp"

#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <string>

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
  return select_kernel_from(NormalModels{}, scene, has_walls);
}

}  // namespace dem
