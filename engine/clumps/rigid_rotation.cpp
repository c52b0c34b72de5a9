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
// formulas. q = (w, v) and pi stay in registers across the five turns (k is a constant). N bodies
// at once, each in its own lane [j]: a body's five turns are one chain of dependent operations, and
// the lanes give the processor N chains to overlap; each lane does exactly one body's arithmetic.
template <int k, int N>
inline void turn_about_axis(double h, const double inverse_moments[3][N], double w[N], double v[3][N],
                            double pi[3][N]) {
  constexpr int a = (k + 1) % 3, b = (k + 2) % 3;
  double sh[N], ch[N];
  for (int j = 0; j < N; ++j) sin_cos(0.5 * h * pi[k][j] * inverse_moments[k][j], sh[j], ch[j]);
  for (int j = 0; j < N; ++j) {
    const double c = 1 - 2 * sh[j] * sh[j], s = 2 * sh[j] * ch[j];
    const double pa = pi[a][j], pb = pi[b][j];
    pi[a][j] = c * pa + s * pb;
    pi[b][j] = -s * pa + c * pb;
    // q * (ch, sh e_k)
    const double w0 = w[j], vk = v[k][j], va = v[a][j], vb = v[b][j];
    w[j] = ch[j] * w0 - sh[j] * vk;
    v[k][j] = ch[j] * vk + sh[j] * w0;
    v[a][j] = ch[j] * va + sh[j] * vb;
    v[b][j] = ch[j] * vb - sh[j] * va;
  }
}

template <int N>
void rotate_free_lanes(RigidRotation* const body[], const Vec3* const moments[], double dt) {
  double pi[3][N], w[N], v[3][N], inverse_moments[3][N];
  for (int j = 0; j < N; ++j) {
    const Vec3 body_pi = body[j]->orientation.conjugate() * body[j]->angular_momentum;  // in the body frame
    const Eigen::Quaterniond& q = body[j]->orientation;
    w[j] = q.w();
    for (int d = 0; d < 3; ++d) {
      pi[d][j] = body_pi[d];
      v[d][j] = q.coeffs()[d];                       // Eigen keeps (x, y, z, w)
      inverse_moments[d][j] = 1 / (*moments[j])[d];  // off the turns' chain
    }
  }
  turn_about_axis<0, N>(0.5 * dt, inverse_moments, w, v, pi);
  turn_about_axis<1, N>(0.5 * dt, inverse_moments, w, v, pi);
  turn_about_axis<2, N>(dt, inverse_moments, w, v, pi);
  turn_about_axis<1, N>(0.5 * dt, inverse_moments, w, v, pi);
  turn_about_axis<0, N>(0.5 * dt, inverse_moments, w, v, pi);
  // round-off only: unit factors. The space-frame momentum is unchanged by the exact sub-flows;
  // keeping the old value (rather than q pi) stops round-off from accumulating in it.
  for (int j = 0; j < N; ++j) body[j]->orientation = Eigen::Quaterniond(w[j], v[0][j], v[1][j], v[2][j]).normalized();
}

}  // namespace

void rotate_free(RigidRotation& body, const Vec3& moments, double dt) {
  RigidRotation* const bodies[1] = {&body};
  const Vec3* const all_moments[1] = {&moments};
  rotate_free_lanes<1>(bodies, all_moments, dt);
}

void rotate_free(RigidRotation* const bodies[], const Vec3* const moments[], int count, double dt) {
  int j = 0;
  for (; j + kRotationLanes <= count; j += kRotationLanes)
    rotate_free_lanes<kRotationLanes>(bodies + j, moments + j, dt);
  for (; j < count; ++j) rotate_free_lanes<1>(bodies + j, moments + j, dt);
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
