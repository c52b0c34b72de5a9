// Picks the force loop once from what the scene contains, so that a scene without walls, friction,
// rolling resistance or tension clamping does not pay for them inside the loop.
#pragma once

#include <memory>
#include <string>

#include "contact/models.hpp"
#include "core/errors.hpp"
#include "sim/kernel_factory.hpp"

namespace dem {

// The loop of the normal model the scene names, among `Normals`; throws SceneError for a name
// that is not in the list.
template <class... Normals>
std::unique_ptr<ForceKernel> select_kernel_from(ModelList<Normals...>, const Scene& scene, bool has_walls) {
  std::unique_ptr<ForceKernel> kernel;
  (void)((Normals::kName == scene.contact.normal && (kernel = make_force_kernel<Normals>(scene, has_walls), true)) ||
         ...);
  if (!kernel) throw SceneError("contact.normal: no normal model named \"" + scene.contact.normal + "\"");
  return kernel;
}

// The engine's own models (contact/models.hpp).
std::unique_ptr<ForceKernel> select_kernel(const Scene& scene, bool has_walls);

using KernelSelector = std::unique_ptr<ForceKernel> (*)(const Scene& scene, bool has_walls);

}  // namespace dem
