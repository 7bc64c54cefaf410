// Lab 3 graded tests: inertia, forces and torques, the Newton-Euler derivative under Lab 1's
// integrators (reference), torque-free motion, the Dzhanibekov flip, and orientation updates.
#include <cmath>

#include "physlab/rigid.hpp"
#include "physlab/special_functions.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

Mat3 diag(double a, double b, double c) { return Vec3(a, b, c).asDiagonal(); }

// Body-frame angular velocity of a state, computed here (not with the student's code).
Vec3 omegaBody(const RigidBodySystem& sys, const VecX& X) {
  const Mat3 R = orientationOf(X).normalized().toRotationMatrix();
  return sys.body().inertia_body_inv * (R.transpose() * X.segment<3>(10));
}

// A torque-free body with I = diag(1, 2, 3) spinning with body-frame omega0 from the identity.
VecX spinning(const RigidBodySystem& sys, const Vec3& omega0) {
  return sys.makeState(Vec3::Zero(), Quat::Identity(), Vec3::Zero(), sys.body().inertia_body * omega0);
}

// First flip time of a torque-free spin about the intermediate axis, in closed form. With
// I1 < I2 < I3, 2E = w.Iw, L^2 = |Iw|^2 and L^2 < 2E I2 (the polhode circles axis 1), Euler's
// equations are solved by w2 = A sn(tau, k), w3 = B cn(tau, k), w1 = C dn(tau, k) with
//   tau = lambda t, lambda^2 = (I2 - I1)(2E I3 - L^2) / (I1 I2 I3),
//   k^2 = (I3 - I2)(L^2 - 2E I1) / ((I2 - I1)(2E I3 - L^2)).
// Starting with w3 = 0 puts tau at K(k) (cn = 0, sn = 1); the flip, defined as the first sign
// change of w2, is at tau = 2K: t_flip = K(k) / lambda. For w0 = (eps, w2, 0) lambda tends to
// w2 sqrt((I2 - I1)(I3 - I2) / (I1 I3)) and K(k) to ln(4 / k'), k' ~ eps / w2, which gives
// 14.37 s for I = diag(1, 2, 3), w0 = (1e-3, 1, 0).
double analyticFlipTime(const Vec3& I, const Vec3& w) {
  const double twoE = w.dot(I.cwiseProduct(w)), L2 = I.cwiseProduct(w).squaredNorm();
  const double lambda = std::sqrt((I[1] - I[0]) * (twoE * I[2] - L2) / (I[0] * I[1] * I[2]));
  const double k = std::sqrt((I[2] - I[1]) * (L2 - twoE * I[0]) / ((I[1] - I[0]) * (twoE * I[2] - L2)));
  return completeEllipticK(k) / lambda;
}

}  // namespace

TEST_CASE("inertia: a solid box matches its closed-form tensor", "[lab03][pts=1][sec=1]") {
  const double M = uniform(0.5, 5.0), a = uniform(0.1, 2.0), b = uniform(0.1, 2.0), c = uniform(0.1, 2.0);
  // The closed form evaluated here in another order: round-off only.
  CHECK(boxInertia(M, Vec3(a, b, c)).isApprox(diag(b * b + c * c, a * a + c * c, a * a + b * b) * M / 12, 1e-14));
}

TEST_CASE("inertia: a solid sphere matches 2/5 M r^2 on every axis", "[lab03][pts=1][sec=1]") {
  const double M = uniform(0.5, 5.0), r = uniform(0.1, 2.0);
  // The closed form evaluated here in another order: round-off only.
  CHECK(sphereInertia(M, r).isApprox(Mat3::Identity() * 2.0 / 5.0 * M * r * r, 1e-14));
}

TEST_CASE("inertia: a solid cylinder matches its closed-form tensor", "[lab03][pts=1][sec=1]") {
  const double M = uniform(0.5, 5.0), r = uniform(0.1, 2.0), height = uniform(0.1, 2.0);
  const double across = M * (3 * r * r + height * height) / 12;
  // The closed form evaluated here in another order: round-off only.
  CHECK(cylinderInertia(M, r, height).isApprox(diag(across, across, M * r * r / 2), 1e-14));
}

