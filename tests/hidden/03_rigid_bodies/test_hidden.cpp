// Lab 3 hidden tests (instructor only, shown after grades are published).
#include "physlab/rigid.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

TEST_CASE("hidden: a spinning sphere turns at the constant rate L / I", "[lab03][pts=2][hidden][sec=4]") {
  const double I = uniform(0.5, 2.0);
  const RigidBodySystem sys(RigidBody(1.0, I * Mat3::Identity()));
  const Vec3 L = randomVec3(2.0);
  const Quat q0(randomRotation());
  VecX X = sys.makeState(Vec3::Zero(), q0, Vec3::Zero(), L);
  const double T = 1.0;
  run(Method::RK4, sys, X, 1e-3, 1000);
  // Isotropic inertia: omega = L / I never changes, so q(T) = exp(T omega / 2) q0 exactly;
  // RK4 at h = 1e-3 with renormalisation is accurate to ~1e-12.
  const Quat expected = Quat(Eigen::AngleAxisd(L.norm() / I * T, L.normalized())) * q0;
  CHECK(orientationOf(X).angularDistance(expected) < 1e-9);
}

TEST_CASE("hidden: Euler's equations conserve kinetic energy and |L| in the body frame", "[lab03][pts=1][hidden][sec=7]") {
  const Mat3 I = Vec3(uniform(0.5, 1.0), uniform(1.5, 2.0), uniform(2.5, 3.0)).asDiagonal();
  Vec3 w = randomVec3(1.0);
  const double E0 = 0.5 * w.dot(I * w), L0 = (I * w).norm();
  const double h = 1e-3;
  for (int n = 0; n < 5000; ++n) {
    const Vec3 k1 = bodyFrameOmegaRate(I, w, Vec3::Zero());
    const Vec3 k2 = bodyFrameOmegaRate(I, w + 0.5 * h * k1, Vec3::Zero());
    const Vec3 k3 = bodyFrameOmegaRate(I, w + 0.5 * h * k2, Vec3::Zero());
    const Vec3 k4 = bodyFrameOmegaRate(I, w + h * k3, Vec3::Zero());
    w += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  // Both are invariants of the exact flow; RK4 at this step keeps them to ~1e-12.
  CHECK(0.5 * w.dot(I * w) == Approx(E0).epsilon(1e-9));
  CHECK((I * w).norm() == Approx(L0).epsilon(1e-9));
}
