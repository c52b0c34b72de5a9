#include "clumps/rigid_rotation.hpp"

#include <cmath>

namespace dem {
namespace {

// The exact flow of H_k = pi_k^2 / (2 I_k) for time h: the body turns by theta = h pi_k / I_k about
// its axis k, and the body-frame momentum pi turns by -theta about the same axis (DLM 1997, eq. 14).
void turn_about_axis(int k, double h, const Vec3& moments, Eigen::Quaterniond& q, Vec3& pi) {
  const double theta = h * pi[k] / moments[k];
  const int a = (k + 1) % 3, b = (k + 2) % 3;
  const double c = std::cos(theta), s = std::sin(theta);
  const double pa = pi[a], pb = pi[b];
  pi[a] = c * pa + s * pb;
  pi[b] = -s * pa + c * pb;
  q = q * Eigen::Quaterniond(Eigen::AngleAxisd(theta, Vec3::Unit(k)));
}

}  // namespace

void rotate_free(RigidRotation& body, const Vec3& moments, double dt) {
  Vec3 pi = body.orientation.conjugate() * body.angular_momentum;  // in the body frame
  Eigen::Quaterniond q = body.orientation;
  turn_about_axis(0, 0.5 * dt, moments, q, pi);
  turn_about_axis(1, 0.5 * dt, moments, q, pi);
  turn_about_axis(2, dt, moments, q, pi);
  turn_about_axis(1, 0.5 * dt, moments, q, pi);
  turn_about_axis(0, 0.5 * dt, moments, q, pi);
  q.normalize();  // round-off only: each factor is a unit quaternion
  body.orientation = q;
  // the space-frame momentum is unchanged by the exact sub-flows; keeping the old value (rather
  // than q pi) stops round-off from accumulating in it
}

void rotate_with_torque(RigidRotation& body, const Vec3& moments, const Vec3& torque, double dt) {
  body.angular_momentum += 0.5 * dt * torque;
  rotate_free(body, moments, dt);
  body.angular_momentum += 0.5 * dt * torque;
}

Vec3 angular_velocity(const RigidRotation& body, const Vec3& moments) {
  const Vec3 pi = body.orientation.conjugate() * body.angular_momentum;
  return body.orientation * pi.cwiseQuotient(moments);
}

double rotational_energy(const RigidRotation& body, const Vec3& moments) {
  const Vec3 pi = body.orientation.conjugate() * body.angular_momentum;
  return 0.5 * pi.cwiseProduct(pi).cwiseQuotient(moments).sum();
}

}  // namespace dem
