// Lab 6 graded tests of projected Gauss-Seidel and its friction-cone variant: convergence on
// well-conditioned problems, the QP objective it decreases, its residual history, and a contact
// on a slope that sticks or slides.
#include <cmath>
#include <limits>
#include <vector>

#include "lcp_support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// A well-conditioned SPD LCP in which b has negative entries (PGS has work to do).
PlantedLcp wellConditioned(Index n, double cond) {
  PlantedLcp p = plantSolution(randomSpd(n, cond, uniform(0.1, 10.0)));
  REQUIRE(p.b.minCoeff() < 0.0);
  return p;
}

// Contact-frame blocks (f_n, f_t, f_o) of k contacts on a few bodies: A = J M^-1 J^T + small
// diagonal (compliance), symmetric positive definite with a coupled, non-diagonal structure.
MatX coneMatrix(Index k) {
  const Index dofs = 6;
  MatX J(3 * k, dofs);
  for (Index i = 0; i < J.rows(); ++i) {
    for (Index j = 0; j < dofs; ++j) J(i, j) = uniform(-1.0, 1.0);
  }
  VecX m_inv(dofs);
  for (Index j = 0; j < dofs; ++j) m_inv(j) = 1.0 / uniform(0.5, 5.0);
  return J * m_inv.asDiagonal() * J.transpose() + MatX::Identity(3 * k, 3 * k) * 0.1;
}

// A warm start of n entries in [-1, 1]: some negative, which PGS must count as 0.
VecX randomWarmStart(Index n) {
  VecX start(n);
  for (Index i = 0; i < n; ++i) start(i) = uniform(-1.0, 1.0);
  return start;
}

}  // namespace

TEST_CASE("pgs: one-step oracles, b >= 0 gives f = 0 exactly and 1 x 1 gives f = -b / a exactly", "[lab06][pts=1][sec=5]") {
  const Index n = static_cast<Index>(uniform(2, 8));
  const MatX A = randomSpd(n, 10.0);
  VecX b(n);
  for (Index i = 0; i < n; ++i) b(i) = i == 0 ? 0.0 : uniform(0.0, 2.0);
  const LcpSolution zero = solveLcpPgs(A, b);
  CHECK(zero.f == VecX::Zero(n));  // max(0, 0 - b_i / a_ii) = 0 at every update
  CHECK(zero.residual == 0.0);
  const double a = uniform(0.1, 10.0), b1 = -uniform(0.1, 10.0);
  const LcpSolution one = solveLcpPgs(MatX::Constant(1, 1, a), VecX::Constant(1, b1));
  CHECK(one.f(0) == -b1 / a);  // one division: exact
  CHECK(one.iterations == 1);   // exact after one sweep, residual 0 or one rounding of a f + b
}

