// Lab 3 graded tests of each function's whole contract: unequal point masses, quaternions that
// are not unit length, Euler's equations with a torque and a non-diagonal inertia tensor, and
// bad input refused by name.
#include <cmath>
#include <limits>

#include "physlab/error.hpp"
#include "physlab/rigid.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// A symmetric positive definite tensor with principal moments in [0.5, 3] along random axes.
Mat3 randomInertia() {
  const Mat3 B = randomRotation();
  return B * Vec3(uniform(0.5, 1.0), uniform(1.5, 2.0), uniform(2.5, 3.0)).asDiagonal() * B.transpose();
}

}  // namespace

TEST_CASE("inertia: point masses of unequal mass obey the parallel-axis theorem", "[lab03][pts=1][sec=1]") {
  const Index n = 6;
  VecX m(n);
  Mat3X r(3, n);
  const Vec3 offset = randomVec3(3.0);  // far from the origin, so the centre matters
  for (Index i = 0; i < n; ++i) {
    m[i] = uniform(0.1, 5.0);  // masses 50x apart: the centre of mass is not the mean point
    r.col(i) = offset + randomVec3(1.0);
  }
  Mat3 about_origin = Mat3::Zero();
  for (Index i = 0; i < n; ++i) {
    about_origin += m[i] * (r.col(i).squaredNorm() * Mat3::Identity() - r.col(i) * r.col(i).transpose());
  }
  const double M = m.sum();
  const Vec3 c = r * m / M;
  // Steiner: I_origin = I_centre + M (|c|^2 1 - c c^T).
  const Mat3 shifted = pointMassInertia(m, r) + M * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
  // Sums of products of numbers ~ 4: the cancellation in I_centre loses at most ~1e-14 relative.
  CHECK((shifted - about_origin).norm() < 1e-12 * about_origin.norm());
}

TEST_CASE("inertia: a single point mass has no inertia about itself, two make a rod", "[lab03][pts=1][sec=1]") {
  // One point mass (the least the header allows) sits at its own centre of mass: I = 0, up to
  // the round-off of c = m r / m (~1e-16 |r|, squared).
  {
    INFO("one point mass, m = 2 at r = (1, -2, 3): allowed, and its inertia about its own centre is 0");
    const Mat3 single = pointMassInertia(VecX::Constant(1, 2.0), Vec3(1.0, -2.0, 3.0));
    CHECK(single.norm() < 1e-12);
  }
  // Masses 1 at the origin and 3 at (4, 0, 0): c = (3, 0, 0), arms 3 and 1 across x, so
  // I = (1 * 9 + 3 * 1) diag(0, 1, 1), exactly (small integers).
  Mat3X r = Mat3X::Zero(3, 2);
  r(0, 1) = 4.0;
  const Mat3 rod = pointMassInertia(Eigen::Vector2d(1.0, 3.0), r);
  CHECK((rod - Vec3(0.0, 12.0, 12.0).asDiagonal().toDenseMatrix()).norm() < 1e-14);
}

TEST_CASE("forces: the wrench of no force is zero, of one force that force and its moment", "[lab03][pts=1][sec=3]") {
  const Vec3 x(1.0, 0.0, 0.0);
  // An empty list: nothing to sum, an exact zero.
  {
    INFO("an empty list of forces about x = (1, 0, 0): the wrench is (0, 0, 0), (0, 0, 0)");
    const Wrench none = wrenchAbout(x, {});
    CHECK(none.force.norm() == 0.0);
    CHECK(none.torque.norm() == 0.0);
  }
  // By hand: (3 z) at x + (0, 2, 0) has moment (0, 2, 0) x (0, 0, 3) = (6, 0, 0); (3 x) at
  // x + (0, 0, 2) has moment (0, 0, 2) x (3, 0, 0) = (0, 6, 0). Small integers: exact.
  const Wrench one = wrenchAbout(x, {AppliedForce{Vec3(1.0, 2.0, 0.0), Vec3(0.0, 0.0, 3.0)}});
  CHECK((one.force - Vec3(0.0, 0.0, 3.0)).norm() == 0.0);
  CHECK((one.torque - Vec3(6.0, 0.0, 0.0)).norm() == 0.0);
  const Wrench other = wrenchAbout(x, {AppliedForce{Vec3(1.0, 0.0, 2.0), Vec3(3.0, 0.0, 0.0)}});
  CHECK((other.force - Vec3(3.0, 0.0, 0.0)).norm() == 0.0);
  CHECK((other.torque - Vec3(0.0, 6.0, 0.0)).norm() == 0.0);
}

TEST_CASE("rigid: the exponential update at its edges: no turn at omega = 0 or h = 0, the tiniest turn kept, a negative step turns back", "[lab03][pts=1][sec=5]") {
  const Quat q0(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 2.0) / 3.0));
  const Vec3 omega(0.3, -0.4, 1.2);
  // Angle exactly 0, either way: q comes back unchanged (round-off at most, 1e-15).
  CHECK((exponentialUpdate(q0, Vec3::Zero(), 0.5).coeffs() - q0.coeffs()).norm() <= 1e-15);
  CHECK((exponentialUpdate(q0, omega, 0.0).coeffs() - q0.coeffs()).norm() <= 1e-15);
  // A step back undoes a step forward: a rotation by -|omega| h about the same axis. Two
  // quaternion products of unit quaternions: a few roundings of ~1e-16 each.
  const Quat forward = exponentialUpdate(q0, omega, 0.25);
  CHECK((exponentialUpdate(forward, omega, -0.25).coeffs() - q0.coeffs()).norm() < 1e-14);
  // A turn of 1e-9 rad about z is (cos 5e-10, 0, 0, sin 5e-10) q0: two products of unit
  // quaternions differ by round-off (~1e-16), while skipping the turn errs by 5e-10.
  const Quat tiny = exponentialUpdate(q0, Vec3(0.0, 0.0, 2.0), 5e-10);
  const Quat expected = Quat(std::cos(5e-10), 0.0, 0.0, std::sin(5e-10)) * q0;
  CHECK((tiny.coeffs() - expected.coeffs()).norm() < 1e-15);
}

