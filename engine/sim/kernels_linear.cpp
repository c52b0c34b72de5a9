// The force loops of the linear normal law (see sim/kernel_factory.hpp).
#include "sim/kernel_factory.hpp"

namespace dem::kernels {

std::unique_ptr<ForceKernel> linear(bool no_tensile, bool friction, RollingModel rolling, bool has_walls) {
  return with_tension<LinearNormal>(no_tensile, friction, rolling, has_walls);
}

}  // namespace dem::kernels
