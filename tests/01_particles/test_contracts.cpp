// Lab 1 graded tests of each function's whole contract: one step of every integrator against
// its formula on a nonlinear system, Newton's failure, pinned particles in every force and
// diagnostic, and forces that accumulate into buffers already holding other forces.
#include "physlab/error.hpp"
#include "physlab/scenes.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// A nonlinear system written here, with 3 positions and 2 velocities (so that a step mixing up
// the two parts' sizes fails), whose position rate depends on p and velocity rate on q: every
// integrator's stages then give different results.
class Coupled final : public System {
 public:
  Index positionSize() const override { return 3; }
  Index velocitySize() const override { return 2; }
  std::string name() const override { return "coupled test system"; }
  static Vec3 qdot(const VecX& X) {
    const double q0 = X[0], q1 = X[1], q2 = X[2], p0 = X[3], p1 = X[4];
    return Vec3(p0 + 0.5 * std::sin(q1), p1 - 0.3 * q0 * p0, std::cos(p0 + q2));
  }
  static Eigen::Vector2d pdot(const VecX& X) {
    const double q0 = X[0], q1 = X[1], q2 = X[2], p0 = X[3], p1 = X[4];
    return Eigen::Vector2d(-q0 - 0.2 * q1 * q1 * q1 + 0.1 * p1, -std::sin(q2) - 0.4 * p0 * p1);
  }
  static VecX f(const VecX& X) {
    VecX dX(5);
    dX << qdot(X), pdot(X);
    return dX;
  }

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> out) const override { out = qdot(X); }
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> out) const override { out = pdot(X); }
};

VecX randomCoupledState() {
  VecX X(5);
  for (Index i = 0; i < 5; ++i) X[i] = uniform(-1.0, 1.0);
  return X;
}

// One step of `method` from X0 with the student's code, compared with the formula's `expected`.
void checkOneStep(Method method, const VecX& X0, double h, const VecX& expected) {
  const Coupled sys;
  VecX X = X0;
  run(method, sys, X, h, 1);
  INFO(methodName(method) << " at h = " << h << ": got " << X.transpose() << ", expected "
                          << expected.transpose());
  // The same arithmetic in another order: round-off of O(1) numbers, ~1e-16 per operation.
  CHECK((X - expected).norm() < 1e-13 * (1.0 + expected.norm()));
}

// A force written here that adds a fixed random vector to each particle.
class ConstantForce final : public Force {
 public:
  explicit ConstantForce(Index n) : c_(Mat3X(3, n)) {
    for (Index i = 0; i < n; ++i) c_.col(i) = randomVec3(3.0);
  }
  std::string name() const override { return "constant test force"; }
  void accumulate(const ParticleView&, Points F) const override { F += c_; }
  double potential(const ParticleView&) const override { return 0.0; }
  const Mat3X& c() const { return c_; }

 private:
  Mat3X c_;
};

// n particles with unequal masses in [0.5, 3], the one at `pinned` given infinite mass.
VecX massesWithPin(Index n, Index pinned) {
  VecX m(n);
  for (Index i = 0; i < n; ++i) m[i] = uniform(0.5, 3.0);
  m[pinned] = std::numeric_limits<double>::infinity();
  return m;
}

}  // namespace

TEST_CASE("one step: explicit Euler is X + h f(X)", "[lab01][pts=1][sec=3]") {
  const VecX X0 = randomCoupledState();
  const double h = uniform(0.05, 0.2);
  checkOneStep(Method::ExplicitEuler, X0, h, X0 + h * Coupled::f(X0));
}

TEST_CASE("one step: symplectic Euler kicks with the old positions, then drifts with the new velocities", "[lab01][pts=1][sec=3]") {
  const VecX X0 = randomCoupledState();
  const double h = uniform(0.05, 0.2);
  VecX expected = X0;
  expected.tail<2>() += h * Coupled::pdot(X0);
  expected.head<3>() += h * Coupled::qdot(expected);
  checkOneStep(Method::SymplecticEuler, X0, h, expected);
}

TEST_CASE("one step: midpoint uses the slope half a step ahead", "[lab01][pts=1][sec=3]") {
  const VecX X0 = randomCoupledState();
  const double h = uniform(0.05, 0.2);
  checkOneStep(Method::Midpoint, X0, h, X0 + h * Coupled::f(X0 + 0.5 * h * Coupled::f(X0)));
}

TEST_CASE("one step: trapezoid averages the slopes at both ends of an Euler step", "[lab01][pts=1][sec=3]") {
  const VecX X0 = randomCoupledState();
  const double h = uniform(0.05, 0.2);
  const VecX k1 = Coupled::f(X0), k2 = Coupled::f(X0 + h * k1);
  checkOneStep(Method::Trapezoid, X0, h, X0 + 0.5 * h * (k1 + k2));
}

