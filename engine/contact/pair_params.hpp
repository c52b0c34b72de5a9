// Contact coefficients of every pair of materials, computed once from the scene.
#pragma once

#include <vector>

#include "core/scene.hpp"

namespace dem {

struct PairParams {
  // linear spring-dashpot (the seeds' eqs. 1-7)
  double kn = 0;        // K_n = 2 kA kB / (kA + kB)   (eq. 4)
  double kt_ratio = 0;  // K_s / K_n (rns)
  double ct_ratio = 0;  // C_s / C_n (rzs)
  double zeta = 0;      // C_n = 2 zeta sqrt(m* K_n)     (eqs. 5-6; corrected for no tension)
  double cn_per_sqrt_mass = 0;  // 2 zeta sqrt(K_n): C_n = this * sqrt(m*)
  // Hertz-Mindlin
  double e_star = 0;    // 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2
  double g_star = 0;    // 1/G* = 2(2-nu1)(1+nu1)/E1 + 2(2-nu2)(1+nu2)/E2
  double eta = 0;       // damping number of the dimensionless Hertz impact (restitution_damping.hpp)
  double hertz_cn = 0;  // eta sqrt(4/3 E*):  C_n = this * (R* d)^(1/4) * sqrt(m*)
  double hertz_ct = 0;  // eta sqrt(16/3 G*): C_t = this * (R* d)^(1/4) * sqrt(m*)
  // both
  double mu = 0;
  double mu_r = 0;
  double rolling_damping = 0;  // eta_r of the EPSD rolling model
  double restitution = 1;
};

class PairTable {
 public:
  PairTable() = default;
  explicit PairTable(const Scene& scene);

  const PairParams& operator()(int a, int b) const { return params_[a * count_ + b]; }
  int material_count() const { return count_; }

 private:
  int count_ = 0;
  std::vector<PairParams> params_;
};

}  // namespace dem
