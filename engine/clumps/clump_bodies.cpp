#include "clumps/clump_bodies.hpp"

#include <algorithm>

#include "core/parallel.hpp"

namespace dem {
namespace {

// Below this many bodies (or members) a loop runs on one thread: the threads' start costs more.
constexpr int kParallelMinBodies = 256;

// Each body's angular velocity, found once for all its members.
std::vector<Vec3> spins(const ClumpBodies& bodies) {
  const int nb = static_cast<int>(bodies.size());
  std::vector<Vec3> w(bodies.size());
  for_ranges(nb, kParallelMinBodies, [&](int begin, int end) {
    for (int b = begin; b < end; ++b) w[b] = angular_velocity(bodies.rotation[b], bodies.moments[b]);
  });
  return w;
}

// Velocity and spin of every member from its body; with `place`, its position first.
void move_members(const ClumpBodies& bodies, Particles& p, bool place) {
  const std::vector<Vec3> w = spins(bodies);
  const int n = static_cast<int>(p.size());
  for_ranges(n, kParallelMinBodies, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const int b = p.body[i];
      if (b < 0) continue;
      if (place) p.x[i] = bodies.x[b] + bodies.rotation[b].orientation * p.body_offset[i];
      p.v[i] = bodies.v[b] + w[b].cross(p.x[i] - bodies.x[b]);
      p.w[i] = w[b];
    }
  });
}

}  // namespace

ClumpBodies make_bodies(const Scene& scene) {
  ClumpBodies b;
  for (const ClumpInit& c : scene.clumps) {
    b.x.push_back(c.position);
    b.v.push_back(c.velocity);
    RigidRotation r;
    r.orientation = c.orientation;
    // L = R I R^T w for the given angular velocity
    r.angular_momentum = c.orientation * (c.moments.cwiseProduct(c.orientation.conjugate() * c.angular_velocity));
    b.rotation.push_back(r);
    b.mass.push_back(c.mass);
    b.moments.push_back(c.moments);
    b.force.push_back(Vec3::Zero());
    b.torque.push_back(Vec3::Zero());
  }
  return b;
}

void mark_members(const Scene& scene, const ClumpBodies& bodies, Particles& p) {
  if (bodies.empty()) return;
  p.body.assign(p.size(), -1);
  p.body_offset.assign(p.size(), Vec3::Zero());
  for (std::size_t c = 0; c < scene.clumps.size(); ++c) {
    const ClumpInit& clump = scene.clumps[c];
    for (int i = clump.first; i < clump.first + clump.count; ++i) {
      p.body[i] = static_cast<int>(c);
      p.body_offset[i] = clump.orientation.conjugate() * (scene.particles[i].position - clump.position);
      p.mass[i] = clump.mass;
      p.inv_mass[i] = 1 / clump.mass;
    }
  }
  move_members(bodies, p, true);
}

double drift_bodies(ClumpBodies& bodies, Particles& p, const std::vector<Vec3>& x_at_build, double dt,
                    std::vector<Vec3>& half_kick, std::vector<Vec3>& spin_kick) {
  const int nb = static_cast<int>(bodies.size());
  std::vector<Vec3> kick(bodies.size()), spin(bodies.size());
  for_ranges(nb, kParallelMinBodies, [&](int begin, int end) {
    for (int b = begin; b < end; ++b) {
      kick[b] = (0.5 * dt / bodies.mass[b]) * bodies.force[b];
      bodies.v[b] += kick[b];
      bodies.x[b] += dt * bodies.v[b];
      bodies.rotation[b].angular_momentum += 0.5 * dt * bodies.torque[b];
      rotate_free(bodies.rotation[b], bodies.moments[b], dt);
      // the spin the half kick's angular momentum adds, at the orientation the contacts see
      spin[b] = angular_velocity(RigidRotation{bodies.rotation[b].orientation, 0.5 * dt * bodies.torque[b]},
                                 bodies.moments[b]);
    }
  });
  move_members(bodies, p, true);
  const int n = static_cast<int>(p.size());
  for_ranges(n, kParallelMinBodies, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const int b = p.body[i];
      if (b < 0) continue;
      half_kick[i] = kick[b] + spin[b].cross(p.x[i] - bodies.x[b]);
      spin_kick[i] = spin[b];
    }
  });
  return reduce_ranges(
      n, kParallelMinBodies, 0.0,
      [&](int begin, int end) {
        double moved2 = 0;
        for (int i = begin; i < end; ++i)
          if (p.body[i] >= 0) moved2 = std::max(moved2, (p.x[i] - x_at_build[i]).squaredNorm());
        return moved2;
      },
      [](double a, double b) { return std::max(a, b); });
}

void kick_bodies(ClumpBodies& bodies, Particles& p, const Vec3& gravity, double dt, double local_damping) {
  // Each body's members in particle order (a counting sort: the order changes with every re-sort),
  // so that each body sums its members in that order: the same sums on any number of threads.
  const int n = static_cast<int>(p.size()), nb = static_cast<int>(bodies.size());
  std::vector<int> start(bodies.size() + 1, 0), members;
  for (int i = 0; i < n; ++i)
    if (p.body[i] >= 0) ++start[p.body[i] + 1];
  for (int b = 0; b < nb; ++b) start[b + 1] += start[b];
  members.resize(start[nb]);
  {
    std::vector<int> next(start.begin(), start.end() - 1);
    for (int i = 0; i < n; ++i)
      if (p.body[i] >= 0) members[next[p.body[i]]++] = i;
  }
  for_ranges(nb, kParallelMinBodies, [&](int begin, int end) {
    for (int b = begin; b < end; ++b) {
      Vec3 force = bodies.mass[b] * gravity, torque = Vec3::Zero();
      for (int k = start[b]; k < start[b + 1]; ++k) {
        const int i = members[k];
        const Vec3 contact = p.f[i] - p.mass[i] * gravity;
        force += contact;
        torque += (p.x[i] - bodies.x[b]).cross(contact) + p.t[i];
      }
      if (local_damping > 0 && dt != 0) {
        const Vec3 w = angular_velocity(bodies.rotation[b], bodies.moments[b]);
        for (int d = 0; d < 3; ++d) {
          if (bodies.v[b][d] != 0) force[d] -= local_damping * std::abs(force[d]) * (bodies.v[b][d] > 0 ? 1 : -1);
          if (w[d] != 0) torque[d] -= local_damping * std::abs(torque[d]) * (w[d] > 0 ? 1 : -1);
        }
      }
      bodies.force[b] = force;
      bodies.torque[b] = torque;
      if (dt == 0) continue;
      bodies.v[b] += (0.5 * dt / bodies.mass[b]) * force;
      bodies.rotation[b].angular_momentum += 0.5 * dt * torque;
    }
  });
  if (dt == 0) return;
  move_members(bodies, p, false);  // the velocities and spins the kick changed
}

double bodies_kinetic_energy(const ClumpBodies& bodies) {
  double e = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    e += 0.5 * bodies.mass[b] * bodies.v[b].squaredNorm() + rotational_energy(bodies.rotation[b], bodies.moments[b]);
  return e;
}

double bodies_rotational_energy(const ClumpBodies& bodies) {
  double e = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) e += rotational_energy(bodies.rotation[b], bodies.moments[b]);
  return e;
}

}  // namespace dem