TEST_CASE("pgs: converges to the planted solution of well-conditioned SPD LCPs", "[lab06][pts=2][sec=5]") {
  for (int trial = 0; trial < 10; ++trial) {
    const Index n = static_cast<Index>(uniform(3, 20));
    const double cond = uniform(1.0, 10.0);
    const PlantedLcp p = wellConditioned(n, cond);
    LcpOptions options;
    options.max_iterations = 100000;
    options.tolerance = 1e-12 * p.A.cwiseAbs().maxCoeff();
    const LcpSolution s = solveLcpPgs(p.A, p.b, options);
    INFO("n " << n << ", cond " << cond << ", sweeps " << s.iterations << ", residual " << s.residual);
    CHECK(s.iterations < options.max_iterations);
    CHECK(s.residual <= options.tolerance);
    CHECK(s.f.minCoeff() >= 0.0);  // projected at every update
    // A residual r moves f by at most about cond r / lambda_min (error bound of the LCP); margin 10
    CHECK((s.f - p.f).cwiseAbs().maxCoeff() <= 10.0 * cond * options.tolerance / (p.A.cwiseAbs().maxCoeff() / cond) + 1e-12);
    CHECK(complementarity(p.A, p.b, s.f) <= 2.0 * options.tolerance);
    CHECK((s.w - (p.A * s.f + p.b)).cwiseAbs().maxCoeff() <= 1e-12 * p.A.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("pgs: a warm start is where the sweeps begin, and at the solution one sweep ends them", "[lab06][pts=1][sec=5]") {
  const Index n = static_cast<Index>(uniform(4, 12));
  const PlantedLcp p = wellConditioned(n, uniform(1.0, 10.0));
  // One sweep from a random start, with negative entries counting as 0, computed here.
  LcpOptions options;
  options.initial = randomWarmStart(n);
  options.max_iterations = 1;
  VecX f = options.initial.cwiseMax(0.0);
  for (Index i = 0; i < n; ++i) f(i) = std::max(0.0, f(i) - (p.A.row(i).dot(f) + p.b(i)) / p.A(i, i));
  const LcpSolution one = solveLcpPgs(p.A, p.b, options);
  // The same products in the same order, up to a dot product's rounding.
  CHECK((one.f - f).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + f.cwiseAbs().maxCoeff()));
  // Started at the planted solution, the first sweep changes nothing beyond round-off and ends.
  options.initial = p.f;
  options.max_iterations = 100;
  options.tolerance = 1e-10 * p.A.cwiseAbs().maxCoeff();
  const LcpSolution warm = solveLcpPgs(p.A, p.b, options);
  CHECK(warm.iterations == 1);
  CHECK((warm.f - p.f).cwiseAbs().maxCoeff() <= 1e-10);
  // A start of the wrong size is no start: the sweeps begin at 0, as without one.
  options.initial = VecX::Ones(n + 1);
  options.max_iterations = 3;
  LcpOptions cold = options;
  cold.initial = VecX();
  CHECK(solveLcpPgs(p.A, p.b, options).f == solveLcpPgs(p.A, p.b, cold).f);
  options.initial = VecX::Constant(n, std::nan(""));
  CHECK_THROWS_AS(solveLcpPgs(p.A, p.b, options), InvalidInput);
}

TEST_CASE("pgs: each sweep never increases the QP objective 1/2 f^T A f + b^T f on SPD problems", "[lab06][pts=2][sec=5]") {
  const Index n = static_cast<Index>(uniform(5, 20));
  const double cond = std::exp(uniform(std::log(10.0), std::log(1000.0)));
  const PlantedLcp p = plantSolution(randomSpd(n, cond));
  LcpOptions options;
  options.tolerance = 0.0;  // run every sweep asked for
  // Each update minimizes the objective exactly along f_i within f_i >= 0: never upwards. Runs
  // with 1, 2, 3, ... sweeps repeat the same first sweeps (deterministic from f = 0).
  double previous = 0.0;  // objective at f = 0
  const double minimum = qpObjective(p.A, p.b, p.f);
  for (int sweeps = 1; sweeps <= 40; ++sweeps) {
    options.max_iterations = sweeps;
    const LcpSolution s = solveLcpPgs(p.A, p.b, options);
    const double objective = qpObjective(p.A, p.b, s.f);
    INFO("sweep " << sweeps << ": objective " << objective << ", previous " << previous << ", minimum " << minimum);
    // Round-off of evaluating the objective: relative 1e-12 of its size
    CHECK(objective <= previous + 1e-12 * std::abs(previous) + 1e-15);
    CHECK(objective >= minimum - 1e-12 * std::abs(minimum) - 1e-15);  // never below the QP's minimum
    CHECK(s.iterations <= sweeps);
    previous = objective;
  }
  CHECK(previous < 0.0);  // b has a negative entry: the first update already lowers it below 0
}

TEST_CASE("pgs: the residual history has one entry per sweep, the last is the returned residual", "[lab06][pts=1][sec=5]") {
  const Index n = static_cast<Index>(uniform(5, 15));
  const PlantedLcp p = wellConditioned(n, uniform(5.0, 50.0));
  // Stops at the first sweep at or below the tolerance, or after max_iterations
  for (const double tolerance : {0.0, 1e-6 * p.A.cwiseAbs().maxCoeff()}) {
    LcpOptions options;
    options.max_iterations = tolerance == 0.0 ? static_cast<int>(uniform(1, 30)) : 100000;
    options.tolerance = tolerance;
    std::vector<double> history;
    const LcpSolution s = solveLcpPgs(p.A, p.b, options, &history);
    INFO("tolerance " << tolerance << ", sweeps " << s.iterations);
    REQUIRE(history.size() == static_cast<std::size_t>(s.iterations));
    REQUIRE(s.iterations >= 1);
    CHECK(history.back() == s.residual);
    // The residual of the returned f (the student may compute it apart from lcpResidual)
    CHECK(s.residual == Approx(lcpResidual(p.A, p.b, s.f)).epsilon(1e-9).margin(1e-15));
    if (tolerance > 0.0) {
      CHECK(s.residual <= tolerance);
      for (std::size_t k = 0; k + 1 < history.size(); ++k) CHECK(history[k] > tolerance);
    } else {
      // Tolerance 0 stops early only on an exact solution (PGS can land on one, e.g. one contact)
      CHECK((s.iterations == options.max_iterations || s.residual == 0.0));
    }
    // Each entry is the residual after that sweep: rerun with k sweeps and compare
    const int k = static_cast<int>(uniform(1, static_cast<double>(s.iterations) + 1));
    options.max_iterations = k;
    const LcpSolution prefix = solveLcpPgs(p.A, p.b, options);
    CHECK(history[static_cast<std::size_t>(k - 1)] == Approx(lcpResidual(p.A, p.b, prefix.f)).epsilon(1e-9).margin(1e-15));
  }
}

TEST_CASE("pgs cone: a contact on a slope sticks inside the cone and slides on its rim opposite w_t", "[lab06][pts=2][sec=6]") {
  // A point mass m on a slope of angle theta: in the contact frame (n, t, o), A = I / m and
  // b = g (-cos theta, sin theta u) with u the downhill direction in the tangent plane.
  const double m = uniform(0.5, 5.0), g = uniform(5.0, 15.0), mu = uniform(0.2, 1.0);
  const double phi = uniform(0.0, 2.0 * M_PI);
  const Vec3 u(0.0, std::cos(phi), std::sin(phi));
  const MatX A = MatX::Identity(3, 3) / m;
  LcpOptions options;
  options.max_iterations = 1000;
  options.tolerance = 1e-13;
  const VecX mus = VecX::Constant(1, mu);
  // Gentle slope, tan theta < mu: static friction holds the mass, w = 0, f = -m b
  {
    const double theta = std::atan(mu * uniform(0.1, 0.9));
    const VecX b = g * Vec3(-std::cos(theta), std::sin(theta) * u.y(), std::sin(theta) * u.z());
    const LcpSolution s = solveLcpPgsCone(A, b, mus, options);
    INFO("stick: theta " << theta << ", mu " << mu << ", f " << s.f.transpose() << ", w " << s.w.transpose());
    CHECK(s.iterations < options.max_iterations);
    CHECK(s.w.cwiseAbs().maxCoeff() <= 1e-12 * g);  // A diagonal: exact after a sweep, round-off only
    CHECK((s.f + m * b).cwiseAbs().maxCoeff() <= 1e-12 * m * g);
  }
  // Steep slope, tan theta > mu: it slides, friction on the rim |f_T| = mu f_n, opposing w_T
  {
    const double theta = std::atan(mu * uniform(1.2, 3.0));
    const VecX b = g * Vec3(-std::cos(theta), std::sin(theta) * u.y(), std::sin(theta) * u.z());
    const LcpSolution s = solveLcpPgsCone(A, b, mus, options);
    INFO("slide: theta " << theta << ", mu " << mu << ", f " << s.f.transpose() << ", w " << s.w.transpose());
    const double f_n = s.f(0);
    const Eigen::Vector2d f_T = s.f.segment<2>(1), w_T = s.w.segment<2>(1);
    CHECK(f_n == Approx(m * g * std::cos(theta)).epsilon(1e-12));  // normal still balances gravity
    CHECK(std::abs(s.w(0)) <= 1e-12 * g);
    CHECK(f_T.norm() == Approx(mu * f_n).epsilon(1e-12));  // on the rim, scaled exactly there
    // It accelerates downhill at g (sin theta - mu cos theta); a few roundings
    CHECK(w_T.norm() == Approx(g * (std::sin(theta) - mu * std::cos(theta))).epsilon(1e-10));
    // Opposite directions: cosine -1 up to round-off
    CHECK(f_T.dot(w_T) / (f_T.norm() * w_T.norm()) <= -1.0 + 1e-12);
  }
}

TEST_CASE("pgs cone: a body touching at an offset slides with friction on the rim exactly opposite w_T", "[lab06][pts=2][sec=6]") {
  // One contact of a rigid body away from its centre: A is a full SPD 3 x 3 (coupled normal and
  // tangents, a_tt != a_oo; diagonally dominant, so the coupling cannot jam the contact), pressed
  // in (b_n < 0) with a tangential pull far beyond what mu f_n can hold: it cannot stick.
  const double scale = uniform(0.1, 10.0);
  MatX A = Vec3(uniform(1.0, 3.0), uniform(1.0, 3.0), uniform(1.0, 3.0)).asDiagonal();
  for (Index i = 0; i < 3; ++i) {
    for (Index j = i + 1; j < 3; ++j) A(i, j) = A(j, i) = uniform(-0.3, 0.3);
  }
  A *= scale;
  const double mu = uniform(0.1, 0.8), angle = uniform(0.0, 2.0 * M_PI), pull = uniform(10.0, 20.0);
  const VecX b = scale * Vec3(-uniform(0.5, 2.0), pull * std::cos(angle), pull * std::sin(angle));
  LcpOptions options;
  options.max_iterations = 100000;
  options.tolerance = 1e-14 * A.cwiseAbs().maxCoeff();
  const LcpSolution s = solveLcpPgsCone(A, b, VecX::Constant(1, mu), options);
  const double f_n = s.f(0);
  const Eigen::Vector2d f_T = s.f.segment<2>(1), w_T = s.w.segment<2>(1);
  INFO("mu " << mu << ", sweeps " << s.iterations << ", f " << s.f.transpose() << ", w " << s.w.transpose());
  CHECK(s.iterations < options.max_iterations);
  REQUIRE(f_n > 0.0);
  REQUIRE(w_T.norm() > 0.0);
  // Converged to changes of 1e-14 relative; A well conditioned: w_n within a few 1e-12 of 0
  CHECK(std::abs(s.w(0)) <= 1e-11 * b.norm());
  CHECK(f_T.norm() == Approx(mu * f_n).epsilon(1e-12));  // on the rim: scaled exactly there
  // Coulomb: friction exactly opposite the sliding; a step per entry would tilt it by percents
  CHECK(f_T.dot(w_T) / (f_T.norm() * w_T.norm()) <= -1.0 + 1e-9);
}

TEST_CASE("pgs cone: coupled contacts that can stick converge to w = 0 inside the cone", "[lab06][pts=1][sec=6]") {
  const Index k = static_cast<Index>(uniform(1, 3));
  const MatX A = coneMatrix(k);
  // Plant a sticking solution well inside the cones: f_n > 0, |f_T| <= 0.5 mu f_n, w = 0
  VecX mu(k), f(3 * k);
  for (Index c = 0; c < k; ++c) {
    mu(c) = uniform(0.3, 1.0);
    f(3 * c) = uniform(0.5, 2.0);
    const double angle = uniform(0.0, 2.0 * M_PI), length = uniform(0.0, 0.5) * mu(c) * f(3 * c);
    f(3 * c + 1) = length * std::cos(angle);
    f(3 * c + 2) = length * std::sin(angle);
  }
  const VecX b = -A * f;
  LcpOptions options;
  options.max_iterations = 100000;
  options.tolerance = 1e-13;
  const LcpSolution s = solveLcpPgsCone(A, b, mu, options);
  INFO(k << " contacts, sweeps " << s.iterations << ", last change " << s.residual);
  CHECK(s.iterations < options.max_iterations);
  CHECK(s.residual <= options.tolerance);
  // Stopping when a sweep changes w by < 1e-13 leaves w within a modest multiple of it (A is
  // well conditioned: the 0.1 compliance keeps lambda_min >= 0.1)
  CHECK(s.w.cwiseAbs().maxCoeff() <= 1e-9);
  CHECK((s.f - f).cwiseAbs().maxCoeff() <= 1e-8);
}

TEST_CASE("pgs cone: mu = 0 gives the frictionless answer of PGS on the normal rows", "[lab06][pts=1][sec=6]") {
  const Index k = static_cast<Index>(uniform(2, 6));
  const MatX A = coneMatrix(k);
  VecX b(3 * k);
  for (Index i = 0; i < 3 * k; ++i) b(i) = uniform(-1.0, 1.0);
  b(0) = -uniform(0.5, 1.0);  // at least one contact pushed
  std::vector<Index> normal;
  for (Index c = 0; c < k; ++c) normal.push_back(3 * c);
  LcpOptions options;
  options.max_iterations = 100000;
  options.tolerance = 1e-14;
  const LcpSolution cone = solveLcpPgsCone(A, b, VecX::Zero(k), options);
  const MatX A_n = A(normal, normal);
  const VecX b_n = b(normal);
  const LcpSolution pgs = solveLcpPgs(A_n, b_n, options);
  INFO(k << " contacts, cone sweeps " << cone.iterations << ", pgs sweeps " << pgs.iterations);
  for (Index c = 0; c < k; ++c) {
    // Both run the same normal updates; they stop on different measures, each at ~1e-14
    CHECK(std::abs(cone.f(3 * c) - pgs.f(c)) <= 1e-10);
    CHECK(cone.f(3 * c + 1) == 0.0);  // the disc of radius 0: no friction at all
    CHECK(cone.f(3 * c + 2) == 0.0);
  }
}

TEST_CASE("pgs cone: after any number of sweeps f_n >= 0 and |f_T| <= mu f_n", "[lab06][pts=1][sec=6]") {
  const Index k = static_cast<Index>(uniform(2, 6));
  const MatX A = coneMatrix(k);
  VecX b(3 * k), mu(k);
  for (Index i = 0; i < 3 * k; ++i) b(i) = uniform(-2.0, 1.0);
  for (Index c = 0; c < k; ++c) mu(c) = uniform(0.2, 1.0);
  b(0) = -uniform(0.5, 2.0);  // at least one contact pushed, so some friction acts
  LcpOptions options;
  options.max_iterations = static_cast<int>(uniform(1, 20));
  options.tolerance = 0.0;
  const LcpSolution s = solveLcpPgsCone(A, b, mu, options);
  // Tolerance 0 stops early only when a sweep changed nothing at all
  CHECK((s.iterations == options.max_iterations || s.residual == 0.0));
  CHECK(s.residual >= 0.0);
  CHECK((s.w - (A * s.f + b)).cwiseAbs().maxCoeff() <= 1e-12);  // w = A f + b, round-off of O(1) sums
  bool any_friction = false;
  for (Index c = 0; c < k; ++c) {
    CHECK(s.f(3 * c) >= 0.0);
    // Projected onto the disc: its length is scaled to mu f_n, round-off only
    CHECK(s.f.segment<2>(3 * c + 1).norm() <= mu(c) * s.f(3 * c) * (1.0 + 1e-12));
    any_friction = any_friction || s.f.segment<2>(3 * c + 1).norm() > 0.0;
  }
  CHECK(any_friction);  // random tangential demands: some contact must use friction
}

TEST_CASE("pgs cone: one sweep from a warm start, computed here: clamp and disc-project the start, normal then disc step", "[lab06][pts=2][sec=6]") {
  // The documented sweep, contact by contact: the start's negative normals count as 0 and its
  // tangential pairs are scaled onto their discs; then f_n <- max(0, f_n - w_n / a_nn), then
  // f_T <- f_T - w_T / lambda_max(symmetrised tangential block), scaled onto |f_T| <= mu f_n.
  const Index k = static_cast<Index>(uniform(2, 5));
  MatX A = coneMatrix(k);
  // A slightly non-symmetric tangential block: lambda is that of its symmetric part
  for (Index c = 0; c < k; ++c) A(3 * c + 1, 3 * c + 2) += uniform(-0.05, 0.05);
  VecX b(3 * k), mu(k), start(3 * k);
  for (Index i = 0; i < 3 * k; ++i) {
    b(i) = uniform(-2.0, 2.0);
    start(i) = uniform(-1.0, 1.0);
  }
  for (Index c = 0; c < k; ++c) {
    mu(c) = uniform(0.2, 1.0);
    start(3 * c) = c == 0 ? -uniform(0.1, 1.0) : uniform(0.5, 2.0);  // contact 0 starts pulling
    b(3 * c) = -uniform(0.5, 2.0);  // every contact pressed: the discs have room
  }
  VecX f = start;
  for (Index c = 0; c < k; ++c) {
    f(3 * c) = std::max(0.0, f(3 * c));
    const double radius = mu(c) * f(3 * c), length = f.segment<2>(3 * c + 1).norm();
    if (length > radius) f.segment<2>(3 * c + 1) *= length > 0.0 ? radius / length : 0.0;
  }
  double largest = 0.0;
  for (Index c = 0; c < k; ++c) {
    const Vec3 before = f.segment<3>(3 * c);
    f(3 * c) = std::max(0.0, f(3 * c) - (A.row(3 * c).dot(f) + b(3 * c)) / A(3 * c, 3 * c));
    // Largest eigenvalue of the symmetric part [p q; q r] of the 2 x 2 tangent block, from
    // det(S - lambda) = 0 (the solution takes another form of it)
    const double p = A(3 * c + 1, 3 * c + 1), r = A(3 * c + 2, 3 * c + 2);
    const double q = 0.5 * (A(3 * c + 1, 3 * c + 2) + A(3 * c + 2, 3 * c + 1));
    const double lambda = 0.5 * (p + r + std::sqrt((p - r) * (p - r) + 4.0 * q * q));
    const Eigen::Vector2d w_T(A.row(3 * c + 1).dot(f) + b(3 * c + 1), A.row(3 * c + 2).dot(f) + b(3 * c + 2));
    f.segment<2>(3 * c + 1) -= w_T / lambda;
    const double radius = mu(c) * f(3 * c), length = f.segment<2>(3 * c + 1).norm();
    if (length > radius) f.segment<2>(3 * c + 1) *= radius / length;
    for (Index i = 0; i < 3; ++i) largest = std::max(largest, std::abs(f(3 * c + i) - before(i)) * A(3 * c + i, 3 * c + i));
  }
  LcpOptions options;
  options.initial = start;
  options.max_iterations = 1;
  options.tolerance = 0.0;
  const LcpSolution s = solveLcpPgsCone(A, b, mu, options);
  INFO(k << " contacts, f " << s.f.transpose() << "\nexpected " << f.transpose());
  CHECK(s.iterations == 1);
  // The same operations on O(1) numbers (the eigenvalue by another formula): round-off only
  CHECK((s.f - f).cwiseAbs().maxCoeff() <= 1e-12);
  CHECK(s.residual == Approx(largest).epsilon(1e-10));  // the sweep's largest |df_i| a_ii
  CHECK((s.w - (A * s.f + b)).cwiseAbs().maxCoeff() <= 1e-12);  // w = A f + b, round-off of O(1) sums
  // Without a start (or one of the wrong size) the sweep begins at 0: a different first sweep
  options.initial = VecX::Ones(3 * k + 1);
  const LcpSolution cold = solveLcpPgsCone(A, b, mu, options);
  options.initial = VecX();
  CHECK(cold.f == solveLcpPgsCone(A, b, mu, options).f);
  CHECK((cold.f - f).cwiseAbs().maxCoeff() > 1e-6);
  // Beside the random case, one where only the friction moves: A = I, b = (-1, 1/2, 0), mu = 1,
  // started at f = (1, 0, 0). The normal update keeps f_n = 1 (w_n = 0); w_T = (1/2, 0), lambda = 1,
  // so f_T = (-1/2, 0), inside the disc of radius 1: the sweep's largest change is 1/2, on f_t.
  // A second sweep changes nothing (w = 0) and stops.
  options.initial = Vec3(1.0, 0.0, 0.0);
  const Vec3 pull(-1.0, 0.5, 0.0);
  const LcpSolution friction = solveLcpPgsCone(MatX::Identity(3, 3), pull, VecX::Constant(1, 1.0), options);
  CHECK(friction.iterations == 1);
  CHECK(friction.f == VecX(Vec3(1.0, -0.5, 0.0)));  // halves: exact
  CHECK(friction.residual == 0.5);
  options.max_iterations = 10;
  const LcpSolution settled = solveLcpPgsCone(MatX::Identity(3, 3), pull, VecX::Constant(1, 1.0), options);
  CHECK(settled.iterations == 2);
  CHECK(settled.residual == 0.0);
}

TEST_CASE("pgs cone: one-step oracle, no contact pressed gives f = 0 exactly after one sweep, whatever the tangential pull", "[lab06][pts=1][sec=6]") {
  // b_n >= 0 (contact 0 just touching, b_n = 0): every normal update is max(0, 0 - b_n / a_nn) = 0,
  // so every disc has radius mu 0 = 0 and the tangential step, whatever b_T asks, is scaled back
  // to f_T = 0 (a zero f_T on a zero disc stays 0, no 0/0). The sweep changed nothing: the
  // largest change is 0 <= tolerance 0, and it stops after that one sweep with f = 0, w = b.
  const Index k = static_cast<Index>(uniform(2, 5));  // contact 0 untouched, the others pulled sideways
  const MatX A = coneMatrix(k);
  VecX b(3 * k), mu(k);
  for (Index c = 0; c < k; ++c) {
    mu(c) = uniform(0.2, 1.0);
    b(3 * c) = c == 0 ? 0.0 : uniform(0.1, 2.0);
    b(3 * c + 1) = c == 0 ? 0.0 : uniform(-2.0, 2.0);  // contact 0: nothing at all, w_T = 0 exactly
    b(3 * c + 2) = c == 0 ? 0.0 : uniform(-2.0, 2.0);
  }
  LcpOptions options;
  options.tolerance = 0.0;
  options.max_iterations = 50;
  const LcpSolution s = solveLcpPgsCone(A, b, mu, options);
  INFO(k << " contacts, f " << s.f.transpose());
  CHECK(s.f == VecX::Zero(3 * k));  // no arithmetic leaves a nonzero entry
  CHECK(s.w == b);                  // A 0 + b
  CHECK(s.iterations == 1);
  CHECK(s.residual == 0.0);
}

TEST_CASE("pgs: the result contract: no sweep at max_iterations <= 0, w of the returned f, tolerance 0 stops on an exact solution", "[lab06][pts=1][sec=5]") {
  const Index n = static_cast<Index>(uniform(4, 12));
  const PlantedLcp p = wellConditioned(n, uniform(1.0, 10.0));
  LcpOptions options;
  options.initial = randomWarmStart(n);
  const VecX start = options.initial.cwiseMax(0.0);  // negative entries count as 0
  // No sweep: the start comes back untouched, measured (residual of the start, w = A f + b)
  options.max_iterations = 0;
  std::vector<double> history;
  const LcpSolution none = solveLcpPgs(p.A, p.b, options, &history);
  CHECK(none.iterations == 0);
  CHECK(history.empty());
  CHECK(none.f == start);  // copied, no arithmetic
  REQUIRE(none.w.size() == n);
  // One matrix-vector product on O(1) numbers in another order: round-off
  CHECK((none.w - (p.A * start + p.b)).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + p.A.cwiseAbs().maxCoeff()));
  CHECK(none.residual == Approx(complementarity(p.A, p.b, start)).epsilon(1e-9).margin(1e-15));
  REQUIRE(none.residual > 0.0);  // random start: not a solution, so a residual of 0 is wrong
  // "max_iterations <= 0": a negative count is no sweep either, not a loop until the tolerance
  options.max_iterations = -static_cast<int>(uniform(1, 10));
  const LcpSolution negative = solveLcpPgs(p.A, p.b, options, &history);
  CHECK(negative.iterations == 0);
  CHECK(history.empty());
  CHECK(negative.f == start);
  CHECK(negative.residual == none.residual);  // the same start measured the same way
  // A few sweeps without converging: w belongs to the returned f, not to the f a sweep ago
  options.max_iterations = static_cast<int>(uniform(1, 4));
  options.tolerance = 0.0;
  const LcpSolution few = solveLcpPgs(p.A, p.b, options);
  INFO("sweeps " << few.iterations << ", residual " << few.residual);
  REQUIRE(few.w.size() == n);
  CHECK((few.w - (p.A * few.f + p.b)).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + p.A.cwiseAbs().maxCoeff()));
  // b >= 0 with a zero entry: every update is max(0, 0 - b_i / a_ii) = 0 exactly, so the first
  // sweep leaves f = 0 with residual max |min(0, b_i)| = 0 exactly, and tolerance 0 stops there
  VecX b(n);
  for (Index i = 0; i < n; ++i) b(i) = i == 1 ? 0.0 : uniform(0.0, 2.0);
  options.initial = VecX();
  options.max_iterations = 50;
  const LcpSolution exact = solveLcpPgs(p.A, b, options);
  CHECK(exact.residual == 0.0);
  CHECK(exact.iterations == 1);
}

