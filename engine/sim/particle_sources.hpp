// Particles that enter during a run (Scene::sources): which are due, and where they go.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/particles.hpp"
#include "core/scene.hpp"

namespace dem {

// What a source has done so far; saved with the state, so that a continued run inserts the same.
struct SourceProgress {
  std::int64_t inserted = 0;         // particles inserted: the next one's index in the source's sequence
  double mass = 0;                   // kg inserted
  std::uint64_t draws = 0;           // random numbers used for the places (the placement's sequence)
  std::int64_t last_attempt = -1;    // the step of the last batch (-1: none yet)
  std::int64_t crowded_batches = 0;  // batches that found no room for a particle due (it waited)
};

// The radius of particle k of the source's sequence: a pure function of the seed and k.
double source_radius(const ParticleSource& source, std::int64_t k);

// The smallest and largest particle the source can insert, at the region's extreme corners with the
// source's velocity (the time step and the scene's extent must allow for them before they exist).
std::vector<ParticleInit> source_extremes(const Scene& scene, const ParticleSource& source);

// Whether the source has inserted its total (mass or count): none given, nothing owed by it.
// A total the rate and the window do not reach is worth saying (a study of sand masses above it
// would give the same run each time).
std::optional<bool> total_reached(const Scene& scene, const ParticleSource& source, const SourceProgress& progress);

// A face of the region (a source on the faces of a plate or mesh), where the wall is now.
using Face = std::array<Vec3, 3>;
// The faces as the wall is now, asked for only when particles are due.
using FacesNow = std::function<std::vector<Face>()>;

// Whether a sphere at x of radius r would touch a wall (the walls there now).
using WallTest = std::function<bool(const Vec3& x, double r)>;

// The particles the source owes after `active` seconds of its activity (rate times time, to the
// nearest particle), placed without overlap among `existing` and clear of the walls; fewer when the
// region is too crowded for them (ParticleSource: they wait for the next batch). Updates `progress`.
// next_radius: source_radius(source, progress.inserted), which the caller keeps between calls.
std::vector<ParticleInit> due_particles(const Scene& scene, const ParticleSource& source, SourceProgress& progress,
                                        double next_radius, double active, const Particles& existing,
                                        const FacesNow& faces_now, const WallTest& touches_wall);

}  // namespace dem
