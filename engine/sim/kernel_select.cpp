// Picks the force loop once from what the scene contains, so that a scene without walls, friction,
// rolling resistance or tension clamping does not pay for them inside the loop.
#include <stdexcept>

#include "sim/force_kernel_impl.hpp"

namespace dem {
namespace {

template <class Normal, bool NoTensile, bool Friction, class Rolling>
std::unique_ptr<ForceKernel> with_walls(bool has_walls) {
  using Law = ContactLaw<Normal, NoTensile, Friction, Rolling>;
  if (has_walls) return std::make_unique<ForceKernelImpl<Law, true>>();
  return std::make_unique<ForceKernelImpl<Law, false>>();
}

template <class Normal, bool NoTensile, bool Friction>
std::unique_ptr<ForceKernel> with_rolling(RollingModel rolling, bool has_walls) {
  switch (rolling) {
    case RollingModel::None: return with_walls<Normal, NoTensile, Friction, NoRolling>(has_walls);
    case RollingModel::Cdt: return with_walls<Normal, NoTensile, Friction, CdtRolling>(has_walls);
    case RollingModel::Epsd: return with_walls<Normal, NoTensile, Friction, EpsdRolling>(has_walls);
  }
  throw std::logic_error("unknown rolling model");
}

template <class Normal, bool NoTensile>
std::unique_ptr<ForceKernel> with_friction(bool friction, RollingModel rolling, bool has_walls) {
  if (friction) return with_rolling<Normal, NoTensile, true>(rolling, has_walls);
  return with_rolling<Normal, NoTensile, false>(rolling, has_walls);
}

template <class Normal>
std::unique_ptr<ForceKernel> with_tension(bool no_tensile, bool friction, RollingModel rolling, bool has_walls) {
  if (no_tensile) return with_friction<Normal, true>(friction, rolling, has_walls);
  return with_friction<Normal, false>(friction, rolling, has_walls);
}

}  // namespace

std::unique_ptr<ForceKernel> select_kernel(const Scene& scene, bool has_walls) {
  bool friction = false, rolling = false;
  for (const Interaction& in : scene.interactions) {
    friction = friction || in.friction > 0;
    rolling = rolling || in.rolling_friction > 0;
  }
  const RollingModel model = rolling ? scene.contact.rolling : RollingModel::None;
  const bool no_tensile = scene.contact.no_tensile_force;
  if (scene.contact.normal == NormalModel::Linear)
    return with_tension<LinearNormal>(no_tensile, friction, model, has_walls);
  return with_tension<HertzNormal>(no_tensile, friction, model, has_walls);
}

}  // namespace dem