TEST_CASE("inertia: point masses sampling a box converge to the box's tensor", "[lab03][pts=2][sec=1]") {
  const double M = uniform(0.5, 5.0);
  const Vec3 size(uniform(0.5, 2.0), uniform(0.5, 2.0), uniform(0.5, 2.0));
  const Vec3 offset = randomVec3(3.0);  // the centre of mass must be moved to the origin
  const Mat3 box = diag(size.y() * size.y() + size.z() * size.z(), size.x() * size.x() + size.z() * size.z(),
                        size.x() * size.x() + size.y() * size.y()) * M / 12;
  for (int n : {5, 10, 20}) {
    Mat3X r(3, n * n * n);
    Index k = 0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        for (int l = 0; l < n; ++l) {
          // Cell midpoints of an n^3 grid over the box
          r.col(k++) = offset + Vec3((i + 0.5) / n - 0.5, (j + 0.5) / n - 0.5, (l + 0.5) / n - 0.5).cwiseProduct(size);
        }
      }
    }
    const Mat3 I = pointMassInertia(VecX::Constant(n * n * n, M / (n * n * n)), r);
    // Midpoint sampling gives exactly sum x^2 / n = a^2 / 12 (1 - 1/n^2) per axis: the tensor
    // equals the box's times (1 - 1/n^2), so the error is exactly 1/n^2 relative.
    CHECK(I.isApprox(box * (1.0 - 1.0 / (n * n)), 1e-12));
  }
}

TEST_CASE("forces: the wrench sums the forces and the moments (p - x) x F", "[lab03][pts=1][sec=3]") {
  const Vec3 x = randomVec3(2.0);
  std::vector<AppliedForce> forces;
  Vec3 F = Vec3::Zero(), tau = Vec3::Zero();
  for (int i = 0; i < 4; ++i) {
    forces.push_back({randomVec3(2.0), randomVec3(5.0)});
    F += forces.back().force;
    tau += (forces.back().point - x).cross(forces.back().force);
  }
  const Wrench w = wrenchAbout(x, forces);
  CHECK(w.force.isApprox(F, 1e-14));    // the same sums in the same order: round-off only
  CHECK(w.torque.isApprox(tau, 1e-13));  // one cross product more per term: round-off only
}

TEST_CASE("forces: a body point moves with v + omega x (p - x)", "[lab03][pts=1][sec=3]") {
  const Vec3 v = randomVec3(1.0), w = randomVec3(2.0), x = randomVec3(1.0), p = randomVec3(1.0);
  const Vec3 r = p - x;
  const Vec3 expected(v.x() + w.y() * r.z() - w.z() * r.y(), v.y() + w.z() * r.x() - w.x() * r.z(),
                      v.z() + w.x() * r.y() - w.y() * r.x());
  CHECK(pointVelocity(v, w, x, p).isApprox(expected, 1e-14));
}

TEST_CASE("rigid: angular velocity is R I_body^-1 R^T L", "[lab03][pts=1][sec=2]") {
  // A full body tensor (principal axes turned by B), so that using only its diagonal fails.
  const Mat3 B = randomRotation();
  const RigidBody body(uniform(1.0, 3.0), B * diag(uniform(0.5, 1.0), uniform(1.5, 2.0), uniform(2.5, 3.0)) * B.transpose());
  const Mat3 R = randomRotation();
  const Vec3 L = randomVec3(2.0);
  // omega must satisfy I_world omega = L, with I_world = R I_body R^T.
  const Vec3 omega = angularVelocity(body, Quat(R), L);
  // I_body's condition number is at most 6: the products and the inverse lose ~1e-15.
  CHECK((R * body.inertia_body * R.transpose() * omega).isApprox(L, 1e-12));
}

TEST_CASE("rigid: the position rate is xdot = P / M and qdot = 1/2 omega q", "[lab03][pts=1][sec=4]") {
  const RigidBodySystem sys(RigidBody(uniform(0.5, 3.0), diag(uniform(0.5, 1.0), uniform(1.5, 2.0), uniform(2.5, 3.0))));
  const VecX X = sys.makeState(randomVec3(1.0), Quat(randomRotation()), randomVec3(2.0), randomVec3(2.0));
  VecX qdot(7);
  sys.positionRate(X, qdot);
  // The oracle: omega = R I_body^-1 R^T L, and the quaternion product (0, omega) q written out.
  const Quat q = orientationOf(X);
  const Mat3 R = q.toRotationMatrix();
  const Vec3 w = R * sys.body().inertia_body_inv * R.transpose() * X.segment<3>(10);
  const Vec3 u = q.vec();
  const double rate_w = -0.5 * w.dot(u);
  const Vec3 rate_u = 0.5 * (q.w() * w + w.cross(u));
  VecX expected(7);
  expected << X.segment<3>(7) / sys.body().mass, rate_w, rate_u;
  CHECK(qdot.isApprox(expected, 1e-13));  // the same products in another order: round-off only
  // A unit quaternion's rate is tangent to the unit sphere: q . qdot = 0.
  CHECK(std::abs(X.segment<4>(3).dot(qdot.tail<4>())) < 1e-14 * qdot.norm());
}