TEST_CASE("one step: RK4 combines its four stages with weights 1/6, 1/3, 1/3, 1/6", "[lab01][pts=1][sec=3]") {
  const VecX X0 = randomCoupledState();
  const double h = uniform(0.05, 0.2);
  const VecX k1 = Coupled::f(X0);
  const VecX k2 = Coupled::f(X0 + 0.5 * h * k1);
  const VecX k3 = Coupled::f(X0 + 0.5 * h * k2);
  const VecX k4 = Coupled::f(X0 + h * k3);
  checkOneStep(Method::RK4, X0, h, X0 + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4));
}

TEST_CASE("one step: Verlet kicks half, drifts, and kicks half with the new forces", "[lab01][pts=1][sec=3]") {
  const VecX X0 = randomCoupledState();
  const double h = uniform(0.05, 0.2);
  VecX expected = X0;
  expected.tail<2>() += 0.5 * h * Coupled::pdot(expected);
  expected.head<3>() += h * Coupled::qdot(expected);
  expected.tail<2>() += 0.5 * h * Coupled::pdot(expected);
  checkOneStep(Method::Verlet, X0, h, expected);
}

TEST_CASE("one step: implicit Euler solves X1 = X0 + h f(X1) on a nonlinear system", "[lab01][pts=1][sec=3]") {
  const Coupled sys;
  const VecX X0 = randomCoupledState();
  const double h = uniform(0.1, 0.3);
  VecX X = X0;
  run(Method::ImplicitEuler, sys, X, h, 1);
  const VecX residual = X - X0 - h * Coupled::f(X);
  INFO("h = " << h << ", residual " << residual.transpose());
  // Newton stops when its update is below 1e-12 (1 + |X|) and converges quadratically, so the
  // residual is round-off; one Newton step from the Euler guess would leave ~1e-5 here.
  CHECK(residual.norm() < 1e-10 * (1.0 + X.norm()));
  CHECK((X - X0).norm() > 1e-3);  // and it did step
}

TEST_CASE("implicit Euler: throws NumericalFailure when Newton runs out of iterations", "[lab01][pts=1][sec=3]") {
  const Coupled sys;
  const VecX X0 = randomCoupledState();
  VecX X = X0;
  Integrator converging(Method::ImplicitEuler);
  converging.step(sys, X, 0.2);
  // One iteration from the Euler guess cannot meet the 1e-12 tolerance on a nonlinear system
  // (its update is ~1e-2): the step must say so rather than return an unconverged state.
  Integrator starved(Method::ImplicitEuler, NewtonSettings{1, 1e-12});
  X = X0;
  CHECK_THROWS_AS(starved.step(sys, X, 0.2), NumericalFailure);
}

TEST_CASE("implicit Euler: Newton may converge on its last allowed iteration, the first one included", "[lab01][pts=1][sec=3]") {
  // A fixed linear oscillator, w = 2, h = 0.1: from the Euler guess the first Newton iteration
  // lands on the solution (I - hJ)^-1 X0 and the second one's update is round-off, below the
  // tolerance. So Newton needs exactly two iterations: max_iterations = 2 must succeed.
  const HarmonicOscillator osc(2.0);
  const double h = 0.1, hw2 = h * 2.0 * 2.0;
  const VecX X0 = Eigen::Vector2d(1.0, 0.5);
  const VecX expected = Eigen::Vector2d(X0[0] + h * X0[1], X0[1] - hw2 * X0[0]) / (1.0 + h * hw2);
  VecX X = X0;
  Integrator two(Method::ImplicitEuler, NewtonSettings{2, 1e-12});
  REQUIRE_NOTHROW(two.step(osc, X, h));
  CHECK((X - expected).norm() < 1e-14);  // a 2 x 2 solve of O(1) numbers: round-off only
  // and one iteration is not enough: its update from the Euler guess is h^2 w^2 |X| ~ 0.04.
  X = X0;
  Integrator one(Method::ImplicitEuler, NewtonSettings{1, 1e-12});
  CHECK_THROWS_AS(one.step(osc, X, h), NumericalFailure);
  // A free particle at rest without forces is a fixed point: the Euler guess is the solution,
  // the first update is exactly 0, and max_iterations = 1 (the least allowed) suffices.
  const ParticleSystem still(VecX::Constant(1, 2.0));
  const VecX Y0 = still.makeState(Vec3(0.25, -0.5, 1.0), Vec3::Zero());
  VecX Y = Y0;
  REQUIRE_NOTHROW(one.step(still, Y, h));
  CHECK(Y == Y0);
}

