// The range of each kind of input quantity the engine accepts, in SI units. The bounds are far
// beyond any scene of granular mechanics (a speed past light's, a body larger than a planet) and
// far below where squares and products of them overflow a double, or their quotients underflow to a
// time step of zero: a value outside is a mistake of units or of typing, refused with the field's
// path (docs/spec.md, "Input range").
#pragma once

namespace dem::spec {

struct Quantity {
  double min;  // smallest value of a positive quantity (a vector's components may be 0)
  double max;  // largest magnitude of a value (each component of a vector)
  const char* unit;
};

inline constexpr Quantity kLength{1e-9, 1e9, "m"};  // positions, corners, boxes, mesh coordinates
inline constexpr Quantity kRadius{1e-9, 1e6, "m"};  // a nanometre to a planet
inline constexpr Quantity kSpeed{0, 3e8, "m/s"};    // the speed of light
inline constexpr Quantity kAngularSpeed{0, 1e9, "rad/s"};
inline constexpr Quantity kAcceleration{0, 1e9, "m/s^2"};  // gravity
inline constexpr Quantity kForce{0, 1e15, "N"};
inline constexpr Quantity kDirection{0, 1e100, ""};        // normals and directions (made unit)
inline constexpr Quantity kDensity{1e-3, 1e12, "kg/m^3"};  // room for density scaling
inline constexpr Quantity kModulus{1e-3, 1e15, "Pa"};      // Young's moduli, strengths
inline constexpr Quantity kStiffness{1e-6, 1e18, "N/m"};
inline constexpr Quantity kRatio{1e-3, 1e3, ""};         // bonds.radiusMultiplier: the disc's radius / the sphere's
inline constexpr Quantity kCoefficient{1e-12, 1e3, ""};  // friction, stiffness and strength ratios, spreads, tolerances
inline constexpr Quantity kMass{1e-30, 1e15, "kg"};      // a nanometre grain of light foam to a mountain
inline constexpr Quantity kInertia{1e-50, 1e30, "kg m^2"};
inline constexpr Quantity kFrequency{1e-9, 1e9, "Hz"};
inline constexpr Quantity kDuration{1e-12, 1e12, "s"};  // a stage's length
inline constexpr Quantity kEnergy{0, 1e30, "J"};
inline constexpr Quantity kGain{1e-15, 1e6, "m/(N s)"};  // a servo's speed per newton of force error

}  // namespace dem::spec
