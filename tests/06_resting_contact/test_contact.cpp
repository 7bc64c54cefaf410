// Lab 6 graded tests of the contact problem: the matrix A against J M^-1 J^T, Baraff's b against
// the separation's second derivative found by finite differences, the velocity-level b by hand,
// and the friction pyramid's LCP against a sliding contact solved by hand.
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "physlab/error.hpp"
#include "physlab/resting.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

namespace {

Mat3 cross(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// A moving body with random mass, inertia, pose and velocities; its world inertia in I.
ContactBody randomBody(Mat3& I) {
  const Mat3 R = randomRotation();
  I = R * Vec3(uniform(0.2, 2.0), uniform(0.2, 2.0), uniform(0.2, 2.0)).asDiagonal() * R.transpose();
  ContactBody body;
  body.x = randomVec3(1.0);
  body.v = randomVec3(2.0);
  body.omega = randomVec3(2.0);
  body.inv_mass = 1.0 / uniform(0.2, 5.0);
  body.I_inv_world = I.inverse();
  return body;
}

ContactBody fixedBody(const Vec3& x) {
  ContactBody body;
  body.x = x;
  return body;
}

// J M^-1 J^T from the 6-per-body Jacobian, computed here apart from the student's code.
MatX jacobianProduct(const std::vector<ContactBody>& bodies, const std::vector<ContactRow>& rows) {
  const Index n = static_cast<Index>(bodies.size());
  MatX J = MatX::Zero(static_cast<Index>(rows.size()), 6 * n), M_inv = MatX::Zero(6 * n, 6 * n);
  for (Index i = 0; i < static_cast<Index>(rows.size()); ++i) {
    const ContactRow& row = rows[i];
    J.block<1, 3>(i, 6 * row.a) += row.d.transpose();
    J.block<1, 3>(i, 6 * row.a + 3) += (row.p - bodies[row.a].x).cross(row.d).transpose();
    J.block<1, 3>(i, 6 * row.b) -= row.d.transpose();
    J.block<1, 3>(i, 6 * row.b + 3) -= (row.p - bodies[row.b].x).cross(row.d).transpose();
  }
  for (Index k = 0; k < n; ++k) {
    M_inv.block<3, 3>(6 * k, 6 * k) = bodies[k].inv_mass * Mat3::Identity();
    M_inv.block<3, 3>(6 * k + 3, 6 * k + 3) = bodies[k].I_inv_world;
  }
  return J * M_inv * J.transpose();
}

}  // namespace

TEST_CASE("contact matrix: A equals J M^-1 J^T for random rows among moving and fixed bodies", "[lab06][pts=3][sec=1]") {
  std::vector<ContactBody> bodies;
  Mat3 I;
  for (int k = 0; k < 4; ++k) bodies.push_back(randomBody(I));
  bodies.push_back(fixedBody(randomVec3(1.0)));
  std::vector<ContactRow> rows;
  for (int i = 0; i < 7; ++i) {
    const int a = static_cast<int>(uniform(0, 5)) % 5;
    const int b = (a + 1 + static_cast<int>(uniform(0, 4)) % 4) % 5;
    rows.push_back({a, b, randomVec3(1.0), randomVec3(1.0).normalized()});
  }
  // Rows 5 and 6 on bodies of their own: their coupling with rows on other bodies is exactly 0
  rows[5] = {0, 1, randomVec3(1.0), randomVec3(1.0).normalized()};
  rows[6] = {2, 3, randomVec3(1.0), randomVec3(1.0).normalized()};
  const MatX A = contactMatrix(bodies, rows), expected = jacobianProduct(bodies, rows);
  REQUIRE(A.rows() == 7);
  REQUIRE(A.cols() == 7);
  // The same sums of products in another order: round-off relative to the largest entry.
  CHECK((A - expected).cwiseAbs().maxCoeff() <= 1e-12 * expected.cwiseAbs().maxCoeff());
  CHECK(A(5, 6) == 0.0);
  CHECK(A(6, 5) == 0.0);
  // Symmetric as J M^-1 J^T is; a_ij and a_ji computed apart may differ in the last bit.
  CHECK((A - A.transpose()).cwiseAbs().maxCoeff() <= 1e-14 * expected.cwiseAbs().maxCoeff());
  CHECK_THROWS_AS(contactMatrix(bodies, {{0, 5, Vec3::Zero(), Vec3::UnitZ()}}), InvalidInput);
  CHECK_THROWS_AS(contactMatrix(bodies, {{-1, 0, Vec3::Zero(), Vec3::UnitZ()}}), InvalidInput);
  CHECK(contactMatrix(bodies, {}).size() == 0);
}

TEST_CASE("contact matrix: a sphere on the ground, hand computed", "[lab06][pts=1][sec=1]") {
  const double m = uniform(0.5, 3.0), I = uniform(0.1, 1.0), s = uniform(0.05, 0.3), R = 0.5;
  ContactBody sphere;
  sphere.x = Vec3(0.0, 0.0, R);
  sphere.inv_mass = 1.0 / m;
  sphere.I_inv_world = Mat3::Identity() / I;
  const std::vector<ContactBody> bodies = {sphere, fixedBody(Vec3::Zero())};
  // Under the centre nothing turns: a = 1/m. A point off to the side turns it: a = 1/m + s^2/I.
  const MatX A = contactMatrix(bodies, {{0, 1, Vec3::Zero(), Vec3::UnitZ()}, {0, 1, Vec3(s, 0, 0), Vec3::UnitZ()}});
  // A few products of exact inputs: round-off.
  CHECK(A(0, 0) == Approx(1.0 / m).epsilon(1e-14));
  CHECK(A(1, 1) == Approx(1.0 / m + s * s / I).epsilon(1e-14));
  CHECK(A(0, 1) == Approx(1.0 / m).epsilon(1e-14));
}

TEST_CASE("contact matrix: two boxes stacked on the ground, hand computed: a body that is B in one row and A in another", "[lab06][pts=1][sec=1]") {
  // Bodies: the ground (fixed), a lower box 1 and an upper box 2, each with an isotropic inertia
  // I_k. Rows with vertical normals n_i = sigma_i z: the lower box on the ground (1, 0), the upper
  // on the lower (2, 1) at two points (rows sharing both bodies), and once the other way round
  // (lower box as A, normal -z). For vertical normals (r_j x n_j) . (r_i x n_i) is sigma_i sigma_j
  // times the dot product of the horizontal offsets rho = (p - x)_xy, so by hand
  //   a_ij = sigma_i sigma_j sum_k s_ki s_kj (1/m_k + rho_ki . rho_kj / I_k),
  // s_ki = +1 when body k is row i's A, -1 when its B. Box 1 is A in the ground rows and B in the
  // stack rows (the reversed row: A again): every row pair exercises both signs.
  const double m1 = uniform(0.5, 3.0), m2 = uniform(0.5, 3.0), I1 = uniform(0.1, 1.0), I2 = uniform(0.1, 1.0);
  ContactBody ground, lower, upper;
  lower.x = Vec3(uniform(-1.0, 1.0), uniform(-1.0, 1.0), 0.1);
  lower.inv_mass = 1.0 / m1;
  lower.I_inv_world = Mat3::Identity() / I1;
  upper.x = lower.x + Vec3(uniform(-0.1, 0.1), uniform(-0.1, 0.1), 0.2);
  upper.inv_mass = 1.0 / m2;
  upper.I_inv_world = Mat3::Identity() / I2;
  const std::vector<ContactBody> bodies = {ground, lower, upper};
  auto at = [&](double height) -> Vec3 { return lower.x + Vec3(uniform(-0.3, 0.3), uniform(-0.2, 0.2), height); };
  const std::vector<ContactRow> rows = {{1, 0, at(-0.1), Vec3::UnitZ()},
                                        {2, 1, at(0.1), Vec3::UnitZ()},
                                        {2, 1, at(0.1), Vec3::UnitZ()},
                                        {1, 2, at(0.1), -Vec3::UnitZ()},
                                        {1, 0, at(-0.1), Vec3::UnitZ()}};
  const Index n = static_cast<Index>(rows.size());
  const double inv_mass[3] = {0.0, 1.0 / m1, 1.0 / m2}, inv_inertia[3] = {0.0, 1.0 / I1, 1.0 / I2};
  MatX expected = MatX::Zero(n, n);
  for (Index i = 0; i < n; ++i) {
    for (Index j = 0; j < n; ++j) {
      const ContactRow &ri = rows[static_cast<std::size_t>(i)], &rj = rows[static_cast<std::size_t>(j)];
      for (int k = 1; k <= 2; ++k) {
        const double s_i = ri.a == k ? 1.0 : (ri.b == k ? -1.0 : 0.0), s_j = rj.a == k ? 1.0 : (rj.b == k ? -1.0 : 0.0);
        const Vec3 rho_i = (ri.p - bodies[static_cast<std::size_t>(k)].x).cwiseProduct(Vec3(1.0, 1.0, 0.0));
        const Vec3 rho_j = (rj.p - bodies[static_cast<std::size_t>(k)].x).cwiseProduct(Vec3(1.0, 1.0, 0.0));
        expected(i, j) += ri.d.z() * rj.d.z() * s_i * s_j * (inv_mass[k] + inv_inertia[k] * rho_i.dot(rho_j));
      }
    }
  }
  const MatX A = contactMatrix(bodies, rows);
  REQUIRE(A.rows() == n);
  REQUIRE(A.cols() == n);
  INFO("A\n" << A << "\nexpected\n" << expected);
  // A few products of numbers of order 1 in another order: round-off relative to the largest entry
  CHECK((A - expected).cwiseAbs().maxCoeff() <= 1e-13 * expected.cwiseAbs().maxCoeff());
}

TEST_CASE("Baraff's b: the second derivative of the separation with no contact force", "[lab06][pts=3][sec=2]") {
  // Two moving bodies (or one against a fixed body) with applied forces and torques. Their
  // motion to second order in t, x(t) = x + v t + F/(2m) t^2 and R(t) = (1 + t W + t^2/2 (W' + W^2)) R,
  // has the true second derivatives at t = 0, so the central difference of
  // d(t) = n(t) . (p_a(t) - p_b(t)) with n and the points carried by the bodies gives d''(0).
  for (const bool b_fixed : {false, true}) {
    Mat3 I_a, I_b;
    std::vector<ContactBody> bodies = {randomBody(I_a), randomBody(I_b)};
    if (b_fixed) {
      bodies[1] = fixedBody(bodies[1].x);
      I_b = Mat3::Zero();
    }
    std::vector<AppliedLoads> loads(2);
    for (int k = 0; k < 2; ++k) {
      loads[k].F = randomVec3(5.0);
      loads[k].tau = randomVec3(2.0);
      loads[k].L = (k == 0 ? I_a : I_b) * bodies[k].omega;
    }
    const Vec3 p = randomVec3(1.0), n = randomVec3(1.0).normalized();
    auto motion = [&](int k, double t, const Vec3& body_point) -> Vec3 {
      const ContactBody& body = bodies[k];
      const Vec3 omega_dot = body.I_inv_world * (loads[k].tau + loads[k].L.cross(body.omega));
      const Mat3 W = cross(body.omega);
      const Mat3 turn = Mat3::Identity() + t * W + 0.5 * t * t * (cross(omega_dot) + W * W);
      return body.x + t * body.v + 0.5 * t * t * body.inv_mass * loads[k].F + turn * (body_point - body.x);
    };
    auto normal = [&](double t) -> Vec3 {
      const ContactBody& B = bodies[1];
      const Vec3 omega_dot = B.I_inv_world * (loads[1].tau + loads[1].L.cross(B.omega));
      const Mat3 W = cross(B.omega);
      return (Mat3::Identity() + t * W + 0.5 * t * t * (cross(omega_dot) + W * W)) * n;
    };
    auto d = [&](double t) { return normal(t).dot(motion(0, t, p) - motion(1, t, p)); };
    // d(t) is a polynomial of degree 4, so the central difference's error is exactly
    // delta^2 d''''(0) / 12, which Richardson's (4 D(delta / 2) - D(delta)) / 3 removes.
    auto central = [&](double delta) { return (d(delta) - 2.0 * d(0.0) + d(-delta)) / (delta * delta); };
    const double d_ddot = (4.0 * central(0.005) - central(0.01)) / 3.0;
    const VecX b = accelerationBias(bodies, loads, {{0, 1, p, n}});
    REQUIRE(b.size() == 1);
    // What is left is round-off, eps |d| / delta^2, about 1e-10 of |d| ~ 1.
    CHECK(b(0) == Approx(d_ddot).epsilon(1e-8).margin(1e-7));
  }
}

TEST_CASE("Baraff's b: a body at rest on the ground feels only gravity; loads must match the bodies", "[lab06][pts=1][sec=2]") {
  ContactBody box;
  box.x = Vec3(0.0, 0.0, 0.1);
  box.inv_mass = 0.5;
  box.I_inv_world = Mat3::Identity() * 3.0;
  const std::vector<ContactBody> bodies = {box, fixedBody(Vec3::Zero())};
  std::vector<AppliedLoads> loads(2);
  loads[0].F = Vec3(0.0, 0.0, -2.0 * 9.81);
  const Vec3 corner(0.3, 0.2, 0.0);
  const VecX b = accelerationBias(bodies, loads, {{0, 1, corner, Vec3::UnitZ()}, {0, 1, -corner, Vec3::UnitZ()}});
  // F / m along the normal, nothing turning: exact up to one rounding.
  CHECK(b(0) == Approx(-9.81).epsilon(1e-15));
  CHECK(b(1) == Approx(-9.81).epsilon(1e-15));
  loads.pop_back();
  CHECK_THROWS_AS(accelerationBias(bodies, loads, {{0, 1, corner, Vec3::UnitZ()}}), InvalidInput);
}

TEST_CASE("velocity bias: relative velocity along the row less the Baumgarte push, hand computed", "[lab06][pts=2][sec=7]") {
  ContactBody ball;
  ball.x = Vec3(0.0, 0.0, 0.1);
  ball.v = Vec3(uniform(0.5, 2.0), 0.0, -uniform(0.1, 1.0));
  ball.omega = Vec3(0.0, uniform(-3.0, 3.0), 0.0);
  ball.inv_mass = 1.0;
  ball.I_inv_world = Mat3::Identity() * 250.0;
  const std::vector<ContactBody> bodies = {ball, fixedBody(Vec3::Zero())};
  const Vec3 p = Vec3::Zero();
  const std::vector<ContactRow> rows = {{0, 1, p, Vec3::UnitZ()}, {0, 1, p, Vec3::UnitX()}};
  const double h = 0.01, beta = 0.2, slop = 0.002, depth = uniform(0.003, 0.02);
  const VecX b = velocityBias(bodies, rows, Vec3(depth, 0.0, 0.0).head<2>(), h, beta, slop);
  // The contact point moves at v + omega x (p - x); omega_y turns it along x by omega_y * 0.1.
  const double slide = ball.v.x() + ball.omega.y() * (-0.1);
  // A handful of roundings.
  CHECK(b(0) == Approx(ball.v.z() - beta / h * (depth - slop)).epsilon(1e-13));
  CHECK(b(1) == Approx(slide).epsilon(1e-13));
  // Overlap within the slop is left alone.
  CHECK(velocityBias(bodies, rows, Vec3(0.5 * slop, 0.0, 0.0).head<2>(), h, beta, slop)(0) ==
        Approx(ball.v.z()).epsilon(1e-15));
  CHECK_THROWS_AS(velocityBias(bodies, rows, VecX::Zero(3), h, beta, slop), InvalidInput);
  CHECK_THROWS_AS(velocityBias(bodies, rows, VecX::Zero(2), 0.0, beta, slop), InvalidInput);
  CHECK_THROWS_AS(velocityBias(bodies, rows, VecX::Zero(2), h, 1.5, slop), InvalidInput);
  CHECK_THROWS_AS(velocityBias(bodies, rows, VecX::Zero(2), h, beta, -1.0), InvalidInput);
  // The ends of the documented ranges are allowed: beta = 1 (remove the whole overlap in a step),
  // beta = 0 (no correction) and slop = 0 (correct every overlap)
  const VecX depths = Vec3(depth, 0.0, 0.0).head<2>();
  CHECK(velocityBias(bodies, rows, depths, h, 1.0, slop)(0) == Approx(ball.v.z() - (depth - slop) / h).epsilon(1e-13));
  CHECK(velocityBias(bodies, rows, depths, h, 0.0, slop)(0) == ball.v.z());  // nothing subtracted
  CHECK(velocityBias(bodies, rows, depths, h, beta, 0.0)(0) == Approx(ball.v.z() - beta / h * depth).epsilon(1e-13));
}

TEST_CASE("velocity bias: a moving, spinning body B counts with its own point velocity, in either row order", "[lab06][pts=1][sec=7]") {
  // The ball of the test above on a platform B that moves and spins about z: at p = 0, B's point
  // moves at v_b + omega_b x (p - x_b) = (v_bx, -0.5 omega_bz, v_bz) for x_b = (0.5, 0, -0.1); the
  // ball's at (v_x - 0.1 omega_y, 0, v_z). Rows: the normal (ball A, platform B), the tangents x and
  // y, and the normal again with the roles swapped (platform A, ball B, normal -z): the same number.
  ContactBody ball, platform;
  ball.x = Vec3(0.0, 0.0, 0.1);
  ball.v = Vec3(uniform(0.5, 2.0), 0.0, -uniform(0.1, 1.0));
  ball.omega = Vec3(0.0, uniform(-3.0, 3.0), 0.0);
  ball.inv_mass = 1.0;
  ball.I_inv_world = Mat3::Identity() * 250.0;
  platform.x = Vec3(0.5, 0.0, -0.1);
  platform.v = Vec3(uniform(-1.0, 1.0), 0.0, uniform(0.2, 1.0));
  platform.omega = Vec3(0.0, 0.0, uniform(1.0, 3.0));
  platform.inv_mass = 0.5;
  platform.I_inv_world = Mat3::Identity() * 2.0;
  const std::vector<ContactBody> bodies = {ball, platform};
  const Vec3 p = Vec3::Zero();
  const std::vector<ContactRow> rows = {
      {0, 1, p, Vec3::UnitZ()}, {0, 1, p, Vec3::UnitX()}, {0, 1, p, Vec3::UnitY()}, {1, 0, p, -Vec3::UnitZ()}};
  const double h = 0.01, beta = 0.2, slop = 0.002, depth = uniform(0.003, 0.02);
  const VecX b = velocityBias(bodies, rows, Eigen::Vector4d(depth, 0.0, 0.0, depth), h, beta, slop);
  const double push = beta / h * (depth - slop);
  // A handful of roundings on numbers of order 1
  CHECK(b(0) == Approx(ball.v.z() - platform.v.z() - push).epsilon(1e-13));
  CHECK(b(1) == Approx(ball.v.x() - 0.1 * ball.omega.y() - platform.v.x()).epsilon(1e-13));
  CHECK(b(2) == Approx(0.5 * platform.omega.z()).epsilon(1e-13));
  CHECK(b(3) == Approx(b(0)).epsilon(1e-13));
}

TEST_CASE("friction pyramid: a sliding sphere's hand solution solves the LCP, a wrong friction does not", "[lab06][pts=3][sec=8]") {
  // A sphere (m, radius r) sliding at u along d_0 with the step's gravity in its velocity. By hand:
  // lambda_n = m g h stops the fall; friction mu lambda_n acts along d_2 = -d_0 (beta_2); the
  // contact point then slides at gamma = u - mu lambda_n (1/m + r^2/I) = u - 3.5 mu g h.
  const double m = uniform(0.5, 2.0), r = 0.1, I = 0.4 * m * r * r, mu = uniform(0.1, 0.8), g = 9.81, h = 0.01;
  const double u = uniform(1.0, 3.0);
  const int k = 4;
  ContactBody sphere;
  sphere.x = Vec3(0.0, 0.0, r);
  sphere.inv_mass = 1.0 / m;
  sphere.I_inv_world = Mat3::Identity() / I;
  const std::vector<Vec3> d = tangentDirections(Vec3::UnitZ(), k);
  sphere.v = u * d[0] - g * h * Vec3::UnitZ();
  const std::vector<ContactBody> bodies = {sphere, fixedBody(Vec3::Zero())};
  std::vector<ContactRow> rows = {{0, 1, Vec3::Zero(), Vec3::UnitZ()}};
  for (const Vec3& direction : d) rows.push_back({0, 1, Vec3::Zero(), direction});
  const MatX A = jacobianProduct(bodies, rows);
  VecX b(1 + k);
  for (std::size_t i = 0; i < rows.size(); ++i) b(static_cast<Index>(i)) = rows[i].d.dot(sphere.v);
  const LcpProblem lcp = frictionPyramid(A, b, VecX::Constant(1, mu), k);
  REQUIRE(lcp.A.rows() == 2 + k);
  REQUIRE(lcp.A.cols() == 2 + k);
  REQUIRE(lcp.b.size() == 2 + k);
  const double lambda_n = m * g * h;
  VecX z = VecX::Zero(2 + k);
  z(0) = lambda_n;
  z(1 + 2) = mu * lambda_n;
  z(1 + k) = u - 3.5 * mu * g * h;
  // The hand solution is exact up to round-off in products of order 1.
  CHECK(lcpResidual(lcp.A, lcp.b, z) <= 1e-12);
  // Friction along the motion, or too little of it, or a wrong sliding speed, is not a solution.
  VecX wrong = z;
  std::swap(wrong(1), wrong(1 + 2));
  CHECK(lcpResidual(lcp.A, lcp.b, wrong) > 1e-3);
  wrong = z;
  wrong(1 + 2) *= 0.5;
  CHECK(lcpResidual(lcp.A, lcp.b, wrong) > 1e-4);
  wrong = z;
  wrong(1 + k) += 0.1;
  CHECK(lcpResidual(lcp.A, lcp.b, wrong) > 1e-3);
  // Sticking: slow enough to stop within the cone, friction below mu lambda_n and gamma = 0.
  const double s = 0.5 * 3.5 * mu * g * h;
  sphere.v = s * d[0] - g * h * Vec3::UnitZ();
  for (std::size_t i = 0; i < rows.size(); ++i) b(static_cast<Index>(i)) = rows[i].d.dot(sphere.v);
  const LcpProblem stick = frictionPyramid(A, b, VecX::Constant(1, mu), k);
  z.setZero();
  z(0) = lambda_n;
  z(1 + 2) = s * m / 3.5;
  CHECK(lcpResidual(stick.A, stick.b, z) <= 1e-12);
}

TEST_CASE("friction pyramid: sizes that do not fit, k < 3 and negative mu are refused", "[lab06][pts=1][sec=8]") {
  const int k = 4;
  const MatX A = MatX::Identity(2 + 2 * k, 2 + 2 * k);
  const VecX b = VecX::Zero(2 + 2 * k), mu = VecX::Constant(2, 0.5);
  CHECK_NOTHROW(frictionPyramid(A, b, mu, k));
  CHECK_THROWS_AS(frictionPyramid(A, b, mu, 2), InvalidInput);
  CHECK_THROWS_AS(frictionPyramid(A, b, mu, 3), InvalidInput);
  CHECK_THROWS_AS(frictionPyramid(A.topLeftCorner(9, 10), b, mu, k), InvalidInput);
  CHECK_THROWS_AS(frictionPyramid(A, b.head(9), mu, k), InvalidInput);
  CHECK_THROWS_AS(frictionPyramid(A, b, VecX::Constant(3, 0.5), k), InvalidInput);
  CHECK_THROWS_AS(frictionPyramid(A, b, Vec3(0.5, -0.1, 0.0).head<2>(), k), InvalidInput);
}

TEST_CASE("friction pyramid: two spheres sliding apart, each contact's directions and gamma kept together", "[lab06][pts=1][sec=8]") {
  // Two spheres (m_s, radius r) on the ground, sliding at u_s: sphere 0 along d_1, sphere 1 along
  // d_0, sphere 1 faster by 1 m/s. Rows: the 2 normals, then sphere 0's k directions, then sphere
  // 1's. By hand, as for one sphere: lambda_s = m_s g h, friction mu_s lambda_s on the direction
  // opposite the sliding (d_3 = -d_1 for sphere 0, d_2 = -d_0 for sphere 1), gamma_s =
  // u_s - 3.5 mu_s g h. (Directions numbered l m + i instead of i k + l would hand each sphere's
  // friction to the other's gamma, whose speed differs by 1 - 3.5 g h |mu_1 - mu_0| >= 0.75.)
  const double r = 0.1, g = 9.81, h = 0.01;
  const int k = 4;
  const std::vector<Vec3> d = tangentDirections(Vec3::UnitZ(), k);
  std::vector<ContactBody> bodies;
  double m[2], mu[2], u[2];
  for (int s = 0; s < 2; ++s) {
    m[s] = uniform(0.5, 2.0);
    mu[s] = uniform(0.1, 0.8);
    u[s] = s == 0 ? uniform(1.0, 2.0) : u[0] + 1.0;
    ContactBody sphere;
    sphere.x = Vec3(2.0 * s, 0.0, r);
    sphere.inv_mass = 1.0 / m[s];
    sphere.I_inv_world = Mat3::Identity() / (0.4 * m[s] * r * r);
    sphere.v = u[s] * d[static_cast<std::size_t>(1 - s)] - g * h * Vec3::UnitZ();
    bodies.push_back(sphere);
  }
  bodies.push_back(fixedBody(Vec3::Zero()));
  std::vector<ContactRow> rows;
  for (int s = 0; s < 2; ++s) rows.push_back({s, 2, Vec3(2.0 * s, 0.0, 0.0), Vec3::UnitZ()});
  for (int s = 0; s < 2; ++s) {
    for (const Vec3& direction : d) rows.push_back({s, 2, Vec3(2.0 * s, 0.0, 0.0), direction});
  }
  const MatX A = jacobianProduct(bodies, rows);
  VecX b(static_cast<Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) b(static_cast<Index>(i)) = rows[i].d.dot(bodies[static_cast<std::size_t>(rows[i].a)].v);
  const LcpProblem lcp = frictionPyramid(A, b, Vec3(mu[0], mu[1], 0.0).head<2>(), k);
  const Index size = 2 + 2 * k + 2;
  REQUIRE(lcp.A.rows() == size);
  REQUIRE(lcp.A.cols() == size);
  REQUIRE(lcp.b.size() == size);
  // Unknowns (lambda_0, lambda_1, beta_0 (k), beta_1 (k), gamma_0, gamma_1)
  VecX z = VecX::Zero(size);
  for (Index s = 0; s < 2; ++s) {
    z(s) = m[s] * g * h;
    z(2 + s * k + (3 - s)) = mu[s] * z(s);  // direction 3 - s = -d_(1 - s)
    z(2 + 2 * k + s) = u[s] - 3.5 * mu[s] * g * h;
  }
  // Exact up to round-off in products of order 1
  CHECK(lcpResidual(lcp.A, lcp.b, z) <= 1e-12);
  // Each gamma limits its own contact's friction only: sphere 1's friction moved onto sphere 0's
  // directions is no solution (sphere 0 would then get two frictions and sphere 1 none)
  VecX wrong = z;
  std::swap(wrong(2 + k + 2), wrong(2 + 2));
  CHECK(lcpResidual(lcp.A, lcp.b, wrong) > 1e-4);
}

TEST_CASE("friction pyramid: the smallest pyramid (k = 3) with a frictionless contact (mu = 0), built here entry by entry", "[lab06][pts=1][sec=8]") {
  // m = 2 contacts, k = 3 directions (the least the header allows), contact 0 without friction
  // (mu = 0 is not negative). Unknowns (lambda_0, lambda_1, beta_0 (3), beta_1 (3), gamma_0, gamma_1).
  const int k = 3;
  const Index m = 2, rows = m + m * k;
  MatX A(rows, rows);
  VecX b(rows);
  for (Index i = 0; i < rows; ++i) {
    b(i) = uniform(-1.0, 1.0);
    for (Index j = 0; j < rows; ++j) A(i, j) = uniform(-1.0, 1.0);
  }
  const VecX mu = Vec3(0.0, uniform(0.1, 1.0), 0.0).head<2>();
  MatX expected = MatX::Zero(rows + m, rows + m);
  VecX expected_b = VecX::Zero(rows + m);
  expected.topLeftCorner(rows, rows) = A;
  expected_b.head(rows) = b;
  for (Index i = 0; i < m; ++i) {
    for (Index l = 0; l < k; ++l) {
      expected(m + i * k + l, rows + i) = 1.0;   // E: w_d sees its contact's sliding speed
      expected(rows + i, m + i * k + l) = -1.0;  // -E^T: the friction inside the pyramid
    }
    expected(rows + i, i) = mu(i);
  }
  INFO("m = 2 contacts, k = 3 directions, mu = (0, " << mu(1) << "): expected an LCP of size " << rows + m);
  const LcpProblem lcp = frictionPyramid(A, b, mu, k);
  REQUIRE(lcp.A.rows() == rows + m);
  REQUIRE(lcp.A.cols() == rows + m);
  REQUIRE(lcp.b.size() == rows + m);
  // Copies and constants: exact
  CHECK(lcp.A == expected);
  CHECK(lcp.b == expected_b);
}

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Three moving bodies and a fixed one last, and a valid row between the first and the last.
struct RowScene {
  std::vector<ContactBody> bodies;
  ContactRow row;
};

RowScene rowScene() {
  RowScene s;
  Mat3 I;
  for (int k = 0; k < 3; ++k) s.bodies.push_back(randomBody(I));
  s.bodies.push_back(fixedBody(randomVec3(1.0)));
  s.row = {0, 3, randomVec3(1.0), randomVec3(1.0).normalized()};
  return s;
}

// The rows every row-taking function must refuse, each with the words its message must contain.
std::vector<std::pair<ContactRow, std::string>> badRows(const ContactRow& good) {
  std::vector<std::pair<ContactRow, std::string>> bad;
  auto add = [&](const std::function<void(ContactRow&)>& spoil, const std::string& words) {
    ContactRow row = good;
    spoil(row);
    bad.emplace_back(row, words);
  };
  add([](ContactRow& r) { r.a = 4; }, "names body 4");
  add([](ContactRow& r) { r.b = 4; }, "names body 4");
  add([](ContactRow& r) { r.a = -1; }, "names body -1");
  add([](ContactRow& r) { r.d *= 1.5; }, "direction d");
  add([](ContactRow& r) { r.d *= 1.0 - 1e-8; }, "direction d");
  add([](ContactRow& r) { r.d = Vec3::Zero(); }, "direction d");
  add([](ContactRow& r) { r.d.y() = kNan; }, "direction d");
  add([](ContactRow& r) { r.p.z() = kInf; }, "point p");
  return bad;
}

}  // namespace

