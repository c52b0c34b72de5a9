#include "bonds/bond_law.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "core/rotation.hpp"

namespace dem {

BondGeometry BondGeometry::of(double bond_radius) {
  const double r2 = bond_radius * bond_radius;
  return {bond_radius, std::numbers::pi * r2, std::numbers::pi * r2 * r2 / 4, std::numbers::pi * r2 * r2 / 2};
}

void glue(Bond& b, const BondEnd& i, const BondEnd& j) {
  const Vec3 d = i.x - j.x;
  const double length = d.norm();
  const Vec3 n = d / length;
  const double gap = length - i.radius - j.radius;
  b.rest_length = length;
  b.lever_i = i.radius + 0.5 * gap;
  b.lever_j = j.radius + 0.5 * gap;
  b.anchor_i = i.q.conjugate() * Vec3(-n);
  b.anchor_j = j.q.conjugate() * n;
  b.relative = i.q.conjugate() * j.q;
  b.normal_force = 0;
  b.shear_force = b.twist = b.bending = Vec3::Zero();
}

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

BondLoad bond_load(Bond& b, const BondEnd& i, const BondEnd& j, double time) {
  if (b.state != BondBreak::Intact) return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  const Vec3 d = i.x - j.x;
  const double dist = d.norm();
  const Vec3 n = d / dist;
  const BondGeometry& g = b.geometry;
  // P&C's dUn summed: the change of the centres' distance
  b.normal_force = -b.kn * g.area * (dist - b.rest_length);
  // dUs summed: where i's and j's attachment points at the bond centre have moved apart, in the plane
  const Vec3 arm_i = b.lever_i * (i.q * b.anchor_i), arm_j = b.lever_j * (j.q * b.anchor_j);
  const Vec3 apart = (i.x + arm_i) - (j.x + arm_j);
  const double apart_n = apart.dot(n);
  b.shear_force = -b.ks * g.area * (apart - apart_n * n);
  if (b.moments) {
    // the rotation of i relative to j since the bond was made, in space: q_i q_i0^-1 q_j0 q_j^-1
    const Vec3 turn = rotation_vector(i.q * b.relative * j.q.conjugate());
    const Vec3 twist_angle = turn.dot(n) * n;
    b.twist = -b.ks * g.polar * twist_angle;
    b.bending = -b.kn * g.inertia * (turn - twist_angle);
  }
  // The forces and moments are the gradients of the springs' energy (bond_energy), so that a bond
  // left to itself keeps its energy and the pair's angular momentum: the normal spring pulls along
  // the line of centres; the shear spring, 1/2 ks A |apart in the plane|^2, turns each particle about
  // its own attachment point (which rolls off the line of centres when the spheres roll on each
  // other, a motion a contact bond does not resist) and pulls the centres with the plane's tilt
  // taken into account (the factor 1 - apart_n / dist). Turning about the line of centres instead
  // made two contact-bonded spheres of 10 and 5 mm rolling on each other gain 5% of their energy in
  // 0.05 s, at any time step.
  BondLoad out{b.normal_force * n + (1 - apart_n / dist) * b.shear_force, Vec3::Zero(), Vec3::Zero()};
  const Vec3 moment = b.twist + b.bending;
  out.moment_i = moment + arm_i.cross(b.shear_force);
  out.moment_j = -moment - arm_j.cross(b.shear_force);

  if (bond_tensile_stress(b) >= b.tensile_strength) {
    b.state = BondBreak::Tension;
  } else if (bond_shear_stress(b) >= b.shear_strength) {
    b.state = BondBreak::Shear;
  }
  if (b.state == BondBreak::Intact) return out;
  b.broken_at = time;  // it gave way during this step: it carries nothing more
  return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
}

void swap_ends(Bond& b) {
  std::swap(b.i, b.j);
  std::swap(b.lever_i, b.lever_j);
  std::swap(b.anchor_i, b.anchor_j);
  b.relative = b.relative.conjugate();
  // the loads are i's: the new i carries what the old j did
  b.shear_force = -b.shear_force;
  b.twist = -b.twist;
  b.bending = -b.bending;
}

double bond_energy(const Bond& b) {
  if (b.state != BondBreak::Intact || b.kn <= 0) return 0;
  const BondGeometry& g = b.geometry;
  double e = b.normal_force * b.normal_force / (2 * b.kn * g.area) + b.shear_force.squaredNorm() / (2 * b.ks * g.area);
  if (b.moments) e += b.twist.squaredNorm() / (2 * b.ks * g.polar) + b.bending.squaredNorm() / (2 * b.kn * g.inertia);
  return e;
}

}  // namespace dem