TEST_CASE("rigid: the velocity rate is the total force and the torque about the centre", "[lab03][pts=1][sec=4]") {
  std::vector<BodyForce> forces;
  for (int i = 0; i < 3; ++i) forces.push_back({randomVec3(1.0), randomVec3(5.0)});
  const Vec3 g = randomVec3(10.0);
  const RigidBodySystem sys(RigidBody(uniform(0.5, 3.0), diag(1, 2, 3)), forces, g);
  const VecX X = sys.makeState(randomVec3(1.0), Quat(randomRotation()), randomVec3(2.0), randomVec3(2.0));
  VecX pdot(6);
  sys.velocityRate(X, pdot);
  // The oracle: each force acts at x + R r_body, so its moment about x is (R r_body) x F;
  // gravity acts at x and adds M g to the force only.
  const Mat3 R = orientationOf(X).toRotationMatrix();
  Vec3 F = sys.body().mass * g, tau = Vec3::Zero();
  for (const BodyForce& f : forces) {
    F += f.force_world;
    tau += (R * f.point_body).cross(f.force_world);
  }
  // Sums of a few O(10) terms; the moment arms pass through x + R r - x: ~1e-15 relative.
  CHECK(pdot.head<3>().isApprox(F, 1e-13));
  CHECK(pdot.tail<3>().isApprox(tau, 1e-12));
}

TEST_CASE("rigid: a force through the centre of mass produces no rotation", "[lab03][pts=1][sec=4]") {
  const RigidBodySystem sys(RigidBody(2.0, diag(1, 2, 3)), {{Vec3::Zero(), randomVec3(5.0)}});
  VecX X = sys.makeState(randomVec3(1.0), Quat(randomRotation()), randomVec3(1.0), Vec3::Zero());
  const Quat q0 = orientationOf(X);
  run(Method::RK4, sys, X, 0.01, 200);
  // Zero torque keeps L exactly zero, so omega and qdot are exactly zero: q is unchanged.
  CHECK(X.segment<3>(10).norm() == 0.0);
  CHECK(orientationOf(X).isApprox(q0, 1e-15));
}

TEST_CASE("rigid: a pure couple produces no translation", "[lab03][pts=1][sec=4]") {
  const Vec3 r = randomVec3(1.0), F = randomVec3(5.0);
  const RigidBodySystem sys(RigidBody(2.0, diag(1, 2, 3)), {{r, F}, {-r, -F}});
  const Vec3 x0 = randomVec3(1.0);
  const Quat q0(randomRotation());
  VecX X = sys.makeState(x0, q0, Vec3::Zero(), Vec3::Zero());
  const double h0 = 1e-3;
  run(Method::RK4, sys, X, h0, 1);
  // Yet the couple spins the body: L = h0 tau with tau = 2 (R r) x F. The force points turn by
  // about |tau| h0^2 / 6 <= 5e-6 rad within the step (|tau| <= 30, I >= 1), so the relative
  // error stays below 1e-5; 1e-3 leaves room for every seed.
  const Vec3 tau = 2.0 * (q0 * r).cross(F);
  CHECK((X.segment<3>(10) - h0 * tau).norm() < 1e-3 * h0 * r.norm() * F.norm());
  run(Method::RK4, sys, X, 0.01, 200);
  // The forces cancel exactly, so P stays zero and x does not move.
  CHECK(X.segment<3>(7).norm() < 1e-14 * F.norm());
  CHECK((X.head<3>() - x0).norm() < 1e-14);
}

