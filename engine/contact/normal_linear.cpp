#include "contact/normal_linear.hpp"

#include <numbers>

#include "contact/restitution_damping.hpp"
#include "sim/kernel_factory_impl.hpp"

namespace dem {

LinearNormal::Pair LinearNormal::mix(const Material& a, const Material& b, const Interaction& in,
                                     const ContactSettings& c) {
  Pair p;
  // Series compliances; a rigid body adds none (K_n = 2 kA kB / (kA + kB) is eq. 4 of the manuals).
  const double ca = a.rigid ? 0 : 1 / a.normal_stiffness, cb = b.rigid ? 0 : 1 / b.normal_stiffness;
  if (ca + cb > 0) p.kn = 2 / (ca + cb);
  p.kt_ratio = c.parameters.value(kStiffnessRatio);
  p.ct_ratio = c.parameters.value(kDampingRatio);
  p.zeta = linear_damping_ratio(in.restitution, c.no_tensile_force);
  p.cn_per_sqrt_mass = 2 * p.zeta * std::sqrt(p.kn);
  return p;
}

double LinearNormal::contact_time(const Pair& p, double m_eff, double, double) {
  if (p.kn <= 0) return kUnbounded;
  const double omega = std::sqrt(p.kn / m_eff);
  if (p.zeta <= 0.5) return std::numbers::pi / (omega * std::sqrt(1 - p.zeta * p.zeta));
  return std::numbers::pi / (omega * std::sqrt(0.75) * 2 * p.zeta);
}

// The force loops of this law (one translation unit per normal law: they compile in parallel).
template std::unique_ptr<ForceKernel> make_force_kernel<LinearNormal>(const Scene&, bool);

}  // namespace dem
