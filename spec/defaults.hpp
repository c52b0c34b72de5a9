// What a spec field left out (or 0, protobuf's "not given") stands for, where the loader fills it
// in: in one place, so that docs/spec.md and the loader cannot drift apart field by field. The
// engine's own settings (numerics, time stepping, outputs) keep their defaults in core/scene.hpp.
#pragma once

#include <cstdint>

namespace dem::spec::defaults {

inline constexpr std::uint32_t kSeed = 1;      // packings, bonds, ballast stones, sources
inline constexpr double kLatticeSpacing = 1;   // nearest-neighbour distance over the diameter
inline constexpr double kSmallFraction = 0.5;  // two sizes: share of the small ones by count
inline constexpr double kMeshScale = 1;        // metres per mesh file unit
inline constexpr double kClumpScale = 1;
inline constexpr double kClumpAccuracy = 1e-4;  // of the subdivision of a clump's volume
inline constexpr int kStoneMinSpheres = 3;
inline constexpr int kStoneMaxSpheresAtLeast = 12;  // maxSpheres: at least this, and minSpheres
inline constexpr int kStoneShapes = 32;
inline constexpr double kBondRadiusMultiplier = 1;
inline constexpr double kBondShearStiffnessRatio = 1;
inline constexpr double kBondGapTolerance = 1e-3;  // of the smaller radius
inline constexpr double kLengthUnit = 1;           // outputs in metres
inline constexpr double kDiscThickness = 1;        // m, a 2D run's discs (PFC2D's unit thickness)

}  // namespace dem::spec::defaults