TEST_CASE("contact matrix: rows naming no body, directions that are not unit, bad points and inverse masses are refused naming them", "[lab06][pts=1][sec=1]") {
  RowScene s = rowScene();
  // Valid: indices 0 and size - 1 either way round, a direction off by round-off, a fixed body
  ContactRow rounded = s.row;
  rounded.d *= 1.0 + 1e-12;
  const MatX A = contactMatrix(s.bodies, {s.row, {3, 0, s.row.p, s.row.d}, rounded});
  CHECK(A.rows() == 3);
  for (const auto& [row, words] : badRows(s.row)) {
    INFO("expected: " << words);
    // The bad row second: the message names row 1
    CHECK_THROWS_AS(contactMatrix(s.bodies, {s.row, row}), InvalidInput);
    CHECK_THROWS_WITH(contactMatrix(s.bodies, {s.row, row}), Contains("row 1") && Contains(words));
  }
  // Negative or non-finite inverse masses, a NaN inverse inertia: a body the rows name or not
  for (const double bad : {-uniform(0.1, 1.0), kNan, kInf}) {
    INFO("inverse mass " << bad);
    std::vector<ContactBody> bodies = s.bodies;
    bodies[2].inv_mass = bad;
    CHECK_THROWS_AS(contactMatrix(bodies, {s.row}), InvalidInput);
    CHECK_THROWS_WITH(contactMatrix(bodies, {s.row}), Contains("body 2 inverse mass"));
  }
  std::vector<ContactBody> bodies = s.bodies;
  bodies[0].I_inv_world(2, 1) = kNan;
  CHECK_THROWS_WITH(contactMatrix(bodies, {s.row}), Contains("body 0") && Contains("I_inv_world"));
}

