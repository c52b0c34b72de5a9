#include "contact/pair_params.hpp"

#include <cmath>
#include <map>
#include <utility>

#include "contact/restitution_damping.hpp"

namespace dem {

PairTable::PairTable(const Scene& scene) : count_(static_cast<int>(scene.materials.size())) {
  params_.resize(static_cast<size_t>(count_) * count_);
  const ContactSettings& c = scene.contact;
  std::map<double, double> damping_of_e;  // the inversion integrates an ODE: do each e once
  auto damping = [&](double e) {
    auto it = damping_of_e.find(e);
    if (it != damping_of_e.end()) return it->second;
    const double d = c.normal == NormalModel::Linear ? linear_damping_ratio(e, c.no_tensile_force)
                                                     : hertz_damping_number(e, c.no_tensile_force);
    damping_of_e.emplace(e, d);
    return d;
  };
  for (int a = 0; a < count_; ++a) {
    for (int b = 0; b < count_; ++b) {
      const Material& ma = scene.materials[a];
      const Material& mb = scene.materials[b];
      const Interaction& in = scene.interaction(a, b);
      PairParams& p = params_[a * count_ + b];
      // Series compliances; a rigid body adds none (K_n = 2 kA kB / (kA + kB) is eq. 4 of the seeds).
      const double ca = ma.rigid ? 0 : 1 / ma.normal_stiffness, cb = mb.rigid ? 0 : 1 / mb.normal_stiffness;
      if (ca + cb > 0) p.kn = 2 / (ca + cb);
      p.kt_ratio = c.tangential_stiffness_ratio;
      p.ct_ratio = c.tangential_damping_ratio;
      const double na = ma.poisson_ratio, nb = mb.poisson_ratio;
      const double ea = ma.rigid ? 0 : (1 - na * na) / ma.youngs_modulus;
      const double eb = mb.rigid ? 0 : (1 - nb * nb) / mb.youngs_modulus;
      const double ga = ma.rigid ? 0 : 2 * (2 - na) * (1 + na) / ma.youngs_modulus;
      const double gb = mb.rigid ? 0 : 2 * (2 - nb) * (1 + nb) / mb.youngs_modulus;
      if (ea + eb > 0) p.e_star = 1 / (ea + eb);
      if (ga + gb > 0) p.g_star = 1 / (ga + gb);
      p.restitution = in.restitution;
      if (c.normal == NormalModel::Linear) p.zeta = damping(in.restitution);
      else p.eta = damping(in.restitution);
      p.cn_per_sqrt_mass = 2 * p.zeta * std::sqrt(p.kn);
      p.hertz_cn = p.eta * std::sqrt(4.0 / 3.0 * p.e_star);
      p.hertz_ct = p.eta * std::sqrt(2.0 / 3.0 * 8 * p.g_star);
      p.mu = in.friction;
      p.mu_r = in.rolling_friction;
      p.rolling_damping = c.rolling_damping_ratio;
    }
  }
}

}  // namespace dem
