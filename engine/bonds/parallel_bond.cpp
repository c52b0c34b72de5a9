#include "bonds/parallel_bond.hpp"

#include <cmath>
#include <numbers>

namespace dem {

BondGeometry BondGeometry::of(double bond_radius) {
  const double r2 = bond_radius * bond_radius;
  return {bond_radius, std::numbers::pi * r2, std::numbers::pi * r2 * r2 / 4, std::numbers::pi * r2 * r2 / 2};
}

namespace {

// The rotation that takes unit vector a to unit vector b (Rodrigues), found once per bond and step
// and applied to the stored shear force and bending moment: they follow the bond plane exactly,
// keeping their length (no energy leak).
struct Turn {
  Vec3 axis;  // unit
  double sin = 0, cos = 1;
  bool none = true;

  Turn(const Vec3& a, const Vec3& b) {
    const Vec3 cross = a.cross(b);
    sin = cross.norm();
    cos = a.dot(b);
    none = sin < 1e-300;
    if (!none) axis = cross / sin;
  }
  Vec3 operator()(const Vec3& v) const {
    if (none) return v;
    return v * cos + axis.cross(v) * sin + axis * (axis.dot(v) * (1 - cos));
  }
};

}  // namespace

double bond_tensile_stress(const Bond& b) {
  // eq. 10: sigma = -Fn / A + |Ms| Rb / I (Fn positive in compression)
  const double bend = b.moments ? b.bending.norm() * b.geometry.radius / b.geometry.inertia : 0.0;
  return -b.normal_force / b.geometry.area + bend;
}

double bond_shear_stress(const Bond& b) {
  // eq. 11: tau = |Fs| / A + |Mn| Rb / J
  const double twist = b.moments ? b.twist.norm() * b.geometry.radius / b.geometry.polar : 0.0;
  return b.shear_force.norm() / b.geometry.area + twist;
}

BondLoad bond_step(Bond& b, const BondMotion& m, const Vec3& lever_i, const Vec3& lever_j, double dt, double time) {
  if (b.state != BondBreak::Intact) return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  const Vec3& n = m.normal;
  if (!b.normal.isZero(0) && b.normal != n) {
    const Turn turn(b.normal, n);
    b.shear_force = turn(b.shear_force);
    b.bending = turn(b.bending);
    b.twist = b.twist.dot(b.normal) * n;  // along the axis: it turns with it
  }
  b.normal = n;
  // the increments of P&C eqs. 2-5 (dUn > 0 when i moves away from j: the compression drops)
  const double du_n = m.velocity.dot(n) * dt;
  const Vec3 du_s = (m.velocity - m.velocity.dot(n) * n) * dt;
  b.normal_force -= b.kn * b.geometry.area * du_n;
  b.shear_force -= b.ks * b.geometry.area * du_s;
  if (b.moments) {
    const double dth_n = m.spin.dot(n) * dt;
    const Vec3 dth_s = (m.spin - m.spin.dot(n) * n) * dt;
    b.twist -= (b.ks * b.geometry.polar * dth_n) * n;
    b.bending -= b.kn * b.geometry.inertia * dth_s;
  }
  // clean the stored vectors of rounding off the plane / axis
  b.shear_force -= b.shear_force.dot(n) * n;
  b.bending -= b.bending.dot(n) * n;
  b.twist = b.twist.dot(n) * n;

  const BondLoad load{b.normal_force * n + b.shear_force, Vec3::Zero(), Vec3::Zero()};
  const Vec3 moment = b.twist + b.bending;
  BondLoad out = load;
  out.moment_i = moment + lever_i.cross(load.force);
  out.moment_j = -moment + lever_j.cross(-load.force);

  if (bond_tensile_stress(b) >= b.tensile_strength) {
    b.state = BondBreak::Tension;
  } else if (bond_shear_stress(b) >= b.shear_strength) {
    b.state = BondBreak::Shear;
  }
  if (b.state == BondBreak::Intact) return out;
  b.broken_at = time;  // it gave way during this step: it carries nothing more
  return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
}

}  // namespace dem