TEST_CASE("Baraff's b and velocity bias: bad rows, inverse masses and depths are refused naming them", "[lab06][pts=1][sec=2][sec=7]") {
  RowScene s = rowScene();
  const std::vector<AppliedLoads> loads(s.bodies.size());
  // Valid: indices 0 and size - 1, a direction off by round-off, depth 0
  ContactRow rounded = s.row;
  rounded.d *= 1.0 - 1e-12;
  const std::vector<ContactRow> good = {s.row, rounded};
  CHECK(accelerationBias(s.bodies, loads, good).size() == 2);
  CHECK(velocityBias(s.bodies, good, VecX::Zero(2), 0.01, 0.2, 0.001).size() == 2);
  for (const auto& [row, words] : badRows(s.row)) {
    INFO("expected: " << words);
    const std::vector<ContactRow> rows = {s.row, row};
    CHECK_THROWS_AS(accelerationBias(s.bodies, loads, rows), InvalidInput);
    CHECK_THROWS_WITH(accelerationBias(s.bodies, loads, rows), Contains("row 1") && Contains(words));
    CHECK_THROWS_AS(velocityBias(s.bodies, rows, VecX::Zero(2), 0.01, 0.2, 0.001), InvalidInput);
    CHECK_THROWS_WITH(velocityBias(s.bodies, rows, VecX::Zero(2), 0.01, 0.2, 0.001), Contains("row 1") && Contains(words));
  }
  std::vector<ContactBody> bodies = s.bodies;
  bodies[1].inv_mass = -uniform(0.1, 1.0);
  CHECK_THROWS_WITH(accelerationBias(bodies, loads, good), Contains("body 1 inverse mass"));
  for (const double bad : {kNan, kInf, -kInf}) {
    INFO("depth " << bad);
    CHECK_THROWS_AS(velocityBias(s.bodies, good, Vec3(0.01, bad, 0.0).head<2>(), 0.01, 0.2, 0.001), InvalidInput);
    CHECK_THROWS_WITH(velocityBias(s.bodies, good, Vec3(0.01, bad, 0.0).head<2>(), 0.01, 0.2, 0.001), Contains("depths"));
  }
}

