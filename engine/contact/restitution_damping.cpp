#include "contact/restitution_damping.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <numbers>
#include <tuple>
#include <utility>

namespace dem {
namespace {

// Integrates x'' = -force(x, x') from x = 0, x' = 1 until the bodies part (x back to 0) and returns
// the rebound speed. The force is the repulsive contact force; clamped at zero if asked.
double dimensionless_rebound(const std::function<double(double, double)>& force, bool no_tensile) {
  auto accel = [&](double x, double xd) {
    double f = force(std::max(x, 0.0), xd);
    if (no_tensile) f = std::max(f, 0.0);
    return -f;
  };
  const double h = 1e-3;  // 1/3000 of the dimensionless contact time: e to ~1e-7 (RK4)
  double x = 0, xd = 1;
  for (int step = 0; step < 400'000; ++step) {
    // RK4 on (x, x')
    const double k1x = xd, k1v = accel(x, xd);
    const double k2x = xd + 0.5 * h * k1v, k2v = accel(x + 0.5 * h * k1x, xd + 0.5 * h * k1v);
    const double k3x = xd + 0.5 * h * k2v, k3v = accel(x + 0.5 * h * k2x, xd + 0.5 * h * k2v);
    const double k4x = xd + h * k3v, k4v = accel(x + h * k3x, xd + h * k3v);
    const double xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double vn = xd + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (xn <= 0) {
      const double s = x / (x - xn);  // interpolate the rebound speed at the crossing
      return -(xd + s * (vn - xd));
    }
    x = xn;
    xd = vn;
  }
  return 0;  // overdamped: the bodies never part
}

double invert_decreasing(const std::function<double(double)>& e_of, double e, double hi) {
  if (e >= 1) return 0;
  double lo = 0;
  while (e_of(hi) > e) hi *= 2;
  for (int it = 0; it < 45; ++it) {  // bracket / 2^45: far below the 1e-7 integration error
    const double mid = 0.5 * (lo + hi);
    if (e_of(mid) > e)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

// The inversions integrate an ODE some hundred times: each (law, e, clamp) is solved once per process.
double remembered(int law, double e, bool no_tensile, const std::function<double()>& solve) {
  static std::mutex mutex;
  static std::map<std::tuple<int, double, bool>, double> solved;
  const auto key = std::make_tuple(law, e, no_tensile);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto it = solved.find(key);
    if (it != solved.end()) return it->second;
  }
  const double value = solve();
  const std::lock_guard<std::mutex> lock(mutex);
  solved.emplace(key, value);
  return value;
}

}  // namespace

double linear_restitution(double zeta, bool no_tensile_force) {
  return dimensionless_rebound([zeta](double x, double xd) { return x + 2 * zeta * xd; }, no_tensile_force);
}

double hertz_restitution(double eta, bool no_tensile_force) {
  return dimensionless_rebound(
      [eta](double x, double xd) { return x * std::sqrt(x) + eta * std::sqrt(std::sqrt(x)) * xd; }, no_tensile_force);
}

double linear_damping_ratio(double e, bool no_tensile_force) {
  if (!no_tensile_force) {
    // the PDEM-EGD manual's eq. 6 (exact for the linear law when tension is allowed)
    const double l = std::log(e);
    return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
  }
  return remembered(0, e, true,
                    [e] { return invert_decreasing([](double z) { return linear_restitution(z, true); }, e, 1.0); });
}

double hertz_damping_number(double e, bool no_tensile_force) {
  return remembered(1, e, no_tensile_force, [e, no_tensile_force] {
    return invert_decreasing([no_tensile_force](double eta) { return hertz_restitution(eta, no_tensile_force); }, e,
                             2.0);
  });
}

}  // namespace dem