TEST_CASE("integrators: one step costs the force evaluations its method documents", "[lab01][pts=1][sec=3]") {
  // Method's documentation: explicit and symplectic Euler 1, midpoint, trapezoid and Verlet 2,
  // RK4 4. The drift reads the position rate (positionRateView()), which is no force evaluation.
  const Coupled sys;
  const std::vector<std::pair<Method, long>> costs = {
      {Method::ExplicitEuler, 1}, {Method::SymplecticEuler, 1}, {Method::Midpoint, 2},
      {Method::Trapezoid, 2},     {Method::RK4, 4},             {Method::Verlet, 2}};
  for (const auto& [method, cost] : costs) {
    INFO(methodName(method));
    Integrator integrator(method);
    VecX X = randomCoupledState();
    sys.resetCount();
    integrator.step(sys, X, 0.1);
    CHECK(sys.forceEvaluations() == cost);
    sys.resetCount();
    integrator.step(sys, X, 0.1);
    CHECK(sys.forceEvaluations() == cost);  // every step alike, none saved up from the first
  }
}

TEST_CASE("particles: the velocity rate overwrites whatever its output buffer held", "[lab01][pts=1][sec=2]") {
  const Index n = 4;
  ParticleSystem sys(massesWithPin(n, 2));
  auto force = std::make_shared<ConstantForce>(n);
  sys.addForce(force);
  const VecX X = sys.makeState(randomPoints(n, 1.0), randomPoints(n, 1.0));
  VecX pdot = VecX::Constant(3 * n, uniform(1.0, 100.0));  // stale values from an earlier step
  sys.velocityRate(X, pdot);
  const ConstPoints a(pdot.data(), 3, n);
  for (Index i = 0; i < n; ++i) {
    INFO("particle " << i);
    const Vec3 expected = i == 2 ? Vec3::Zero() : Vec3(force->c().col(i) / sys.masses()[i]);
    CHECK((a.col(i) - expected).norm() <= 1e-14 * force->c().col(i).norm());  // one division
  }
}

TEST_CASE("particles: a pinned particle feels no acceleration under gravity and drag", "[lab01][pts=1][sec=2]") {
  const Index n = 3;
  const VecX m = massesWithPin(n, 1);
  ParticleSystem sys(m);
  const Vec3 g = randomVec3(10.0);
  const double d = uniform(0.1, 2.0);
  sys.addForce(std::make_shared<UniformGravity>(g));
  sys.addForce(std::make_shared<ViscousDrag>(d));
  const Mat3X v = randomPoints(n, 1.0);
  VecX dX;
  sys.derivative(sys.makeState(randomPoints(n, 1.0), v), dX);
  CHECK(velocities(dX).col(1).norm() == 0.0);  // exactly: F times 1/inf = 0, never NaN
  for (Index i : {0, 2}) {
    const Vec3 expected = g - d * v.col(i) / m[i];
    // Two forces summed and divided by m: round-off of numbers ~10.
    CHECK((velocities(dX).col(i) - expected).norm() < 1e-13 * (1.0 + expected.norm()));
  }
}

TEST_CASE("diagnostics: pinned particles are left out of the energies and the momenta", "[lab01][pts=1][sec=4]") {
  const Index n = 4;
  const VecX m = massesWithPin(n, 3);
  ParticleSystem sys(m);
  const Vec3 g = randomVec3(10.0);
  sys.addForce(std::make_shared<UniformGravity>(g));
  // The pinned particle is given a velocity too: the diagnostics must ignore it, not multiply it.
  const Mat3X x = randomPoints(n, 2.0), v = randomPoints(n, 2.0);
  const VecX X = sys.makeState(x, v);
  double T = 0.0, U = 0.0;
  Vec3 P = Vec3::Zero(), L = Vec3::Zero();
  for (Index i = 0; i < 3; ++i) {
    T += 0.5 * m[i] * v.col(i).squaredNorm();
    U -= m[i] * g.dot(x.col(i));
    P += m[i] * v.col(i);
    L += m[i] * x.col(i).cross(v.col(i));
  }
  // Sums of three products: round-off only, measured against the size of the terms.
  CHECK(kineticEnergy(sys, X) == Approx(T).epsilon(1e-13));
  CHECK(potentialEnergy(sys, X) == Approx(U).epsilon(1e-12).margin(1e-12 * m.head(3).sum() * g.norm()));
  CHECK((linearMomentum(sys, X) - P).norm() < 1e-13 * (1.0 + P.norm()));
  CHECK((angularMomentum(sys, X) - L).norm() < 1e-13 * (1.0 + L.norm()));
}

