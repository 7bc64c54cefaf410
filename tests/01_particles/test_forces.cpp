// Lab 1 graded tests: each force against its formula (an independent expression written here)
// and against the negative gradient of its own potential energy.
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

struct Cloud {
  VecX m;
  Mat3X x;
  Mat3X v;
  ParticleView view() const {
    return ParticleView{ConstPoints(x.data(), 3, x.cols()), ConstPoints(v.data(), 3, v.cols()), m};
  }
};

// n particles with masses in [0.5, 2], spread over a box of half-width `spread`, kept at least
// `min_gap` apart so that pair forces stay moderate.
Cloud randomCloud(Index n, double spread, double min_gap) {
  Cloud c{VecX(n), Mat3X(3, n), Mat3X(3, n)};
  for (Index i = 0; i < n; ++i) {
    c.m[i] = uniform(0.5, 2.0);
    bool far_enough = false;
    while (!far_enough) {
      c.x.col(i) = randomVec3(spread);
      far_enough = true;
      for (Index j = 0; j < i; ++j) far_enough &= (c.x.col(i) - c.x.col(j)).norm() > min_gap;
    }
    c.v.col(i) = randomVec3(1.0);
  }
  return c;
}

Mat3X forceOf(const Force& force, const Cloud& c) {
  Mat3X F = Mat3X::Zero(3, c.x.cols());
  force.accumulate(c.view(), Points(F.data(), 3, F.cols()));
  return F;
}

// -dU/dx by central differences on the student's potential(); error O(eps^2) ~ 1e-10 relative.
Mat3X minusGradient(const Force& force, Cloud c) {
  Mat3X G(3, c.x.cols());
  const double eps = 1e-5;
  for (Index i = 0; i < c.x.cols(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double x0 = c.x(k, i);
      c.x(k, i) = x0 + eps;
      const double up = force.potential(c.view());
      c.x(k, i) = x0 - eps;
      const double down = force.potential(c.view());
      c.x(k, i) = x0;
      G(k, i) = -(up - down) / (2.0 * eps);
    }
  }
  return G;
}

// Relative matrix error, so a tolerance means the same for large and small forces.
double relative(const Mat3X& a, const Mat3X& b) { return (a - b).norm() / std::max(b.norm(), 1e-300); }

}  // namespace

TEST_CASE("forces: uniform gravity is m g, nothing on a pinned particle, and minus the gradient of its potential", "[lab01][pts=1][sec=1]") {
  Cloud c = randomCloud(5, 2.0, 0.0);
  c.m[3] = std::numeric_limits<double>::infinity();  // pinned: m g would be infinite (or NaN)
  const Vec3 g = randomVec3(10.0);
  const UniformGravity gravity(g);
  Mat3X expected(3, 5);
  for (Index i = 0; i < 5; ++i) expected.col(i) = i == 3 ? Vec3::Zero() : Vec3(c.m[i] * g);
  // Both are exact up to round-off; central differences of a linear potential are exact too.
  CHECK(relative(forceOf(gravity, c), expected) < 1e-12);
  CHECK(relative(minusGradient(gravity, c), expected) < 1e-8);
}

TEST_CASE("forces: N-body gravity matches Newton's law and minus the gradient of its potential", "[lab01][pts=2][sec=1]") {
  const Cloud c = randomCloud(6, 2.0, 0.3);
  const double G = uniform(0.5, 2.0), soft = uniform(0.0, 0.1);
  const NBodyGravity gravity(G, soft);
  Mat3X expected = Mat3X::Zero(3, 6);
  for (Index i = 0; i < 6; ++i) {
    for (Index j = 0; j < 6; ++j) {
      if (i == j) continue;
      const Vec3 d = c.x.col(j) - c.x.col(i);
      expected.col(i) += G * c.m[i] * c.m[j] * d / std::pow(d.squaredNorm() + soft * soft, 1.5);
    }
  }
  const Mat3X F = forceOf(gravity, c);
  CHECK(relative(F, expected) < 1e-12);                        // same formula: round-off only
  CHECK(relative(minusGradient(gravity, c), expected) < 1e-7);  // central differences: O(eps^2)
  // Equal and opposite pair forces sum to zero (round-off relative to the largest force).
  CHECK(F.rowwise().sum().norm() < 1e-13 * F.colwise().norm().maxCoeff() * 6);
}

