// Framework tests for Lab 3: bad bodies and states are refused with a message naming them.
#include "physlab/error.hpp"
#include "physlab/rigid.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

TEST_CASE("rigid validation: bad mass and inertia are refused", "[common]") {
  CHECK_THROWS_WITH(RigidBody(0.0, Mat3::Identity()), Contains("rigid body mass"));
  CHECK_THROWS_WITH(RigidBody(-1.0, Mat3::Identity()), Contains("rigid body mass"));
  CHECK_THROWS_WITH(RigidBody(1.0, Vec3(1.0, -2.0, 3.0).asDiagonal()), Contains("not positive definite"));
  Mat3 skewed = Mat3::Identity();
  skewed(0, 1) = 0.5;
  CHECK_THROWS_WITH(RigidBody(1.0, skewed), Contains("not symmetric"));
  Mat3 nan = Mat3::Identity();
  nan(2, 2) = std::nan("");
  CHECK_THROWS_WITH(RigidBody(1.0, nan), Contains("inertia tensor has a non-finite entry"));
}

TEST_CASE("rigid validation: zero and non-finite quaternions are refused", "[common]") {
  const RigidBodySystem sys(RigidBody(1.0, Mat3::Identity()));
  CHECK_THROWS_WITH(sys.makeState(Vec3::Zero(), Quat(0, 0, 0, 0), Vec3::Zero(), Vec3::Zero()),
                    Contains("quaternion is zero"));
  CHECK_THROWS_WITH(sys.makeState(Vec3::Zero(), Quat(std::nan(""), 0, 0, 0), Vec3::Zero(), Vec3::Zero()),
                    Contains("orientation quaternion has a non-finite entry"));
  const RotationMatrixSystem matrix(RigidBody(1.0, Mat3::Identity()), true);
  CHECK_THROWS_WITH(matrix.makeState(Vec3::Zero(), Quat(0, 0, 0, 0), Vec3::Zero(), Vec3::Zero()),
                    Contains("quaternion is zero"));
  CHECK_THROWS_WITH(matrix.makeState(Vec3::Zero(), Quat(1, std::nan(""), 0, 0), Vec3::Zero(), Vec3::Zero()),
                    Contains("orientation quaternion has a non-finite entry"));
  const VecX X = sys.makeState(Vec3::Zero(), Quat(2, 0, 0, 0), Vec3::Zero(), Vec3::Zero());
  CHECK(orientationOf(X).norm() == Approx(1.0));  // normalised on the way in
}