TEST_CASE("forces: every force adds to a buffer that already holds other forces", "[lab01][pts=1][sec=1]") {
  const Index n = 4;
  VecX m(n);
  for (Index i = 0; i < n; ++i) m[i] = uniform(0.5, 2.0);
  Mat3X x(3, n);
  x << 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0;  // a unit square: every pair at least 1 apart
  x += randomPoints(n, 0.1);
  const Mat3X v = randomPoints(n, 1.0);
  const ParticleView s{ConstPoints(x.data(), 3, n), ConstPoints(v.data(), 3, n), m};
  const std::vector<std::shared_ptr<const Force>> forces = {
      std::make_shared<UniformGravity>(randomVec3(10.0)), std::make_shared<NBodyGravity>(1.0, 0.1),
      std::make_shared<ViscousDrag>(uniform(0.1, 2.0)),
      std::make_shared<DampedSpring>(0, 3, 1.0, uniform(1.0, 50.0), uniform(0.1, 2.0)),
      std::make_shared<LennardJones>(uniform(0.5, 2.0), 0.8)};
  for (const auto& force : forces) {
    INFO(force->name());
    Mat3X alone = Mat3X::Zero(3, n);
    force->accumulate(s, Points(alone.data(), 3, n));
    const Mat3X before = randomPoints(n, 5.0);  // what the forces added earlier left there
    Mat3X F = before;
    force->accumulate(s, Points(F.data(), 3, n));
    // The same additions starting from other values: round-off relative to both.
    CHECK((F - before - alone).norm() < 1e-13 * (before.norm() + alone.norm()));
  }
}

TEST_CASE("forces: Jacobians add to matrices that already hold other forces' Jacobians", "[lab01][pts=1][sec=1]") {
  const Index n = 3;
  const VecX m = VecX::Ones(n);
  Mat3X x(3, n);
  x << 0, 1, 2, 0, 0, 0, 0, 0, 0;
  x += randomPoints(n, 0.2);
  const Mat3X v = randomPoints(n, 1.0);
  const ParticleView s{ConstPoints(x.data(), 3, n), ConstPoints(v.data(), 3, n), m};
  // Two springs sharing particle 1, drag and gravity, all into one pair of matrices.
  const std::vector<std::shared_ptr<const Force>> forces = {
      std::make_shared<DampedSpring>(0, 1, uniform(0.5, 1.5), uniform(1.0, 50.0), uniform(0.1, 2.0)),
      std::make_shared<DampedSpring>(1, 2, uniform(0.5, 1.5), uniform(1.0, 50.0), uniform(0.1, 2.0)),
      std::make_shared<ViscousDrag>(uniform(0.1, 2.0)), std::make_shared<UniformGravity>(randomVec3(10.0))};
  MatX sum_x(9, 9), sum_v(9, 9);  // what earlier forces' Jacobians left there
  for (Index k = 0; k < 81; ++k) {
    sum_x.data()[k] = uniform(-10.0, 10.0);
    sum_v.data()[k] = uniform(-10.0, 10.0);
  }
  MatX dF_dx = sum_x, dF_dv = sum_v;
  for (const auto& force : forces) {
    MatX alone_x = MatX::Zero(9, 9), alone_v = MatX::Zero(9, 9);
    REQUIRE(force->addJacobians(s, alone_x, alone_v));
    sum_x += alone_x;
    sum_v += alone_v;
    REQUIRE(force->addJacobians(s, dF_dx, dF_dv));
  }
  // The same sums in another order: round-off relative to entries up to ~100.
  CHECK((dF_dx - sum_x).norm() < 1e-12 * sum_x.norm());
  CHECK((dF_dv - sum_v).norm() < 1e-12 * sum_v.norm());
}

TEST_CASE("forces: N-body potential is softened like its force", "[lab01][pts=1][sec=1]") {
  const Index n = 4;
  VecX m(n);
  for (Index i = 0; i < n; ++i) m[i] = uniform(0.5, 3.0);
  const Mat3X x = randomPoints(n, 1.0), v = Mat3X::Zero(3, n);
  const double G = uniform(0.5, 2.0), soft = uniform(0.3, 0.6);  // a softening that matters
  double U = 0.0;
  for (Index i = 0; i < n; ++i) {
    for (Index j = i + 1; j < n; ++j) {
      U -= G * m[i] * m[j] / std::sqrt((x.col(i) - x.col(j)).squaredNorm() + soft * soft);
    }
  }
  const ParticleView s{ConstPoints(x.data(), 3, n), ConstPoints(v.data(), 3, n), m};
  // The formula in another order: round-off only.
  CHECK(NBodyGravity(G, soft).potential(s) == Approx(U).epsilon(1e-13));
}
