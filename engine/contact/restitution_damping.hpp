// Damping coefficients that give a requested coefficient of restitution e.
//
// Both normal laws are written in a dimensionless form in which e depends on one damping number
// only (not on the impact speed), so e -> damping is found once per material pair:
//   linear:  x'' = -x - 2 zeta x'                (zeta: the PDEM-EGD manual's eq. 6 when tension is allowed)
//   Hertz:   x'' = -x^1.5 - eta x^0.25 x'        (Tsuji et al. 1992 form; eta = sqrt(5) * |beta| of
//                                                 the usual fit, which is only approximate)
// With "no tensile force" the contact force is clamped at zero, which ends the contact early and
// raises e (Thornton et al. 2013, Powder Technol. 233:30-46): the usual fits are then wrong, so the
// damping number is found by integrating the dimensionless equation and solving for e.
#pragma once

namespace dem {

// Restitution of the dimensionless impact, by integration (exposed for tests and the docs' table).
double linear_restitution(double zeta, bool no_tensile_force);
double hertz_restitution(double eta, bool no_tensile_force);

// The inverse: the damping number that yields restitution e (0 < e <= 1).
double linear_damping_ratio(double e, bool no_tensile_force);
double hertz_damping_number(double e, bool no_tensile_force);

}  // namespace dem
