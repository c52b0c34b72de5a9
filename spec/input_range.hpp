// The range of each kind of input quantity the engine accepts, in SI units. The bounds are far
// beyond any scene of granular mechanics (a speed past light's, a body larger than a planet) and
// far below where squares and products of them overflow a double: a value outside is a mistake of
// units or of typing, refused with the field's path (docs/spec.md, "Input range").
#pragma once

namespace dem::spec {

struct Quantity {
  double max;        // largest magnitude of a value (each component of a vector)
  const char* unit;
};

inline constexpr Quantity kLength{1e9, "m"};              // positions, corners, boxes, mesh coordinates
inline constexpr Quantity kRadius{1e6, "m"};
inline constexpr Quantity kSpeed{3e8, "m/s"};             // the speed of light
inline constexpr Quantity kAngularSpeed{1e9, "rad/s"};
inline constexpr Quantity kAcceleration{1e9, "m/s^2"};    // gravity
inline constexpr Quantity kForce{1e15, "N"};
inline constexpr Quantity kDirection{1e100, ""};          // normals and directions (made unit)
inline constexpr Quantity kDensity{1e12, "kg/m^3"};       // room for density scaling
inline constexpr Quantity kModulus{1e15, "Pa"};           // Young's moduli, strengths
inline constexpr Quantity kStiffness{1e18, "N/m"};

}  // namespace dem::spec
