// Framework tests: bad input is refused with a message naming what was wrong. They grade
// nothing (the checks live in common/, not in student code), so they carry [common].
#include "physlab/error.hpp"
#include "physlab/integrators.hpp"
#include "physlab/particles.hpp"
#include "physlab/scenes.hpp"
#include "support.hpp"

using namespace physlab;
using Catch::Matchers::Contains;

TEST_CASE("validation: zero, negative and NaN masses are refused", "[common]") {
  CHECK_THROWS_WITH(ParticleSystem(Eigen::Vector2d(1.0, 0.0)), Contains("mass of particle 1"));
  CHECK_THROWS_WITH(ParticleSystem(Eigen::Vector2d(-2.0, 1.0)), Contains("mass of particle 0"));
  CHECK_THROWS_AS(ParticleSystem(Eigen::Vector2d(1.0, std::nan(""))), InvalidInput);
  CHECK_NOTHROW(ParticleSystem(Eigen::Vector2d(1.0, std::numeric_limits<double>::infinity())));
}

TEST_CASE("validation: a non-positive or NaN step is refused", "[common]") {
  const HarmonicOscillator osc(1.0);
  VecX X = VecX::Ones(2);
  Integrator integrator(Method::RK4);
  CHECK_THROWS_WITH(integrator.step(osc, X, 0.0), Contains("step size h"));
  CHECK_THROWS_WITH(integrator.step(osc, X, -0.1), Contains("step size h"));
  CHECK_THROWS_AS(integrator.step(osc, X, std::nan("")), InvalidInput);
}

TEST_CASE("validation: a state of the wrong size or with a NaN is refused", "[common]") {
  const HarmonicOscillator osc(1.0);
  Integrator integrator(Method::Verlet);
  VecX wrong = VecX::Ones(3);
  CHECK_THROWS_WITH(integrator.step(osc, wrong, 0.1), Contains("has size 3, expected 2"));
  VecX nan = VecX::Ones(2);
  nan[1] = std::nan("");
  // The step checks its result only: a NaN passed in stays NaN (and spreads: the drift carries
  // v into x) and is reported with both causes
  CHECK_THROWS_WITH(integrator.step(osc, nan, 0.1), Contains("non-finite entry") && Contains("passed in"));
  // Implicit Euler checks its input first, so Newton's method does not take it for non-convergence
  nan = VecX::Ones(2);
  nan[0] = std::nan("");
  CHECK_THROWS_AS(Integrator(Method::ImplicitEuler).step(osc, nan, 0.1), InvalidInput);
  // A finite state that a step makes non-finite: the method diverged
  Integrator euler(Method::ExplicitEuler);
  VecX huge = VecX::Constant(2, 1e300);
  CHECK_THROWS_WITH(euler.step(HarmonicOscillator(1e10), huge, 1.0), Contains("diverged"));
  huge = VecX::Constant(2, 1e300);
  CHECK_THROWS_AS(euler.step(HarmonicOscillator(1e10), huge, 1.0), NumericalFailure);
  const ParticleSystem sys(VecX::Ones(2));
  CHECK_THROWS_WITH(sys.makeState(Mat3X::Zero(3, 3), Mat3X::Zero(3, 2)),
                    Contains("positions (columns) has size 3, expected 2"));
}

TEST_CASE("validation: bad force parameters are refused", "[common]") {
  CHECK_THROWS_WITH(DampedSpring(0, 1, 1.0, -5.0, 0.0), Contains("spring stiffness ks"));
  CHECK_THROWS_WITH(DampedSpring(0, 1, -1.0, 5.0, 0.0), Contains("spring rest length"));
  CHECK_THROWS_WITH(DampedSpring(2, 2, 1.0, 5.0, 0.0), Contains("joins particle 2 to itself"));
  CHECK_THROWS_WITH(ViscousDrag(-1.0), Contains("drag coefficient"));
  CHECK_THROWS_WITH(NBodyGravity(0.0, 0.1), Contains("gravitational constant"));
  CHECK_THROWS_WITH(LennardJones(1.0, 0.0), Contains("sigma"));
  ParticleSystem sys(VecX::Ones(2));
  CHECK_THROWS_WITH(sys.addForce(std::make_shared<DampedSpring>(0, 5, 1.0, 1.0, 0.0)),
                    Contains("names particle 5"));
}

TEST_CASE("validation: unknown integrator names are refused", "[common]") {
  CHECK(methodFromId("rk4") == Method::RK4);
  CHECK_THROWS_WITH(methodFromId("rk5"), Contains("unknown integrator 'rk5'"));
}

TEST_CASE("framework: positionRateView reads a particle system's velocities in place", "[common]") {
  const ParticleSystem particles(VecX::Ones(2));
  const VecX X = VecX::LinSpaced(12, 1.0, 12.0);
  VecX scratch = VecX::Zero(6);
  const Eigen::Map<const VecX> v = particles.positionRateView(X, scratch);
  CHECK(v.data() == X.data() + 6);  // the velocities themselves, no copy
  CHECK(scratch.isZero());
  // A system whose position rate is computed writes it into the scratch
  const HarmonicOscillator osc(2.0);
  const VecX Y = Eigen::Vector2d(0.5, -3.0);
  VecX qdot(1);
  const Eigen::Map<const VecX> rate = osc.positionRateView(Y, qdot);
  CHECK(rate.data() == qdot.data());
  CHECK(rate[0] == -3.0);
}

TEST_CASE("framework: the finite-difference Jacobian matches the analytic one", "[common]") {
  // Kepler has no analytic Jacobian, so jacobian() differentiates numerically; compare with
  // the exact d(-mu r/|r|^3)/dr = -mu (I/|r|^3 - 3 r r^T/|r|^5).
  const Kepler kepler(1.3);
  VecX X(6);
  X << 0.7, -0.4, 0.2, 0.1, 0.9, -0.3;
  const MatX J = kepler.jacobian(X);
  const Vec3 r = X.head<3>();
  const double n = r.norm();
  const Mat3 expected = -1.3 * (Mat3::Identity() / std::pow(n, 3) - 3.0 * r * r.transpose() / std::pow(n, 5));
  // cbrt(eps)-sized central differences: ~1e-10 relative error.
  CHECK((J.bottomLeftCorner<3, 3>() - expected).norm() < 1e-8 * expected.norm());
  CHECK(J.topRightCorner<3, 3>().isIdentity(1e-8));
}