TEST_CASE("forces: N-body gravity at both ends of its softening: eps = 0 is Newton's law, coincident softened particles feel no pull", "[lab01][pts=1][sec=1]") {
  // Fixed masses and positions. Softened (eps = 0.5), particles 0 and 1 coincide: their pair
  // term G m m d / (|d|^2 + eps^2)^(3/2) is 0 and their potential -G m m / eps is finite.
  // Unsoftened (eps = 0, the least allowed), particle 1 is moved off particle 0.
  Cloud c{Eigen::Vector3d(1.0, 2.0, 3.0), Mat3X(3, 3), Mat3X::Zero(3, 3)};
  c.x << 0.5, 0.5, -1.0,  //
      -0.25, -0.25, 1.0,  //
      1.0, 1.0, 3.0;
  const double G = 1.5;
  for (const double soft : {0.5, 0.0}) {
    CAPTURE(soft);
    if (soft == 0.0) c.x.col(1) += Vec3(0.0, 0.0, 1.0);
    // The formula term by term, written here.
    Mat3X expected = Mat3X::Zero(3, 3);
    double U = 0.0;
    for (Index i = 0; i < 3; ++i) {
      for (Index j = 0; j < 3; ++j) {
        if (i == j) continue;
        const Vec3 d = c.x.col(j) - c.x.col(i);
        expected.col(i) += G * c.m[i] * c.m[j] * d / std::pow(d.squaredNorm() + soft * soft, 1.5);
        if (i < j) U -= G * c.m[i] * c.m[j] / std::sqrt(d.squaredNorm() + soft * soft);
      }
    }
    const NBodyGravity gravity(G, soft);
    const Mat3X F = forceOf(gravity, c);
    REQUIRE(F.allFinite());
    CHECK(relative(F, expected) < 1e-13);  // the same formula in another order: round-off only
    CHECK(gravity.potential(c.view()) == Approx(U).epsilon(1e-13));
  }
}

TEST_CASE("forces: damped spring by hand: stretched pulls, compressed pushes, damping resists approach and separation", "[lab01][pts=1][sec=1]") {
  // A spring along x: x_a = 0, x_b = (2, 0, 0), so l = (-2, 0, 0), |l| = 2, u = (-1, 0, 0);
  // ks = 10, kd = 0.5. f_a = -[ks (|l| - r) + kd l_dot.u] u = (ks (2 - r) + kd l_dot.u, 0, 0).
  // Every number is a short binary fraction: the arithmetic is exact, 1e-14 is only a guard.
  Cloud c{VecX::Ones(2), Mat3X::Zero(3, 2), Mat3X::Zero(3, 2)};
  c.x(0, 1) = 2.0;
  struct Case {
    double rest, va;  // rest length; particle a's x velocity (b is still), so l_dot.u = -va
    double fa;        // expected x component of f_a
    double geometric; // expected s / |l|, the transverse diagonal entries of -df_a/dl
  };
  for (const Case& k : {Case{1.0, 1.0, 9.5, 4.75},       // stretched by 1, a approaching b
                        Case{1.0, -1.0, 10.5, 5.25},     // stretched by 1, a moving away
                        Case{3.0, 1.0, -10.5, -5.25},    // compressed by 1, approaching
                        Case{3.0, -1.0, -9.5, -4.75}}) { // compressed by 1, moving away
    CAPTURE(k.rest, k.va);
    c.v(0, 0) = k.va;
    const DampedSpring spring(0, 1, k.rest, 10.0, 0.5);
    Mat3X expected = Mat3X::Zero(3, 2);
    expected(0, 0) = k.fa;
    expected(0, 1) = -k.fa;
    CHECK((forceOf(spring, c) - expected).norm() < 1e-14);
    CHECK(spring.potential(c.view()) == Approx(5.0).epsilon(1e-14));  // 1/2 ks (1)^2 either way
    // The Jacobians: df_a/dl = -[ks u u^T + (s / |l|) P] with P = diag(0, 1, 1) (the damping's
    // u l_dot^T P term vanishes, l_dot being along u), df_a/dl_dot = -kd u u^T.
    MatX dF_dx = MatX::Zero(6, 6), dF_dv = MatX::Zero(6, 6);
    REQUIRE(spring.addJacobians(c.view(), dF_dx, dF_dv));
    const Mat3 df_dl = -Vec3(10.0, k.geometric, k.geometric).asDiagonal().toDenseMatrix();
    const Mat3 df_dldot = -Vec3(0.5, 0.0, 0.0).asDiagonal().toDenseMatrix();
    MatX expected_x(6, 6), expected_v(6, 6);
    expected_x << df_dl, -df_dl, -df_dl, df_dl;
    expected_v << df_dldot, -df_dldot, -df_dldot, df_dldot;
    CHECK((dF_dx - expected_x).norm() < 1e-14);
    CHECK((dF_dv - expected_v).norm() < 1e-14);
  }
}

