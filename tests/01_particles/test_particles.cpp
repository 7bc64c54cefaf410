// Lab 1 graded tests: the particle system's derivative, N-body physics and the diagnostics.
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// A force written here that pushes particle i by a fixed random vector c_i + B x_i: the
// derivative test then depends on nothing the student wrote but the derivative itself.
class TestForce final : public Force {
 public:
  explicit TestForce(Index n) : c_(Mat3X(3, n)), B_(randomRotation()), U_(uniform(-5.0, 5.0)) {
    for (Index i = 0; i < n; ++i) c_.col(i) = randomVec3(3.0);
  }
  std::string name() const override { return "test force"; }
  void accumulate(const ParticleView& s, Points F) const override { F += c_ + B_ * s.x; }
  double potential(const ParticleView&) const override { return U_; }
  Mat3X expected(const Mat3X& x) const { return c_ + B_ * x; }

 private:
  Mat3X c_;
  Mat3 B_;
  double U_;
};

VecX randomMasses(Index n) {
  VecX m(n);
  for (Index i = 0; i < n; ++i) m[i] = uniform(0.5, 3.0);
  return m;
}

}  // namespace

TEST_CASE("particles: the derivative is [v, F/m] with every force summed", "[lab01][pts=2][sec=2]") {
  const Index n = 4;
  ParticleSystem sys(randomMasses(n));
  auto f1 = std::make_shared<TestForce>(n);
  auto f2 = std::make_shared<TestForce>(n);
  sys.addForce(f1);
  sys.addForce(f2);
  const Mat3X x = randomPoints(n, 2.0), v = randomPoints(n, 1.0);
  const VecX X = sys.makeState(x, v);
  VecX dX;
  sys.derivative(X, dX);
  const Mat3X F = f1->expected(x) + f2->expected(x);
  Mat3X a(3, n);
  for (Index i = 0; i < n; ++i) a.col(i) = F.col(i) / sys.masses()[i];
  // Sums and one division per entry: round-off only.
  CHECK((positions(dX) - v).norm() < 1e-14 * v.norm());
  CHECK((velocities(dX) - a).norm() < 1e-13 * a.norm());
}

TEST_CASE("particles: a pinned particle (infinite mass) gets no acceleration", "[lab01][pts=1][sec=2]") {
  VecX m = randomMasses(3);
  m[1] = std::numeric_limits<double>::infinity();
  ParticleSystem sys(m);
  auto force = std::make_shared<TestForce>(3);
  sys.addForce(force);
  const Mat3X x = randomPoints(3, 1.0);
  VecX dX;
  sys.derivative(sys.makeState(x, Mat3X::Zero(3, 3)), dX);
  CHECK(velocities(dX).col(1).norm() == 0.0);  // exactly: F times 1/inf
  CHECK(velocities(dX).col(0).isApprox(force->expected(x).col(0) / m[0], 1e-13));
}

TEST_CASE("N-body: total momentum is conserved to round-off", "[lab01][pts=2][sec=1]") {
  const Index n = 8;
  const VecX m = randomMasses(n);
  const OracleParticles sys(m, {std::make_shared<NBodyGravity>(1.0, 0.05)});
  VecX X(6 * n);
  X << randomPoints(n, 3.0).reshaped(), randomPoints(n, 0.5).reshaped();
  const Vec3 P0 = sys.momentum(X);
  double scale = 0.0;  // sum of |m v|: the size round-off is measured against
  oracleRK4(sys, X, 1e-3, 2000);
  for (Index i = 0; i < n; ++i) scale += m[i] * velocities(X).col(i).norm();
  // Pair forces cancel exactly in exact arithmetic; 2000 steps of round-off leave ~1e-13.
  CHECK((sys.momentum(X) - P0).norm() < 1e-11 * scale);
}

TEST_CASE("N-body: a two-body circular orbit keeps its radius", "[lab01][pts=2][sec=1]") {
  const double m1 = uniform(1.0, 5.0), m2 = uniform(0.1, 1.0), G = 1.0, d = uniform(1.0, 2.0);
  const double soft = 0.01;
  // Circular orbit about the centre of mass: each body's centripetal force m w^2 r equals the
  // softened attraction G m1 m2 d / (d^2 + eps^2)^(3/2).
  const double w = std::sqrt(G * (m1 + m2) * d / std::pow(d * d + soft * soft, 1.5) / d);
  const double r1 = d * m2 / (m1 + m2), r2 = d * m1 / (m1 + m2);
  Mat3X x(3, 2), v(3, 2);
  x << -r1, r2, 0, 0, 0, 0;
  v << 0, 0, -w * r1, w * r2, 0, 0;
  const OracleParticles sys(Eigen::Vector2d(m1, m2), {std::make_shared<NBodyGravity>(G, soft)});
  VecX X(12);
  X << x.reshaped(), v.reshaped();
  const double period = 2.0 * M_PI / w;
  const long steps = 2000;
  double worst = 0.0;
  for (int k = 0; k < 10; ++k) {
    oracleRK4(sys, X, period / steps, steps / 10);
    worst = std::max(worst, std::abs((positions(X).col(0) - positions(X).col(1)).norm() - d) / d);
  }
  // RK4 with 2000 steps per orbit has error ~1e-12; a wrong force law changes the radius by O(1).
  CHECK(worst < 1e-8);
}

TEST_CASE("diagnostics: kinetic energy is the sum of m v^2 / 2", "[lab01][pts=1][sec=4]") {
  const VecX m = randomMasses(5);
  const ParticleSystem sys(m);
  const Mat3X v = randomPoints(5, 2.0);
  const VecX X = sys.makeState(randomPoints(5, 1.0), v);
  double T = 0.0;
  for (Index i = 0; i < 5; ++i) T += 0.5 * m[i] * v.col(i).squaredNorm();
  CHECK(kineticEnergy(sys, X) == Approx(T).epsilon(1e-13));  // round-off only
}

TEST_CASE("diagnostics: potential energy sums every force's potential", "[lab01][pts=1][sec=4]") {
  ParticleSystem sys(randomMasses(4));
  const int count = 2 + static_cast<int>(uniform(0.0, 3.0));  // 2 to 4: several always add up
  double expected = 0.0;
  for (int k = 0; k < count; ++k) {
    auto force = std::make_shared<TestForce>(4);
    expected += force->potential(sys.view(VecX::Zero(24)));
    sys.addForce(force);
  }
  const VecX X = sys.makeState(randomPoints(4, 2.0), Mat3X::Zero(3, 4));
  CHECK(potentialEnergy(sys, X) == Approx(expected).epsilon(1e-13));  // a sum: round-off only
}

TEST_CASE("diagnostics: linear momentum is the sum of m v", "[lab01][pts=1][sec=4]") {
  const VecX m = randomMasses(6);
  const ParticleSystem sys(m);
  const Mat3X v = randomPoints(6, 2.0);
  const VecX X = sys.makeState(randomPoints(6, 1.0), v);
  CHECK((linearMomentum(sys, X) - v * m).norm() < 1e-13 * (v * m).norm() + 1e-15);
}

TEST_CASE("diagnostics: angular momentum is the sum of x cross m v", "[lab01][pts=1][sec=4]") {
  const VecX m = randomMasses(6);
  const ParticleSystem sys(m);
  const Mat3X x = randomPoints(6, 2.0), v = randomPoints(6, 2.0);
  Vec3 L = Vec3::Zero();
  for (Index i = 0; i < 6; ++i) L += m[i] * x.col(i).cross(v.col(i));
  CHECK((angularMomentum(sys, sys.makeState(x, v)) - L).norm() < 1e-13 * L.norm());
}
