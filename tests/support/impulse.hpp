// Rigid-body impact theory in gross sliding, the closed form that Chung & Ooi (2011) tests 4-8
// check DEM codes against (e.g. Maw, Barber & Fawcett 1976; Wu, Thornton & Li 2003): the normal
// impulse P_n = (1 + e) m* V_n, and a friction impulse mu P_n opposing the initial slip of the
// contact point, whose direction does not change while the contact slides throughout.
#pragma once

#include <limits>

#include "core/vec.hpp"

namespace dem::test {

struct Body {
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
  double m = std::numeric_limits<double>::infinity();  // a wall: infinite mass and inertia
  double inertia = std::numeric_limits<double>::infinity();
  double r = 0;
};

struct ImpactResult {
  Body i, j;
  bool gross_sliding = false;  // the contact point still slides in the same direction at the end
};

// n: unit normal from j to i at the contact point.
inline ImpactResult impact_in_gross_sliding(Body i, Body j, const Vec3& n, double e, double mu) {
  auto slip_of = [&](const Body& a, const Body& b) {
    const Vec3 u = a.v - b.v - (a.r * a.w + b.r * b.w).cross(n);
    return Vec3(u - u.dot(n) * n);
  };
  const Vec3 u = i.v - j.v - (i.r * i.w + j.r * j.w).cross(n);
  const double approach = -u.dot(n);
  const double inv_m = 1 / i.m + (std::isinf(j.m) ? 0 : 1 / j.m);
  const double pn = (1 + e) * approach / inv_m;
  const Vec3 slip0 = slip_of(i, j);
  const Vec3 s = slip0.norm() > 0 ? Vec3(slip0.normalized()) : Vec3::Zero();
  const Vec3 impulse_on_i = pn * n - mu * pn * s;
  ImpactResult out{i, j, false};
  out.i.v += impulse_on_i / i.m;
  out.i.w += i.r * mu * pn * n.cross(s) / i.inertia;
  if (!std::isinf(j.m)) {
    out.j.v -= impulse_on_i / j.m;
    out.j.w += j.r * mu * pn * n.cross(s) / j.inertia;
  }
  out.gross_sliding = slip_of(out.i, out.j).dot(s) > 0;
  return out;
}

}  // namespace dem::test
