// Parallel bonds (Potyondy & Cundall 2004, IJRMMS 41:1329-1364; PDEM-EGD manual eqs. 8-11): an
// elastic disc of radius Rb = lambda min(RA, RB) glues two particles and carries a normal force, a
// shear force, a twisting and a bending moment, updated incrementally from the relative motion and
// turned with the bond plane. It breaks when the largest tensile or shear stress on the disc exceeds
// the bond's strength (eqs. 10-11). A contact bond carries the forces only (no moments).
#pragma once

#include <cstdint>

#include "core/vec.hpp"

namespace dem {

struct BondGeometry {
  double radius = 0;  // Rb
  double area = 0;    // A = pi Rb^2
  double inertia = 0; // I = pi Rb^4 / 4 (bending)
  double polar = 0;   // J = pi Rb^4 / 2 (twist)

  static BondGeometry of(double bond_radius);
};

enum class BondBreak : std::uint8_t { Intact, Tension, Shear };

// One bond between particles i and j (i < j), with its state. Forces and moments are those on i
// (j gets the opposite force; see bond_step for the moments).
struct Bond {
  int i = 0, j = 0;
  BondGeometry geometry;
  double kn = 0;               // normal stiffness per area, N/m^3 (Eb / (RA + RB))
  double ks = 0;               // shear stiffness per area, N/m^3
  double tensile_strength = 0; // Pa
  double shear_strength = 0;   // Pa
  bool moments = true;         // false: a contact bond (forces only)
  double normal_force = 0;     // on i along n (n from j to i): positive pushes i away (compression)
  Vec3 shear_force = Vec3::Zero();
  Vec3 twist = Vec3::Zero();   // moment on i along n
  Vec3 bending = Vec3::Zero(); // moment on i in the bond plane
  Vec3 normal = Vec3::Zero();  // n of the last step (to turn the stored vectors)
  BondBreak state = BondBreak::Intact;
  double broken_at = -1;       // time of the break, s
};

// The motion of i relative to j over one step, at the bond: everything bond_step needs.
struct BondMotion {
  Vec3 normal;         // unit, from j to i, now
  Vec3 velocity;       // of i's side of the bond relative to j's, at the bond centre
  Vec3 spin;           // w_i - w_j
};

struct BondLoad {
  Vec3 force;          // on i (j: -force)
  Vec3 moment_i;       // about i's centre, including the lever of the force
  Vec3 moment_j;       // about j's centre
};

// Updates the bond by one step of dt and returns its load; checks the break criterion after the
// update (then the bond carries nothing from this step on, and state/broken_at say how and when).
// lever_i and lever_j: from each centre to the bond centre.
BondLoad bond_step(Bond& bond, const BondMotion& motion, const Vec3& lever_i, const Vec3& lever_j, double dt,
                   double time);

// The largest tensile and shear stresses on the disc (eqs. 10-11), Pa.
double bond_tensile_stress(const Bond& bond);
double bond_shear_stress(const Bond& bond);

}  // namespace dem
