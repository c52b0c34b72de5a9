#include "clumps/clump_bodies.hpp"

#include <algorithm>

#include "core/local_damping.hpp"
#include "core/parallel.hpp"

namespace dem {
namespace {

// Below this many bodies a loop runs on one thread: the threads' start costs more.
constexpr int kParallelMinBodies = 256;

// Velocity and spin of body b's members from its body (orientation R, spin w); with `place`, their
// positions first.
void move_members_of(const ClumpBodies& bodies, int b, const Eigen::Matrix3d& R, const Vec3& w, Particles& p,
                     bool place) {
  for (int k = bodies.member_start[b]; k < bodies.member_start[b + 1]; ++k) {
    const int i = bodies.members[k];
    if (place) p.x[i] = bodies.x[b] + R * p.body_offset[i];
    p.v[i] = bodies.v[b] + w.cross(p.x[i] - bodies.x[b]);
    p.w[i] = w;
  }
}

// Body b's spin, from its angular momentum, at orientation R.
Vec3 spin_of(const ClumpBodies& bodies, int b, const Eigen::Matrix3d& R) {
  return angular_velocity(R, bodies.rotation[b].angular_momentum, bodies.moments[b].cwiseInverse());
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

void mark_members(const Scene& scene, ClumpBodies& bodies, Particles& p) {
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
  index_members(bodies, p);
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b) {
    const Eigen::Matrix3d R = bodies.rotation[b].orientation.toRotationMatrix();
    move_members_of(bodies, b, R, spin_of(bodies, b, R), p, true);
  }
}

void index_members(ClumpBodies& bodies, const Particles& p) {
  const int n = static_cast<int>(p.body.size()), nb = static_cast<int>(bodies.size());  // no bodies: no p.body
  std::vector<int>& start = bodies.member_start;
  start.assign(bodies.size() + 1, 0);
  for (int i = 0; i < n; ++i)
    if (p.body[i] >= 0) ++start[p.body[i] + 1];
  for (int b = 0; b < nb; ++b) start[b + 1] += start[b];
  bodies.members.resize(start[nb]);
  std::vector<int> next(start.begin(), start.end() - 1);
  for (int i = 0; i < n; ++i)
    if (p.body[i] >= 0) bodies.members[next[p.body[i]]++] = i;
}

double drift_bodies(ClumpBodies& bodies, Particles& p, const std::vector<Vec3>& x_at_build, double dt,
                    std::vector<Vec3>& half_kick, std::vector<Vec3>& spin_kick) {
  const int nb = static_cast<int>(bodies.size());
  std::vector<ClumpBodies::Motion>& motion = bodies.motion;
  motion.resize(bodies.size());
  // The bodies: their drift and free rotation, kRotationLanes at a time (rigid_rotation.hpp: the same
  // bits, the chains overlapped), then what their members take from them.
  for_ranges(nb, kParallelMinBodies, [&](int begin, int end) {
    RigidRotation* group[kRotationLanes];
    const Vec3* group_moments[kRotationLanes];
    for (int first = begin; first < end; first += kRotationLanes) {
      const int count = std::min(kRotationLanes, end - first);
      for (int j = 0; j < count; ++j) {
        const int b = first + j;
        bodies.v[b] += (0.5 * dt / bodies.mass[b]) * bodies.force[b];
        bodies.x[b] += dt * bodies.v[b];
        bodies.rotation[b].angular_momentum += 0.5 * dt * bodies.torque[b];
        group[j] = &bodies.rotation[b];
        group_moments[j] = &bodies.moments[b];
      }
      rotate_free(group, group_moments, count, dt);
      for (int b = first; b < first + count; ++b) {
        ClumpBodies::Motion& m = motion[b];
        m.to_space = bodies.rotation[b].orientation.toRotationMatrix();
        const Vec3 inverse_moments = bodies.moments[b].cwiseInverse();
        m.centre = bodies.x[b];
        m.velocity = bodies.v[b];
        m.spin = angular_velocity(m.to_space, bodies.rotation[b].angular_momentum, inverse_moments);
        m.kick = (0.5 * dt / bodies.mass[b]) * bodies.force[b];
        // the spin the half kick's angular momentum adds, at the orientation the contacts see
        m.spin_kick = angular_velocity(m.to_space, 0.5 * dt * bodies.torque[b], inverse_moments);
      }
    }
  });
  // The members placed and moved, with their kicks, in particle order, the particles split among the
  // threads as every other particle loop splits them (kParticleBlock): a thread writes its own particles.
  // Written body by body instead, two threads wrote neighbouring members (members lie anywhere in the
  // particles' order) on one cache line: the clumps' phase of bench/run ballast's load took 4.98 s on
  // two threads and 4.89 s on one (3.77 s on two now).
  // Returns the members' largest squared move since the list was built (exact in any order). Raw
  // pointers: through the std::vectors the compiler reloaded their data pointers after every store.
  const int n = static_cast<int>(p.size());
  const int* __restrict body = p.body.data();
  const Vec3* __restrict body_offset = p.body_offset.data();
  const Vec3* __restrict x_built = x_at_build.data();
  Vec3* __restrict x = p.x.data();
  Vec3* __restrict v = p.v.data();
  Vec3* __restrict w = p.w.data();
  Vec3* __restrict member_kick = half_kick.data();
  Vec3* __restrict member_spin_kick = spin_kick.data();
  const ClumpBodies::Motion* __restrict of = motion.data();
  return reduce_ranges(
      n, kParallelMinParticles, 0.0,
      [&](int begin, int end) {
        double moved2 = 0;
        for (int i = begin; i < end; ++i) {
          if (body[i] < 0) continue;
          const ClumpBodies::Motion& m = of[body[i]];
          const Vec3 xi = m.centre + m.to_space * body_offset[i];
          const Vec3 arm = xi - m.centre;
          x[i] = xi;
          v[i] = m.velocity + m.spin.cross(arm);
          w[i] = m.spin;
          member_kick[i] = m.kick + m.spin_kick.cross(arm);
          member_spin_kick[i] = m.spin_kick;
          moved2 = std::max(moved2, (xi - x_built[i]).squaredNorm());
        }
        return moved2;
      },
      [](double a, double b) { return std::max(a, b); }, kParticleBlock);
}

void kick_bodies(ClumpBodies& bodies, Particles& p, const Vec3& gravity, double dt, double local_damping) {
  const int nb = static_cast<int>(bodies.size());
  std::vector<ClumpBodies::Motion>& motion = bodies.motion;
  motion.resize(bodies.size());
  // Each body sums its members in particle order (the same sums on any number of threads), then takes
  // its second half kick.
  const int* __restrict start = bodies.member_start.data();
  const int* __restrict members = bodies.members.data();
  const Vec3* __restrict f = p.f.data();
  const Vec3* __restrict t = p.t.data();
  const double* __restrict mass = p.mass.data();
  const Vec3* __restrict x = p.x.data();
  for_ranges(nb, kParallelMinBodies, [&](int begin, int end) {
    for (int b = begin; b < end; ++b) {
      const Vec3 centre = bodies.x[b];
      Vec3 force = bodies.mass[b] * gravity, torque = Vec3::Zero();
      for (int k = start[b]; k < start[b + 1]; ++k) {
        const int i = members[k];
        const Vec3 contact = f[i] - mass[i] * gravity;
        force += contact;
        torque += (x[i] - centre).cross(contact) + t[i];
      }
      // built once for both the damping and the members
      const Eigen::Matrix3d R = bodies.rotation[b].orientation.toRotationMatrix();
      // damped at the start's and a stage's first evaluation (dt = 0) too, as a sphere's force is: the
      // first half kick takes that force (undamped, a clump thrown down fell alpha g dt / 2 too fast)
      if (local_damping > 0) {
        const Vec3 spin = spin_of(bodies, b, R);
        damp_locally(force, bodies.v[b], local_damping);
        damp_locally(torque, spin, local_damping);
      }
      bodies.force[b] = force;
      bodies.torque[b] = torque;
      if (dt == 0) continue;
      bodies.v[b] += (0.5 * dt / bodies.mass[b]) * force;
      bodies.rotation[b].angular_momentum += 0.5 * dt * torque;
      ClumpBodies::Motion& m = motion[b];
      m.centre = centre;
      m.velocity = bodies.v[b];
      m.spin = spin_of(bodies, b, R);
    }
  });
  if (dt == 0) return;
  // the velocities and spins the kick changed (as move_members_of), in particle order as in drift_bodies
  const int n = static_cast<int>(p.size());
  const int* __restrict body = p.body.data();
  Vec3* __restrict v = p.v.data();
  Vec3* __restrict w = p.w.data();
  const ClumpBodies::Motion* __restrict of = motion.data();
  for_ranges(
      n, kParallelMinParticles,
      [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
          if (body[i] < 0) continue;
          const ClumpBodies::Motion& m = of[body[i]];
          v[i] = m.velocity + m.spin.cross(x[i] - m.centre);
          w[i] = m.spin;
        }
      },
      kParticleBlock);
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

double bodies_translational_energy(const ClumpBodies& bodies) {
  double e = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) e += 0.5 * bodies.mass[b] * bodies.v[b].squaredNorm();
  return e;
}

}  // namespace dem