TEST_CASE("friction pyramid: a NaN or infinite entry of A or b, and an infinite mu, are refused naming them", "[lab06][pts=1][sec=8]") {
  const int k = 3;
  const MatX A = MatX::Identity(2 + 2 * k, 2 + 2 * k);
  const VecX b = VecX::Constant(2 + 2 * k, -1.0), mu = VecX::Constant(2, 0.5);
  INFO("m = 2 contacts, k = 3 directions, mu = (0.5, 0.5), A = I (8 x 8), b = -1");
  CHECK(frictionPyramid(A, b, mu, k).A.rows() == 2 + 2 * k + 2);
  MatX bad_A = A;
  const Index row = static_cast<Index>(uniform(0, 8)), col = static_cast<Index>(uniform(0, 8));
  CAPTURE(row, col);
  bad_A(row, col) = kNan;
  CHECK_THROWS_AS(frictionPyramid(bad_A, b, mu, k), InvalidInput);
  CHECK_THROWS_WITH(frictionPyramid(bad_A, b, mu, k), Contains("pyramid A") && Contains("non-finite"));
  VecX bad_b = b;
  const Index entry = static_cast<Index>(uniform(0, 8));
  CAPTURE(entry);
  bad_b(entry) = -kInf;
  CHECK_THROWS_AS(frictionPyramid(A, bad_b, mu, k), InvalidInput);
  CHECK_THROWS_WITH(frictionPyramid(A, bad_b, mu, k), Contains("pyramid b") && Contains("non-finite"));
  CHECK_THROWS_WITH(frictionPyramid(A, b, Vec3(0.5, kInf, 0.0).head<2>(), k), Contains("mu of contact 1"));
  CHECK_THROWS_WITH(frictionPyramid(A, b, Vec3(kNan, 0.5, 0.0).head<2>(), k), Contains("mu of contact 0"));
}