TEST_CASE("rigid: a torque-free body conserves world angular momentum to round-off", "[lab03][pts=2][sec=4]") {
  const RigidBodySystem sys(RigidBody(1.0, diag(uniform(0.5, 1.0), uniform(1.5, 2.0), uniform(2.5, 3.0))));
  VecX X = sys.makeState(Vec3::Zero(), Quat(randomRotation()), randomVec3(1.0), randomVec3(2.0));
  const Vec3 L0 = X.segment<3>(10);
  run(Method::RK4, sys, X, 0.01, 1000);
  // Ldot = tau = 0 exactly in the momentum form: L never changes.
  CHECK((X.segment<3>(10) - L0).norm() <= 1e-14 * L0.norm());
  // and the body does turn, so the test is not vacuous
  CHECK(omegaBody(sys, X).norm() > 0.1);
}

TEST_CASE("rigid: RK4's energy drift is far below explicit Euler's on a torque-free body", "[lab03][pts=2][sec=4]") {
  const RigidBodySystem sys(RigidBody(1.0, diag(1, 2, 3)));
  const VecX X0 = spinning(sys, Vec3(uniform(0.5, 1.0), uniform(0.1, 0.3), uniform(0.5, 1.0)));
  const double E0 = sys.kineticEnergy(X0);
  double drift[2];
  int k = 0;
  for (Method m : {Method::RK4, Method::ExplicitEuler}) {
    VecX X = X0;
    run(m, sys, X, 0.01, 2000);
    drift[k++] = std::abs(sys.kineticEnergy(X) - E0) / E0;
  }
  INFO("relative energy drift: RK4 " << drift[0] << ", explicit Euler " << drift[1]);
  // RK4's error is O(h^4) ~ 1e-8 here and explicit Euler's O(h) ~ 1e-2: 1000x is a safe ranking.
  CHECK(drift[0] * 1000.0 < drift[1]);
}

