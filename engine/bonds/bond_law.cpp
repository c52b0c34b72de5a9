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

namespace {

// The loads of N intact bonds, each in its own lane [k]. A bond's load is one chain of dependent
// square roots, divisions and an atan2; taken in three passes over N bonds, the processor has N
// chains to overlap (docs/benchmarks.md, "Bonded scenes": 98 ns a bond alone, 87 ns four at a time). Each lane
// evaluates exactly the expressions of one bond in the same order, so the bits are those of one bond at a time.
template <int N>
void load_lanes(Bond* const bond[], const BondEnd ends_i[], const BondEnd ends_j[], double time, BondLoad out[]) {
  double dist[N], apart_n[N];
  Vec3 n[N], arm_i[N], arm_j[N];
  Quat turned[N];
  for (int k = 0; k < N; ++k) {
    Bond& b = *bond[k];
    const BondEnd &i = ends_i[k], &j = ends_j[k];
    const Vec3 d = i.x - j.x;
    dist[k] = d.norm();
    n[k] = d / dist[k];
    const BondGeometry& g = b.geometry;
    // P&C's dUn summed: the change of the centres' distance
    b.normal_force = -b.kn * g.area * (dist[k] - b.rest_length);
    // dUs summed: where i's and j's attachment points at the bond centre have moved apart, in the plane
    arm_i[k] = b.lever_i * (i.q * b.anchor_i), arm_j[k] = b.lever_j * (j.q * b.anchor_j);
    const Vec3 apart = (i.x + arm_i[k]) - (j.x + arm_j[k]);
    apart_n[k] = apart.dot(n[k]);
    b.shear_force = -b.ks * g.area * (apart - apart_n[k] * n[k]);
    // the rotation of i relative to j since the bond was made, in space: q_i q_i0^-1 q_j0 q_j^-1
    turned[k] = b.moments ? Quat(i.q * b.relative * j.q.conjugate()) : Quat::Identity();
  }
  for (int k = 0; k < N; ++k) {
    Bond& b = *bond[k];
    if (!b.moments) continue;
    const Vec3 turn = rotation_vector(turned[k]);
    const Vec3 twist_angle = turn.dot(n[k]) * n[k];
    b.twist = -b.ks * b.geometry.polar * twist_angle;
    b.bending = -b.kn * b.geometry.inertia * (turn - twist_angle);
  }
  for (int k = 0; k < N; ++k) {
    Bond& b = *bond[k];
    // The forces and moments are the gradients of the springs' energy (bond_energy), so that a bond
    // left to itself keeps its energy and the pair's angular momentum: the normal spring pulls along
    // the line of centres; the shear spring, 1/2 ks A |apart in the plane|^2, turns each particle
    // about its own attachment point (which rolls off the line of centres when the spheres roll on
    // each other, a motion a contact bond does not resist) and pulls the centres with the plane's
    // tilt taken into account (the factor 1 - apart_n / dist). Turning about the line of centres
    // instead made two contact-bonded spheres of 10 and 5 mm rolling on each other gain 5% of their
    // energy in 0.05 s, at any time step.
    out[k] = {b.normal_force * n[k] + (1 - apart_n[k] / dist[k]) * b.shear_force, Vec3::Zero(), Vec3::Zero()};
    const Vec3 moment = b.twist + b.bending;
    out[k].moment_i = moment + arm_i[k].cross(b.shear_force);
    out[k].moment_j = -moment - arm_j[k].cross(b.shear_force);

    if (bond_tensile_stress(b) >= b.tensile_strength) {
      b.state = BondBreak::Tension;
    } else if (bond_shear_stress(b) >= b.shear_strength) {
      b.state = BondBreak::Shear;
    }
    if (b.state == BondBreak::Intact) continue;
    b.broken_at = time;  // it gave way during this step: it carries nothing more
    out[k] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  }
}

}  // namespace

BondLoad bond_load(Bond& b, const BondEnd& i, const BondEnd& j, double time) {
  BondLoad out{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  if (b.state != BondBreak::Intact) return out;
  Bond* const bond[1] = {&b};
  load_lanes<1>(bond, &i, &j, time, &out);
  return out;
}

void bond_loads(Bond* const bonds[], const BondEnd ends_i[], const BondEnd ends_j[], int count, double time,
                BondLoad out[]) {
  int k = 0;
  for (; k + kBondLanes <= count; k += kBondLanes)
    load_lanes<kBondLanes>(bonds + k, ends_i + k, ends_j + k, time, out + k);
  for (; k < count; ++k) load_lanes<1>(bonds + k, ends_i + k, ends_j + k, time, out + k);
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