TEST_CASE("pgs cone: with max_iterations <= 0 the start comes back projected, residual infinity, w = A f + b", "[lab06][pts=1][sec=6]") {
  const Index k = static_cast<Index>(uniform(1, 4));
  const MatX A = coneMatrix(k);
  VecX b(3 * k), mu(k), start(3 * k);
  for (Index i = 0; i < 3 * k; ++i) {
    b(i) = uniform(-2.0, 2.0);
    start(i) = uniform(-1.0, 1.0);
  }
  for (Index c = 0; c < k; ++c) mu(c) = uniform(0.2, 1.0);
  start(0) = uniform(0.5, 2.0);  // contact 0 pushes: its disc has room
  // The documented start, computed here: f_n >= 0, each f_T scaled onto |f_T| <= mu f_n
  VecX f = start;
  for (Index c = 0; c < k; ++c) {
    f(3 * c) = std::max(0.0, f(3 * c));
    const double radius = mu(c) * f(3 * c), length = f.segment<2>(3 * c + 1).norm();
    if (length > radius) f.segment<2>(3 * c + 1) *= length > 0.0 ? radius / length : 0.0;
  }
  LcpOptions options;
  options.initial = start;
  options.max_iterations = 0;
  const LcpSolution s = solveLcpPgsCone(A, b, mu, options);
  CHECK(s.iterations == 0);
  // "infinity when no sweep ran": no change was measured, so nothing says it converged
  CHECK(s.residual == std::numeric_limits<double>::infinity());
  // One scaling of a 2-vector: round-off
  CHECK((s.f - f).cwiseAbs().maxCoeff() <= 1e-15 * (1.0 + f.cwiseAbs().maxCoeff()));
  REQUIRE(s.w.size() == 3 * k);
  CHECK((s.w - (A * s.f + b)).cwiseAbs().maxCoeff() <= 1e-12);  // w = A f + b, round-off of O(1) sums
  // A negative count is no sweep either, not a loop until the changes are small
  options.max_iterations = -static_cast<int>(uniform(1, 10));
  const LcpSolution negative = solveLcpPgsCone(A, b, mu, options);
  CHECK(negative.iterations == 0);
  CHECK(negative.residual == std::numeric_limits<double>::infinity());
  CHECK(negative.f == s.f);  // the same start, projected the same way
}
