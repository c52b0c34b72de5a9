// The definition of make_force_kernel (kernel_factory.hpp): it walks the lists of contact/models.hpp,
// so that adding a tangential or rolling model there adds its loops for every normal model.
#pragma once

#include <string>
#include <string_view>

#include "contact/contact_law.hpp"
#include "contact/models.hpp"
#include "core/errors.hpp"
#include "sim/force_kernel_impl.hpp"
#include "sim/kernel_factory.hpp"

namespace dem {
namespace kernels {

template <class Normal, bool NoTensile, class Tangential, class... Rollings>
std::unique_ptr<ForceKernel> with_rolling(const Scene& scene, bool has_walls, std::string_view rolling,
                                          ModelList<Rollings...>) {
  std::unique_ptr<ForceKernel> kernel;
  (void)((Rollings::kName == rolling &&
          (kernel =
               std::make_unique<ForceKernelImpl<ContactLaw<Normal, NoTensile, Tangential, Rollings>>>(scene, has_walls),
           true)) ||
         ...);
  return kernel;
}

// The first tangential model that wants the scene.
template <class Normal, bool NoTensile, class... Tangentials>
std::unique_ptr<ForceKernel> with_tangential(const Scene& scene, bool has_walls, std::string_view rolling,
                                             ModelList<Tangentials...>) {
  std::unique_ptr<ForceKernel> kernel;
  (void)((Tangentials::wanted(scene) &&
          (kernel = with_rolling<Normal, NoTensile, Tangentials>(scene, has_walls, rolling, RollingModels{}), true)) ||
         ...);
  return kernel;
}

// A rolling model only where some pair has rolling friction: otherwise the loop without one.
inline std::string_view rolling_in_use(const Scene& scene) {
  for (const Interaction& in : scene.interactions)
    if (in.rolling_friction > 0) return scene.contact.rolling;
  return NoRolling::kName;
}

}  // namespace kernels

template <class Normal>
std::unique_ptr<ForceKernel> make_force_kernel(const Scene& scene, bool has_walls) {
  const std::string_view rolling = kernels::rolling_in_use(scene);
  std::unique_ptr<ForceKernel> kernel =
      scene.contact.no_tensile_force
          ? kernels::with_tangential<Normal, true>(scene, has_walls, rolling, TangentialModels{})
          : kernels::with_tangential<Normal, false>(scene, has_walls, rolling, TangentialModels{});
  if (!kernel) throw SceneError("contact.rolling: no rolling model named \"" + std::string(rolling) + "\"");
  return kernel;
}

}  // namespace dem