TEST_CASE("rigid: an axisymmetric top precesses at (I3 - I1) / I1 omega3 in the body frame", "[lab03][pts=2][sec=7]") {
  const double I1 = uniform(1.0, 2.0), I3 = uniform(2.5, 4.0);
  const Vec3 w0(uniform(0.1, 0.5), 0.0, uniform(1.0, 3.0));
  const Mat3 I = diag(I1, I1, I3);
  // Euler's equations for a symmetric top: w3 constant, (w1, w2) turns at Omega.
  const double Omega = (I3 - I1) / I1 * w0.z();
  Vec3 w = w0;
  const double h = 1e-3, T = 2.0;
  for (int n = 0; n < 2000; ++n) {  // RK4 on the student's bodyFrameOmegaRate
    const Vec3 k1 = bodyFrameOmegaRate(I, w, Vec3::Zero());
    const Vec3 k2 = bodyFrameOmegaRate(I, w + 0.5 * h * k1, Vec3::Zero());
    const Vec3 k3 = bodyFrameOmegaRate(I, w + 0.5 * h * k2, Vec3::Zero());
    const Vec3 k4 = bodyFrameOmegaRate(I, w + h * k3, Vec3::Zero());
    w += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  const double angle = std::atan2(w.y(), w.x());
  const double expected = std::remainder(Omega * T, 2.0 * M_PI);
  // RK4 at h = 1e-3 is accurate to ~1e-12 rad here; a wrong sign or factor misses by O(1).
  CHECK(std::remainder(angle - expected, 2.0 * M_PI) == Approx(0.0).margin(1e-8));
  // omega3's rate (I1 - I2) omega1 omega2 / I3 vanishes up to round-off when I1 = I2.
  CHECK(w.z() == Approx(w0.z()).epsilon(1e-12));
}

TEST_CASE("rigid: the intermediate axis flips near the analytic time while the others stay stable", "[lab03][pts=3][sec=4]") {
  const RigidBodySystem sys(RigidBody(1.0, diag(1, 2, 3)));
  const Vec3 w0(1e-3, 1.0, 0.0);
  const double t_flip = analyticFlipTime(Vec3(1, 2, 3), w0);
  VecX X = spinning(sys, w0);
  const double h = 1e-3;
  double t = 0.0;
  while (omegaBody(sys, X).y() > 0.0 && t < 30.0) {
    run(Method::RK4, sys, X, h, 1);
    t += h;
  }
  INFO("flip (first sign change of body omega_2) at t = " << t << " s, analytic " << t_flip << " s");
  // The loop stops at the first step past the sign change, so t overshoots by at most one step
  // (1e-3 s); RK4's own phase error at h = 1e-3 over 15 s is below 1e-6 s.
  CHECK(t == Approx(t_flip).margin(2e-3));
  // The small-perturbation limit ln(4 eps^-1) / lambda, lambda = 1 / sqrt(3): the closed form
  // agrees to O(eps^2).
  CHECK(t_flip == Approx(std::log(4e3) * std::sqrt(3.0)).margin(1e-3));
  for (const Vec3& axis : {Vec3(1.0, 1e-3, 0.0), Vec3(0.0, 1e-3, 1.0)}) {
    VecX Y = spinning(sys, axis);
    double wobble = 0.0;
    for (int n = 0; n < 30; ++n) {
      run(Method::RK4, sys, Y, 0.01, 100);
      const Vec3 w = omegaBody(sys, Y);
      wobble = std::max(wobble, w.y());
    }
    // About the smallest and largest axes the 1e-3 perturbation only oscillates (stays ~1e-3).
    CHECK(wobble < 1e-2);
  }
}

TEST_CASE("rigid: renormalising keeps |q| = 1 while plain integration drifts", "[lab03][pts=2][sec=4]") {
  RigidBodySystem sys(RigidBody(1.0, diag(1, 2, 3)));
  const VecX X0 = spinning(sys, Vec3(0.5, 1.0, 0.3));
  VecX X = X0;
  sys.setRenormalize(false);
  run(Method::ExplicitEuler, sys, X, 0.01, 500);
  // Explicit Euler on qdot = 1/2 omega q scales |q|^2 by 1 + h^2 |omega|^2 / 4 per step.
  CHECK(orientationOf(X).norm() - 1.0 > 1e-4);
  sys.setRenormalize(true);
  X = X0;
  run(Method::ExplicitEuler, sys, X, 0.01, 500);
  // renormalised after every step: |q| - 1 is one rounding, ~1e-16
  CHECK(std::abs(orientationOf(X).norm() - 1.0) < 1e-12);
}

TEST_CASE("rigid: Gram-Schmidt keeps a rotation matrix orthonormal", "[lab03][pts=2][sec=6]") {
  const RigidBody body(1.0, diag(1, 2, 3));
  const Quat q0(randomRotation());
  // |L| in [1, 2], so that |omega| >= 1/3 and the uncorrected drift is well above its floor.
  const Vec3 L = uniform(1.0, 2.0) * Vec3(randomRotation().col(0));
  double error[2], det = 0.0;
  int k = 0;
  for (bool gs : {false, true}) {
    const RotationMatrixSystem sys(body, gs);
    VecX X = sys.makeState(Vec3::Zero(), q0, Vec3::Zero(), L);
    run(Method::ExplicitEuler, sys, X, 0.01, 500);
    error[k++] = sys.orthonormalityError(X);
    det = Eigen::Map<const Mat3>(X.data() + 3).determinant();
  }
  INFO("|R^T R - 1| without Gram-Schmidt " << error[0] << ", with " << error[1]);
  // Explicit Euler on Rdot = omega* R inflates R by 1 + h^2 |omega|^2 / 2 >= 1 + 5e-6 per step:
  // 500 steps give at least 5e-3.
  CHECK(error[0] > 1e-3);
  CHECK(error[1] < 1e-13);  // re-orthonormalised after every step: round-off only
  CHECK(det == Approx(1.0).epsilon(1e-13));  // a rotation, not a reflection; round-off only
}

TEST_CASE("rigid: a plain rotation-matrix step is one explicit Euler step and drifts off the rotations", "[lab03][pts=1][sec=6]") {
  const Mat3 R0 = randomRotation();
  const Vec3 omega = uniform(1.0, 2.0) * Vec3(randomRotation().col(0));  // |omega| in [1, 2]
  const double h = 0.01;
  Mat3 omega_star;  // the cross-product matrix, written here
  omega_star << 0, -omega.z(), omega.y(), omega.z(), 0, -omega.x(), -omega.y(), omega.x(), 0;
  // One plain step is R + h omega* R exactly (a few roundings of O(1) numbers).
  CHECK(rotationMatrixStep(R0, omega, h, false).isApprox(R0 + h * omega_star * R0, 1e-14));
  Mat3 plain = R0;
  for (int n = 0; n < 500; ++n) plain = rotationMatrixStep(plain, omega, h, false);
  const double plain_error = (plain.transpose() * plain - Mat3::Identity()).norm();
  INFO("|R^T R - 1| after 500 plain steps " << plain_error);
  // Each plain step multiplies squared lengths across omega by 1 + h^2 |omega|^2 >= 1 + 1e-4:
  // after 500 steps two diagonal entries of R^T R are off by 0.05 or more; 1e-2 is a safe floor.
  CHECK(plain_error > 1e-2);
}

TEST_CASE("rigid: the orthonormalising rotation-matrix step stays a rotation", "[lab03][pts=1][sec=6]") {
  const Mat3 R0 = randomRotation();
  const Vec3 omega = uniform(1.0, 2.0) * Vec3(randomRotation().col(0));  // |omega| in [1, 2]
  const double h = 0.01;
  Mat3 repaired = R0;
  for (int n = 0; n < 500; ++n) repaired = rotationMatrixStep(repaired, omega, h, true);
  const double repaired_error = (repaired.transpose() * repaired - Mat3::Identity()).norm();
  INFO("|R^T R - 1| after 500 orthonormalised steps " << repaired_error);
  CHECK(repaired_error < 1e-13);  // re-orthonormalised after every step: round-off only
  CHECK(repaired.determinant() == Approx(1.0).epsilon(1e-13));  // a rotation, not a reflection
}

TEST_CASE("rigid: the exponential map rotates by exactly |omega| h", "[lab03][pts=2][sec=5]") {
  const Quat q0(randomRotation());
  const Vec3 omega = randomVec3(2.0);
  const double h = uniform(0.01, 1.0);
  const Quat q1 = exponentialUpdate(q0, omega, h);
  // q1 q0^-1 is a rotation by |omega| h about omega (in the world frame).
  const Eigen::AngleAxisd turn(q1 * q0.conjugate());
  // Exact up to round-off: a few roundings in the angle and in the axis, which loses digits
  // only as the angle shrinks (axis error ~1e-16 / angle; the angle here is almost always > 1e-3).
  CHECK(turn.angle() == Approx(omega.norm() * h).epsilon(1e-12));
  CHECK(turn.axis().isApprox(omega.normalized(), 1e-10));
  CHECK(q1.norm() == Approx(1.0).epsilon(1e-14));  // a product of unit quaternions: round-off
  // The lecture's check: 1 rad/s for 1 s about z turns x into (cos 1, sin 1, 0); round-off only.
  const Quat q = exponentialUpdate(Quat::Identity(), Vec3(0, 0, 1), 1.0);
  CHECK((q * Vec3::UnitX()).isApprox(Vec3(std::cos(1.0), std::sin(1.0), 0.0), 1e-14));
}

TEST_CASE("rigid: two explicit Euler steps of a box pushed off-centre match the hand computation", "[lab03][pts=2][sec=4]") {
  // Box M = 2, edges (1, 2, 3): I_body = 2/12 diag(13, 10, 5). Force (0, 0, 1) N at body point
  // (0.5, 0, 0), at rest at the origin, h = 0.1.
  // Step 1: P = (0, 0, 0.1), L = h (r x F) = 0.1 (0, -0.5, 0) = (0, -0.05, 0); x and q unchanged
  //         (v = omega = 0 at the start).
  // Step 2: omega = I^-1 L = (0, -0.05 / (20/12), 0) = (0, -0.03, 0); x = h P / M = (0, 0, 0.005);
  //         q = q + h/2 (0, omega) q = (1, 0, -0.0015, 0); P = (0, 0, 0.2); L = (0, -0.1, 0)
  //         (the force point has not moved yet: R = 1 at the start of step 2).
  const RigidBodySystem sys(RigidBody(2.0, diag(13, 10, 5) * 2.0 / 12.0), {{Vec3(0.5, 0, 0), Vec3(0, 0, 1)}});
  RigidBodySystem plain = sys;
  plain.setRenormalize(false);
  VecX X = plain.makeState(Vec3::Zero(), Quat::Identity(), Vec3::Zero(), Vec3::Zero());
  run(Method::ExplicitEuler, plain, X, 0.1, 2);
  VecX expected(13);
  expected << 0, 0, 0.005, 1, 0, -0.0015, 0, 0, 0, 0.2, 0, -0.1, 0;
  CHECK((X - expected).cwiseAbs().maxCoeff() < 1e-12);  // a few roundings of exact decimals
}
