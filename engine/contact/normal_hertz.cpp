#include "contact/normal_hertz.hpp"

#include <algorithm>
#include <numbers>

#include "contact/restitution_damping.hpp"
#include "sim/kernel_factory_impl.hpp"

namespace dem {

HertzNormal::Pair HertzNormal::mix(const Material& a, const Material& b, const Interaction& in,
                                   const ContactSettings& c) {
  Pair p;
  const double na = a.poisson_ratio, nb = b.poisson_ratio;
  const double ea = a.rigid ? 0 : (1 - na * na) / a.youngs_modulus;
  const double eb = b.rigid ? 0 : (1 - nb * nb) / b.youngs_modulus;
  const double ga = a.rigid ? 0 : 2 * (2 - na) * (1 + na) / a.youngs_modulus;
  const double gb = b.rigid ? 0 : 2 * (2 - nb) * (1 + nb) / b.youngs_modulus;
  if (ea + eb > 0) p.e_star = 1 / (ea + eb);
  if (ga + gb > 0) p.g_star = 1 / (ga + gb);
  p.eta = hertz_damping_number(in.restitution, c.no_tensile_force);
  p.hertz_cn = p.eta * std::sqrt(4.0 / 3.0 * p.e_star);
  p.hertz_ct = p.eta * std::sqrt(2.0 / 3.0 * 8 * p.g_star);
  return p;
}

double HertzNormal::contact_time(const Pair& p, double m_eff, double r_eff, double v) {
  if (p.e_star <= 0) return kUnbounded;
  const double alpha = std::pow(15 * m_eff * v * v / (16 * std::sqrt(r_eff) * p.e_star), 0.4);
  return 2.9432 * alpha / v / std::max(1.0, p.eta);
}

double HertzNormal::wave_time(const Material& m, double r_min) {
  const double shear_modulus = m.youngs_modulus / (2 * (1 + m.poisson_ratio));
  return std::numbers::pi * r_min * std::sqrt(m.density / shear_modulus) / (0.1631 * m.poisson_ratio + 0.8766);
}

// The force loops of this law (one translation unit per normal law: they compile in parallel).
template std::unique_ptr<ForceKernel> make_force_kernel<HertzNormal>(const Scene&, bool);

}  // namespace dem