TEST_CASE("forces: viscous drag is -d v and stores no energy", "[lab01][pts=1][sec=1]") {
  const Cloud c = randomCloud(4, 1.0, 0.0);
  const double d = uniform(0.1, 3.0);
  const ViscousDrag drag(d);
  CHECK(relative(forceOf(drag, c), -d * c.v) < 1e-14);  // a single product: round-off only
  CHECK(drag.potential(c.view()) == 0.0);               // dissipative: no potential at all
  MatX dF_dx = MatX::Zero(12, 12), dF_dv = MatX::Zero(12, 12);
  REQUIRE(drag.addJacobians(c.view(), dF_dx, dF_dv));
  CHECK((dF_dv + d * MatX::Identity(12, 12)).norm() < 1e-14);
  CHECK(dF_dx.norm() == 0.0);
}

TEST_CASE("forces: damped spring follows the lecture's formula and its potential", "[lab01][pts=2][sec=1]") {
  const Cloud c = randomCloud(3, 1.0, 0.2);
  const Vec3 l = c.x.col(2) - c.x.col(0), l_dot = c.v.col(2) - c.v.col(0);
  // Stretched or compressed by at least 20 %: near |l| = rest the force vanishes while the
  // difference quotient's O(eps^2) error does not, and the relative check would measure noise.
  const double rest = l.norm() * (uniform(0.0, 1.0) < 0.5 ? uniform(0.3, 0.8) : uniform(1.2, 2.0));
  const double ks = uniform(1.0, 100.0), kd = uniform(0.0, 5.0);
  const DampedSpring spring(2, 0, rest, ks, kd);
  const Vec3 f_a = -(ks * (l.norm() - rest) + kd * l_dot.dot(l) / l.norm()) * l / l.norm();
  Mat3X expected = Mat3X::Zero(3, 3);
  expected.col(2) = f_a;
  expected.col(0) = -f_a;
  CHECK(relative(forceOf(spring, c), expected) < 1e-12);
  // The potential 1/2 ks (|l| - r)^2 explains the elastic part; without damping the force is
  // minus its gradient (central differences, O(eps^2) ~ 1e-9 relative).
  const DampedSpring undamped(2, 0, rest, ks, 0.0);
  CHECK(relative(minusGradient(undamped, c), forceOf(undamped, c)) < 1e-7);
  CHECK(undamped.potential(c.view()) == Approx(0.5 * ks * std::pow(l.norm() - rest, 2)).epsilon(1e-12));
}

TEST_CASE("forces: damped spring Jacobians match central differences", "[lab01][pts=2][sec=1]") {
  Cloud c = randomCloud(3, 1.0, 0.2);
  const DampedSpring spring(0, 2, uniform(0.1, 1.0), uniform(1.0, 100.0), uniform(0.1, 5.0));
  MatX dF_dx = MatX::Zero(9, 9), dF_dv = MatX::Zero(9, 9);
  REQUIRE(spring.addJacobians(c.view(), dF_dx, dF_dv));
  MatX fd_x(9, 9), fd_v(9, 9);
  const double eps = 1e-6;
  for (Index j = 0; j < 9; ++j) {
    for (Mat3X* field : {&c.x, &c.v}) {
      double& entry = field->data()[j];
      const double saved = entry;
      entry = saved + eps;
      const Mat3X up = forceOf(spring, c);
      entry = saved - eps;
      const Mat3X down = forceOf(spring, c);
      entry = saved;
      (field == &c.x ? fd_x : fd_v).col(j) = (up - down).reshaped() / (2.0 * eps);
    }
  }
  // Central differences are accurate to O(eps^2) ~ 1e-12 times the curvature; 1e-6 relative
  // passes any correct Jacobian and fails one missing a term (those are O(1) relative).
  CHECK((dF_dx - fd_x).norm() < 1e-6 * fd_x.norm());
  CHECK((dF_dv - fd_v).norm() < 1e-6 * fd_v.norm());
}

TEST_CASE("forces: Lennard-Jones matches its formula and minus the gradient of its potential", "[lab01][pts=2][sec=1]") {
  const double sigma = uniform(0.5, 1.0), eps_lj = uniform(0.5, 2.0);
  const Cloud c = randomCloud(5, 1.5, 0.9 * sigma);
  const LennardJones lj(eps_lj, sigma);
  Mat3X expected = Mat3X::Zero(3, 5);
  double U = 0.0;
  for (Index i = 0; i < 5; ++i) {
    for (Index j = 0; j < 5; ++j) {
      if (i == j) continue;
      const Vec3 d = c.x.col(i) - c.x.col(j);
      const double r = d.norm(), s6 = std::pow(sigma / r, 6);
      expected.col(i) += 24.0 * eps_lj / r * (2.0 * s6 * s6 - s6) * d / r;
      if (i < j) U += 4.0 * eps_lj * (s6 * s6 - s6);
    }
  }
  CHECK(relative(forceOf(lj, c), expected) < 1e-11);  // same formula, other rounding
  CHECK(lj.potential(c.view()) == Approx(U).epsilon(1e-11));
  CHECK(relative(minusGradient(lj, c), expected) < 1e-6);  // central differences of a steep U
}
