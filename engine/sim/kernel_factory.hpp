// The kernels of one normal law: every combination of tension clamping, friction, rolling model
// and walls, each a separate instantiation of the force loop. Split by normal law into two
// translation units (kernels_linear.cpp, kernels_hertz.cpp) so that they compile in parallel.
#pragma once

#include <memory>
#include <stdexcept>

#include "sim/force_kernel_impl.hpp"

namespace dem::kernels {

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

std::unique_ptr<ForceKernel> linear(bool no_tensile, bool friction, RollingModel rolling, bool has_walls);
std::unique_ptr<ForceKernel> hertz(bool no_tensile, bool friction, RollingModel rolling, bool has_walls);

}  // namespace dem::kernels
