#include "clumps/rigid_rotation.hpp"

#include <cmath>

namespace dem {
namespace {

// sin and cos of a small angle by their Taylor series, exact to round-off for |x| <= 1/64 (the first
// term left out is below 1e-20 of the result); a step turns a body far less than that, and the
// series has no call and no branch the turns below would wait on. Larger angles go to libm.
void sin_cos(double x, double& s, double& c) {
  if (std::abs(x) > 1.0 / 64) {
    s = std::sin(x);
    c = std::cos(x);
    return;
  }
  const double x2 = x * x;  // Horner in x^2, with the inverse factorials as constants (no division)
  s = x * (1 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040))));
  c = 1 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320))));
}

// The exact flow of H_k = pi_k^2 / (2 I_k) for time h: the body turns by theta = h pi_k / I_k about
// its axis k, and the body-frame momentum pi turns by -theta about the same axis (DLM 1997, eq. 14).
// One sin and cos of theta/2 give both: the quaternion's half angle, and theta's by the double-angle
// formulas. q = (w, v) and pi stay in registers across the five turns (k is a constant).
template <int k>
inline void turn_about_axis(double h, const double inverse_moments[3], double& w, double v[3], double pi[3]) {
  constexpr int a = (k + 1) % 3, b = (k + 2) % 3;
  double sh = 0, ch = 0;
  sin_cos(0.5 * h * pi[k] * inverse_moments[k], sh, ch);
  const double c = 1 - 2 * sh * sh, s = 2 * sh * ch;
  const double pa = pi[a], pb = pi[b];
  pi[a] = c * pa + s * pb;
  pi[b] = -s * pa + c * pb;
  // q * (ch, sh e_k)
  const double w0 = w, vk = v[k], va = v[a], vb = v[b];
  w = ch * w0 - sh * vk;
  v[k] = ch * vk + sh * w0;
  v[a] = ch * va + sh * vb;
  v[b] = ch * vb - sh * va;
}

}  // namespace

void rotate_free(RigidRotation& body, const Vec3& moments, double dt) {
  const Vec3 body_pi = body.orientation.conjugate() * body.angular_momentum;  // in the body frame
  double pi[3] = {body_pi.x(), body_pi.y(), body_pi.z()};
  double w = body.orientation.w(), v[3] = {body.orientation.x(), body.orientation.y(), body.orientation.z()};
  const double inverse_moments[3] = {1 / moments.x(), 1 / moments.y(), 1 / moments.z()};  // off the turns' chain
  turn_about_axis<0>(0.5 * dt, inverse_moments, w, v, pi);
  turn_about_axis<1>(0.5 * dt, inverse_moments, w, v, pi);
  turn_about_axis<2>(dt, inverse_moments, w, v, pi);
  turn_about_axis<1>(0.5 * dt, inverse_moments, w, v, pi);
  turn_about_axis<0>(0.5 * dt, inverse_moments, w, v, pi);
  body.orientation = Eigen::Quaterniond(w, v[0], v[1], v[2]).normalized();  // round-off only: unit factors
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

Vec3 angular_velocity(const Eigen::Matrix3d& to_space, const Vec3& angular_momentum, const Vec3& inverse_moments) {
  return to_space * (to_space.transpose() * angular_momentum).cwiseProduct(inverse_moments);
}

double rotational_energy(const RigidRotation& body, const Vec3& moments) {
  const Vec3 pi = body.orientation.conjugate() * body.angular_momentum;
  return 0.5 * pi.cwiseProduct(pi).cwiseQuotient(moments).sum();
}

}  // namespace dem