TEST_CASE("rigid: angular velocity depends on the rotation q stands for, not on its length", "[lab03][pts=1][sec=2]") {
  const RigidBody body(uniform(1.0, 3.0), randomInertia());
  const Quat q(randomRotation());
  const Vec3 L = randomVec3(2.0);
  const double scale = uniform(1.25, 2.0);  // the drift a state without renormalisation shows
  const Quat stretched(scale * q.w(), scale * q.x(), scale * q.y(), scale * q.z());
  const Vec3 omega = angularVelocity(body, q, L);
  // q and scale q are the same rotation: equal up to the round-off of normalising.
  CHECK((angularVelocity(body, stretched, L) - omega).norm() < 1e-12 * omega.norm());
  // and the unit q gives I_world omega = L (condition number of I at most 6).
  const Mat3 R = q.toRotationMatrix();
  CHECK((R * body.inertia_body * R.transpose() * omega - L).norm() < 1e-12 * L.norm());
}

TEST_CASE("rigid: Euler's equations balance torque and the gyroscopic term for any inertia tensor", "[lab03][pts=1][sec=7]") {
  const Mat3 I = randomInertia();  // not diagonal: the body axes are not its principal axes
  const Vec3 omega = randomVec3(2.0), torque = randomVec3(5.0);
  const Vec3 gyroscopic = omega.cross(I * omega);
  const Vec3 rate = bodyFrameOmegaRate(I, omega, torque);
  // I omega_dot = tau - omega x I omega; the solve with condition number <= 6 loses ~1e-15.
  CHECK((I * rate + gyroscopic - torque).norm() < 1e-12 * (torque.norm() + gyroscopic.norm()));
  // A body at rest only feels the torque: omega_dot = I^-1 tau.
  CHECK((I * bodyFrameOmegaRate(I, Vec3::Zero(), torque) - torque).norm() < 1e-12 * torque.norm());
}

TEST_CASE("bad input: no inertia for a non-positive mass or size, no rotation for a zero quaternion", "[lab03][pts=1][sec=1][sec=2]") {
  using Catch::Matchers::Contains;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double M = uniform(0.5, 2.0), r = uniform(0.1, 1.0);
  // Valid input of any size is accepted (a tiny body has a tiny inertia, not an error)
  CHECK(sphereInertia(1e-6, 1e-3)(0, 0) > 0.0);
  for (const double bad : {0.0, -M, nan}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(sphereInertia(bad, r), InvalidInput);
    CHECK_THROWS_AS(sphereInertia(M, bad), InvalidInput);
    CHECK_THROWS_AS(boxInertia(bad, Vec3(r, r, r)), InvalidInput);
    for (int k = 0; k < 3; ++k) {  // each edge on its own: a box is flat if any edge is
      Vec3 size = Vec3::Constant(r);
      size[k] = bad;
      CHECK_THROWS_AS(boxInertia(M, size), InvalidInput);
    }
    CHECK_THROWS_AS(cylinderInertia(bad, r, r), InvalidInput);
    CHECK_THROWS_AS(cylinderInertia(M, bad, r), InvalidInput);
    CHECK_THROWS_AS(cylinderInertia(M, r, bad), InvalidInput);
    CHECK_THROWS_AS(pointMassInertia(Vec3(M, bad, M), Mat3::Identity()), InvalidInput);
  }
  CHECK_THROWS_AS(pointMassInertia(VecX::Ones(2), Mat3X::Zero(3, 3)), InvalidInput);  // 2 masses, 3 points
  CHECK_THROWS_AS(pointMassInertia(VecX(0), Mat3X(3, 0)), InvalidInput);              // nothing at all
  Mat3 positions = Mat3::Identity();
  positions(1, 2) = nan;
  CHECK_THROWS_AS(pointMassInertia(Vec3::Ones(), positions), InvalidInput);
  // A zero quaternion stands for no rotation: no angular velocity, no update
  const RigidBody body(M, sphereInertia(M, r));
  const Vec3 L = randomVec3(1.0), omega = randomVec3(1.0);
  CHECK_THROWS_WITH(angularVelocity(body, Quat(0, 0, 0, 0), L), Contains("zero"));
  CHECK_THROWS_AS(angularVelocity(body, Quat(nan, 0, 0, 0), L), InvalidInput);
  CHECK_THROWS_AS(angularVelocity(body, Quat(1, 0, 0, 0), Vec3(0, nan, 0)), InvalidInput);
  CHECK_THROWS_WITH(exponentialUpdate(Quat(0, 0, 0, 0), omega, 0.01), Contains("zero"));
  CHECK_THROWS_AS(exponentialUpdate(Quat(1, 0, 0, 0), Vec3(nan, 0, 0), 0.01), InvalidInput);
  CHECK_THROWS_AS(exponentialUpdate(Quat(1, 0, 0, 0), omega, nan), InvalidInput);
  // A state whose quaternion was zeroed does not step on
  const RigidBodySystem sys(body);
  VecX X = sys.makeState(Vec3::Zero(), Quat(randomRotation()), Vec3::Zero(), L);
  X.segment<4>(3).setZero();
  VecX dXdt;
  CHECK_THROWS_AS(sys.derivative(X, dXdt), InvalidInput);
}
