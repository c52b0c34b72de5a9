// The force loops of one normal model: every combination of the tension clamp, the tangential and
// rolling models (contact/models.hpp) and walls, each a separate instantiation of the force loop.
// Defined in kernel_factory_impl.hpp; each normal model's .cpp instantiates its own, so that the
// laws compile in parallel.
#pragma once

#include <memory>

#include "core/scene.hpp"
#include "sim/force_kernel.hpp"

namespace dem {

// The loop for this normal model and the rest of the scene's choice; throws SceneError when
// contact.rolling names no rolling model.
template <class Normal>
std::unique_ptr<ForceKernel> make_force_kernel(const Scene& scene, bool has_walls);

}  // namespace dem
