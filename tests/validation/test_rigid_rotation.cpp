// Rotation of asymmetric rigid bodies (clumps) against Euler's equations: energy over a million
// steps, the trajectory against an accurate integration, the Dzhanibekov flip period, and the
// precession of a symmetric body at (I3 - I1) w3 / I1.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "clumps/rigid_rotation.hpp"

namespace dem {
namespace {

// Euler's equations with the orientation, integrated by classical RK4 with a step `substeps` times
// finer: the reference. State: body-frame angular velocity and the quaternion body -> space.
struct Reference {
  Vec3 omega;  // body frame
  Eigen::Quaterniond q;
};

Reference reference_rotation(Reference s, const Vec3& I, double t, int steps) {
  const double h = t / steps;
  auto deriv = [&](const Vec3& w, const Eigen::Vector4d& qv, Vec3& dw, Eigen::Vector4d& dq) {
    dw = Vec3((I[1] - I[2]) * w[1] * w[2] / I[0], (I[2] - I[0]) * w[2] * w[0] / I[1],
              (I[0] - I[1]) * w[0] * w[1] / I[2]);
    const Eigen::Quaterniond q(qv[0], qv[1], qv[2], qv[3]);
    const Eigen::Quaterniond d = q * Eigen::Quaterniond(0, w.x(), w.y(), w.z());  // dq/dt = q (0, w) / 2
    dq = 0.5 * Eigen::Vector4d(d.w(), d.x(), d.y(), d.z());
  };
  Vec3 w = s.omega;
  Eigen::Vector4d q(s.q.w(), s.q.x(), s.q.y(), s.q.z());
  for (int k = 0; k < steps; ++k) {
    Vec3 w1, w2, w3, w4;
    Eigen::Vector4d q1, q2, q3, q4;
    deriv(w, q, w1, q1);
    deriv(w + 0.5 * h * w1, q + 0.5 * h * q1, w2, q2);
    deriv(w + 0.5 * h * w2, q + 0.5 * h * q2, w3, q3);
    deriv(w + h * w3, q + h * q3, w4, q4);
    w += h / 6 * (w1 + 2 * w2 + 2 * w3 + w4);
    q += h / 6 * (q1 + 2 * q2 + 2 * q3 + q4);
    q.normalize();
  }
  return {w, Eigen::Quaterniond(q[0], q[1], q[2], q[3])};
}

RigidRotation body_with(const Vec3& omega_body, const Vec3& I, const Eigen::Quaterniond& q) {
  RigidRotation b;
  b.orientation = q;
  b.angular_momentum = q * omega_body.cwiseProduct(I);
  return b;
}

Vec3 body_omega(const RigidRotation& b, const Vec3& I) {
  return (b.orientation.conjugate() * b.angular_momentum).cwiseQuotient(I);
}

TEST(RigidRotation, AnAsymmetricBodyKeepsItsEnergyAndFollowsEulersEquations) {
  const Vec3 I(1.0, 2.0, 3.5);
  const Vec3 w0(0.7, -1.1, 0.4);
  const Eigen::Quaterniond q0(Eigen::AngleAxisd(0.8, Vec3(1, 2, 3).normalized()));
  const double dt = 1e-4;  // |w| dt = 1.4e-4 rad a step: a DEM step turns a stone far less
  const int steps = 1000000;
  RigidRotation b = body_with(w0, I, q0);
  const Vec3 L0 = b.angular_momentum;
  const double e0 = rotational_energy(b, I);
  double worst_energy = 0;
  for (int k = 0; k < steps; ++k) {
    rotate_free(b, I, dt);
    if (k % 1000 == 0) worst_energy = std::max(worst_energy, std::abs(rotational_energy(b, I) / e0 - 1));
  }
  worst_energy = std::max(worst_energy, std::abs(rotational_energy(b, I) / e0 - 1));
  // the momentum computed from the motion (I_space omega), not the stored vector
  const Eigen::Matrix3d R = b.orientation.toRotationMatrix();
  const Vec3 L = R * I.asDiagonal() * R.transpose() * angular_velocity(b, I);
  const Reference ref = reference_rotation({w0, q0}, I, dt * steps, 4 * steps);
  const double angle = ref.q.angularDistance(b.orientation);
  std::printf(
      "energy: largest relative change %.2e over %d steps; |dL|/|L| %.2e; orientation vs RK4 %.2e rad after %.0f s\n",
      worst_energy, steps, (L - L0).norm() / L0.norm(), angle, dt * steps);
  EXPECT_LT(worst_energy, 1e-6);
  EXPECT_LT((L - L0).norm() / L0.norm(), 1e-6);
  EXPECT_LT(angle, 1e-3);
  EXPECT_LT((body_omega(b, I) - ref.omega).norm() / w0.norm(), 1e-3);
}

// Times at which x(t) crosses zero upwards, found by linear interpolation between samples.
std::vector<double> upward_crossings(const std::vector<double>& x, double dt) {
  std::vector<double> t;
  for (std::size_t k = 1; k < x.size(); ++k)
    if (x[k - 1] < 0 && x[k] >= 0) t.push_back(dt * (k - 1 + x[k - 1] / (x[k - 1] - x[k])));
  return t;
}

double mean_period(const std::vector<double>& crossings) {
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

TEST(RigidRotation, SpunNearItsIntermediateAxisItFlipsWithTheEulerPeriod) {
  const Vec3 I(1.0, 2.0, 3.0);
  const Vec3 w0(0.05, 2.0, 0.05);  // the Dzhanibekov effect: spin about the middle axis, slightly off
  const double dt = 1e-4, t_end = 100;
  const int steps = static_cast<int>(t_end / dt);
  RigidRotation b = body_with(w0, I, Eigen::Quaterniond::Identity());
  std::vector<double> ours, euler;
  Reference r{w0, Eigen::Quaterniond::Identity()};
  for (int k = 0; k < steps; ++k) {
    ours.push_back(body_omega(b, I)[1]);
    euler.push_back(r.omega[1]);
    rotate_free(b, I, dt);
    r = reference_rotation(r, I, dt, 1);
  }
  const std::vector<double> a = upward_crossings(ours, dt), e = upward_crossings(euler, dt);
  ASSERT_GE(e.size(), 3u) << "the body should flip several times in " << t_end << " s";
  ASSERT_EQ(a.size(), e.size());
  std::printf("flip period: %.6f s (Euler's equations, RK4: %.6f s), over %zu full flips\n", mean_period(a),
              mean_period(e), a.size() - 1);
  EXPECT_NEAR(mean_period(a), mean_period(e), 1e-3 * mean_period(e));
}

TEST(RigidRotation, ASymmetricBodyPrecessesAtTheClosedFormRate) {
  const Vec3 I(1.0, 1.0, 2.5);
  const Vec3 w0(0.3, 0.0, 1.2);
  const double rate = (I[2] - I[0]) * w0[2] / I[0];  // body-frame precession of omega about axis 3
  const double dt = 1e-4;
  const int steps = static_cast<int>(10 * 2 * std::numbers::pi / rate / dt);
  RigidRotation b = body_with(w0, I, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3::UnitY())));
  std::vector<double> w1;
  for (int k = 0; k < steps; ++k) {
    w1.push_back(body_omega(b, I)[1]);
    rotate_free(b, I, dt);
  }
  const double period = mean_period(upward_crossings(w1, dt));
  std::printf("precession: %.7f rad/s, closed form %.7f rad/s\n", 2 * std::numbers::pi / period, rate);
  EXPECT_NEAR(2 * std::numbers::pi / period, rate, 1e-5 * rate);
}

TEST(RigidRotation, ATorqueChangesTheMomentumByItsImpulse) {
  const Vec3 I(1.0, 2.0, 3.0);
  RigidRotation b;
  const Vec3 torque(0.2, -0.1, 0.3);
  for (int k = 0; k < 1000; ++k) rotate_with_torque(b, I, torque, 1e-3);
  EXPECT_NEAR((b.angular_momentum - torque).norm(), 0, 1e-12);
}

}  // namespace
}  // namespace dem
