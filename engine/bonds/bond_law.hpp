// The elastic disc bond of Potyondy & Cundall (2004, IJRMMS 41:1329-1364; PDEM-EGD manual eqs.
// 8-11): a disc of radius Rb = lambda min(RA, RB) glues two particles and carries a normal force, a
// shear force, a twisting and a bending moment; it breaks when the largest tensile or shear stress
// on the disc exceeds the bond's strength (eqs. 10-11). The parallel bond carries all four, the
// contact bond the forces only (bonds/bond_models.hpp).
//
// The loads are P&C's increments (dFn = -kn A dUn, dFs = -ks A dUs, dMn = -ks J dth_n,
// dMs = -kn I dth_s) summed in closed form from the configuration, not from velocities step by step:
// the relative displacement of the two particles' attachment points at the bond centre and their
// relative rotation since the bond was made, each particle's orientation being integrated from its
// spin (the approach of Wang 2009, Acta Geotech. 4:117, and LAMMPS' bpm/rotational). The sum equals
// the increments to first order, and it is exactly zero for any rigid motion of the pair, at any
// time step: summing half-step velocities against end-of-step geometry instead opened a spinning
// bond by about omega dt R per radian turned (docs/physics.md, "Bonds").
#pragma once

#include <cstdint>

#include "core/vec.hpp"

namespace dem {

struct BondGeometry {
  double radius = 0;   // Rb
  double area = 0;     // A = pi Rb^2
  double inertia = 0;  // I = pi Rb^4 / 4 (bending)
  double polar = 0;    // J = pi Rb^4 / 2 (twist)

  static BondGeometry of(double bond_radius);
};

enum class BondBreak : std::uint8_t { Intact, Tension, Shear };

// One end of a bond as it is now: the particle's centre, orientation (body to space) and radius.
struct BondEnd {
  Vec3 x = Vec3::Zero();
  Quat q = Quat::Identity();
  double radius = 0;
};

// One bond between particles i and j (i < j). The loads are those on i, along n from j to i (j gets
// the opposite force; the moments follow bond_load).
struct Bond {
  int i = 0, j = 0;
  BondGeometry geometry;
  double kn = 0;                // normal stiffness per area, N/m^3 (Eb / (RA + RB))
  double ks = 0;                // shear stiffness per area, N/m^3
  double tensile_strength = 0;  // Pa
  double shear_strength = 0;    // Pa
  bool moments = true;          // false: a contact bond (forces only)
  BondBreak state = BondBreak::Intact;
  std::uint8_t padding[6] = {};  // saved with the state: its bytes are set, not whatever the memory held
  // The bonded state, from which the loads are measured: the distance of the centres, each centre's
  // distance to the bond centre along the bond, the direction to the other particle in each
  // particle's own frame, and the rotation from j's frame to i's (q_i^-1 q_j).
  double rest_length = 0;
  double lever_i = 0, lever_j = 0;
  Vec3 anchor_i = Vec3::Zero(), anchor_j = Vec3::Zero();
  double broken_at = -1;  // time of the break, s (here, so that `relative` falls on 16 bytes without padding)
  Quat relative = Quat::Identity();
  // The loads of the last evaluation.
  double normal_force = 0;  // on i along n: positive pushes i away (compression)
  Vec3 shear_force = Vec3::Zero();
  Vec3 twist = Vec3::Zero();    // moment on i along n
  Vec3 bending = Vec3::Zero();  // moment on i in the bond plane
};

// Records the pair's state now as the bond's unloaded state.
void glue(Bond& bond, const BondEnd& i, const BondEnd& j);

struct BondLoad {
  Vec3 force;     // on i (j: -force)
  Vec3 moment_i;  // about i's centre, including the lever of the force
  Vec3 moment_j;  // about j's centre
};

// The bond's loads for the ends as they are now (kept in the bond), then the break criterion: a
// bond past its strength breaks at `time` and carries nothing from then on.
BondLoad bond_load(Bond& bond, const BondEnd& i, const BondEnd& j, double time);

// The same for `count` intact bonds (bonds[k] between ends_i[k] and ends_j[k], its loads to out[k]),
// kBondLanes at a time: the same bits as bond_load on each in turn, in less time (a bond's load is a
// chain of dependent square roots and divisions that the lanes overlap).
inline constexpr int kBondLanes = 4;
void bond_loads(Bond* const bonds[], const BondEnd ends_i[], const BondEnd ends_j[], int count, double time,
                BondLoad out[]);

// The same bond with the roles of its particles exchanged (after a re-sort made j < i).
void swap_ends(Bond& bond);

// The largest tensile and shear stresses on the disc (eqs. 10-11), Pa.
double bond_tensile_stress(const Bond& bond);
double bond_shear_stress(const Bond& bond);

// Energy stored in the bond's springs, J.
double bond_energy(const Bond& bond);

}  // namespace dem
