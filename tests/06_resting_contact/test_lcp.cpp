// Lab 6 graded tests of the exact LCP solvers (pivoting and Lemke): one-step oracles, LCPs with
// a planted solution, degenerate and duplicated contacts, problems without a solution, and a
// heavy box on a light one.
#include <cmath>
#include <limits>

#include "lcp_support.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

namespace {

using LcpSolver = LcpSolution (*)(const MatX&, const VecX&, const LcpOptions&);

LcpSolution pivoting(const MatX& A, const VecX& b, const LcpOptions& options) { return solveLcpPivoting(A, b, options); }
LcpSolution lemke(const MatX& A, const VecX& b, const LcpOptions& options) { return solveLcpLemke(A, b, options); }

// b >= 0 (some entries exactly zero): f = 0 solves it; 1 x 1 with b < 0: f = -b / a.
void checkOneStepOracles(LcpSolver solve) {
  {
    const Index n = static_cast<Index>(uniform(2, 8));
    const MatX A = randomSpd(n, 10.0);
    VecX b(n);
    for (Index i = 0; i < n; ++i) b(i) = i == 0 ? 0.0 : uniform(0.0, 2.0);
    INFO("n " << n << ", b >= 0: b = (" << b.transpose() << "), expected f = 0, w = b, no pivot");
    const LcpSolution zero = solve(A, b, {});
    // Nothing to push: no arithmetic on f at all.
    CHECK(zero.f == VecX::Zero(n));
    CHECK(zero.w == b);  // A 0 + b
    CHECK(zero.residual == 0.0);
    // b >= 0 needs no pivot, a b_i of exactly 0 (a contact just touching) included
    CHECK(zero.iterations == 0);
  }
  const double a = uniform(0.1, 10.0), b1 = -uniform(0.1, 10.0);
  INFO("1 x 1: a = " << a << ", b = " << b1 << ", expected f = -b / a = " << -b1 / a);
  const LcpSolution one = solve(MatX::Constant(1, 1, a), VecX::Constant(1, b1), {});
  // One division: exact in binary floating point.
  CHECK(one.f(0) == -b1 / a);
  CHECK(std::abs(one.w(0)) <= 4.5e-16 * std::abs(b1));  // a (-b / a) + b: roundings of quotient and product
  CHECK(one.iterations >= 1);
}

// A = [[2, 1], [1, 2]]: b = (-1, 1) clamps contact 0 alone, f = (1/2, 0), w = (0, 3/2);
// b = (-3, -3) clamps both, f = (1, 1), w = 0.
void checkTwoByTwo(LcpSolver solve) {
  MatX A(2, 2);
  A << 2.0, 1.0, 1.0, 2.0;
  {
    INFO("A = [[2, 1], [1, 2]], b = (-1, 1): expected f = (1/2, 0), w = (0, 3/2)");
    const LcpSolution one = solve(A, VecX((VecX(2) << -1.0, 1.0).finished()), {});
    // A handful of operations on small integers: a few ulps at most.
    CHECK(std::abs(one.f(0) - 0.5) <= 4e-16);
    CHECK(one.f(1) == 0.0);  // a free contact's force is never touched
    CHECK(std::abs(one.w(1) - 1.5) <= 4e-16);
  }
  INFO("A = [[2, 1], [1, 2]], b = (-3, -3): expected f = (1, 1), w = 0");
  const LcpSolution both = solve(A, VecX::Constant(2, -3.0), {});
  CHECK((both.f - VecX::Ones(2)).cwiseAbs().maxCoeff() <= 4e-16);
  CHECK(both.w.cwiseAbs().maxCoeff() <= 1e-15);
}

// A planted LCP on an SPD (unique solution) or P-matrix: the solver must return f* itself.
void checkPlanted(LcpSolver solve, const PlantedLcp& p, double cond) {
  const Index n = p.A.rows();
  INFO("n " << n << ", cond " << cond << ", active " << p.active << ", free " << p.free << ", degenerate "
            << p.degenerate << ", planted f* = (" << p.f.transpose() << ")");
  const LcpSolution s = solve(p.A, p.b, {});
  INFO("pivots " << s.iterations << ", |f - f*| " << (s.f - p.f).cwiseAbs().maxCoeff());
  REQUIRE(s.f.size() == n);
  REQUIRE(s.w.size() == n);
  // Backward-stable pivoting: error of order eps * cond(A) * |f*| per pivot, with margin
  const double scale = std::max(1.0, std::max(p.f.cwiseAbs().maxCoeff(), p.w.cwiseAbs().maxCoeff()));
  const double tol = 1e-13 * cond * static_cast<double>(n) * scale;
  CHECK((s.f - p.f).cwiseAbs().maxCoeff() <= tol);
  CHECK((s.w - p.w).cwiseAbs().maxCoeff() <= tol * p.A.cwiseAbs().maxCoeff());
  CHECK(s.f.minCoeff() >= 0.0);  // the contract: f >= 0, round-off included
  // w reported as A f + b of the returned f (to round-off of the product)
  CHECK((s.w - (p.A * s.f + p.b)).cwiseAbs().maxCoeff() <= 1e-13 * scale * p.A.cwiseAbs().maxCoeff());
  CHECK(complementarity(p.A, p.b, s.f) <= tol * p.A.cwiseAbs().maxCoeff());
  CHECK(s.residual == Approx(lcpResidual(p.A, p.b, s.f)).epsilon(1e-9).margin(1e-15));  // the same measure
  // Every contact that pushes entered the clamped set (or the basis) by a pivot of its own
  CHECK(s.iterations >= p.active);
}

// Contacts of a 6-dof body (M = masses and inertias) in random directions, some duplicated
// (a box corner counted twice) and more contacts than degrees of freedom: A = J M^-1 J^T is
// only positive semidefinite, so f is not unique, but w and the generalized force J^T f are.
struct DuplicatedContacts {
  MatX J, A;
  VecX b, f, w;
};

DuplicatedContacts duplicatedContacts() {
  const Index base = static_cast<Index>(uniform(4, 9)), copies = static_cast<Index>(uniform(1, 4));
  const Index n = base + copies;
  DuplicatedContacts s;
  s.J.resize(n, 6);
  for (Index i = 0; i < base; ++i) {
    for (Index j = 0; j < 6; ++j) s.J(i, j) = uniform(-1.0, 1.0);
  }
  std::vector<Index> original(static_cast<std::size_t>(n));
  for (Index i = base; i < n; ++i) {
    original[static_cast<std::size_t>(i)] = static_cast<Index>(uniform(0, static_cast<double>(base)));
    s.J.row(i) = s.J.row(original[static_cast<std::size_t>(i)]);
  }
  VecX m_inv(6);
  for (Index j = 0; j < 6; ++j) m_inv(j) = 1.0 / uniform(0.5, 5.0);
  s.A = s.J * m_inv.asDiagonal() * s.J.transpose();
  // Plant on the distinct contacts; a copy has its original's w and shares its force
  const PlantedLcp p = plantSolution(s.A.topLeftCorner(base, base));
  s.f = VecX::Zero(n);
  s.w = VecX::Zero(n);
  s.f.head(base) = p.f;
  s.w.head(base) = p.w;
  for (Index i = base; i < n; ++i) {
    const Index o = original[static_cast<std::size_t>(i)];
    s.w(i) = s.w(o);
    const double share = uniform(0.0, 1.0) * s.f(o);
    s.f(i) = share;
    s.f(o) -= share;
  }
  s.b = s.w - s.A * s.f;
  for (Index i = base; i < n; ++i) s.b(i) = s.b(original[static_cast<std::size_t>(i)]);  // identical rows
  return s;
}

void checkDuplicated(LcpSolver solve) {
  const DuplicatedContacts s = duplicatedContacts();
  INFO(s.A.rows() << " contacts on 6 dofs, some rows repeated (A singular PSD: only w and J^T f are unique), "
       "expected w = (" << s.w.transpose() << ")");
  const LcpSolution r = solve(s.A, s.b, {});
  INFO("pivots " << r.iterations << ", w = (" << r.w.transpose() << ")");
  // The planted f is one of many: compare only what is unique. A and J are O(1), but random
  // contact directions in 6-D are at times nearly dependent (clamped blocks with condition up
  // to ~1e7): 1e-8 is round-off times that, while a wrong answer is off by O(1).
  CHECK(r.f.minCoeff() >= 0.0);
  CHECK(complementarity(s.A, s.b, r.f) <= 1e-8);
  CHECK((r.w - s.w).cwiseAbs().maxCoeff() <= 1e-8);
  CHECK((s.J.transpose() * (r.f - s.f)).cwiseAbs().maxCoeff() <= 1e-8);
  CHECK(r.residual <= 1e-8);
}

// Two point masses stacked on the ground, heavy on light: contact 0 ground-light, contact 1
// light-heavy. Velocities (v_light, v_heavy), J = [[1, 0], [-1, 1]], A = J M^-1 J^T,
// b = J M^-1 (-m g) = (-g, 0). The exact answer holds both: f = (m_l + m_h, m_h) g, w = 0.
struct Stack {
  MatX A;
  VecX b, f;
};

Stack heavyOnLightLcp(double ratio) {
  const double m_light = uniform(0.5, 2.0), m_heavy = ratio * m_light, g = uniform(5.0, 15.0);
  MatX J(2, 2);
  J << 1.0, 0.0, -1.0, 1.0;
  const VecX m_inv = (VecX(2) << 1.0 / m_light, 1.0 / m_heavy).finished();
  Stack s;
  s.A = J * m_inv.asDiagonal() * J.transpose();
  s.b = J * VecX::Constant(2, -g);
  s.f = (VecX(2) << (m_light + m_heavy) * g, m_heavy * g).finished();
  return s;
}

}  // namespace

TEST_CASE("pivoting: one-step oracles, b >= 0 gives f = 0 exactly and 1 x 1 gives f = -b / a exactly", "[lab06][pts=1][sec=3]") {
  checkOneStepOracles(pivoting);
  checkTwoByTwo(pivoting);
}

TEST_CASE("lemke: one-step oracles, b >= 0 gives f = 0 exactly and 1 x 1 gives f = -b / a exactly", "[lab06][pts=1][sec=4]") {
  checkOneStepOracles(lemke);
  checkTwoByTwo(lemke);
}

TEST_CASE("pivoting: recovers the planted solution of random SPD LCPs, degenerate contacts included", "[lab06][pts=3][sec=3]") {
  for (int trial = 0; trial < 20; ++trial) {
    const Index n = static_cast<Index>(uniform(3, 25));
    const double cond = std::exp(uniform(0.0, std::log(1e4)));
    checkPlanted(pivoting, plantSolution(randomSpd(n, cond, uniform(0.01, 100.0))), cond);
  }
}

TEST_CASE("lemke: recovers the planted solution of random SPD LCPs, degenerate contacts included", "[lab06][pts=3][sec=4]") {
  for (int trial = 0; trial < 20; ++trial) {
    const Index n = static_cast<Index>(uniform(3, 25));
    const double cond = std::exp(uniform(0.0, std::log(1e4)));
    checkPlanted(lemke, plantSolution(randomSpd(n, cond, uniform(0.01, 100.0))), cond);
  }
}

TEST_CASE("lemke: recovers the planted solution of non-symmetric P-matrix LCPs", "[lab06][pts=2][sec=4]") {
  for (int trial = 0; trial < 20; ++trial) {
    const Index n = static_cast<Index>(uniform(3, 20));
    const MatX A = randomPMatrix(n, 10.0, uniform(0.5, 3.0));
    checkPlanted(lemke, plantSolution(A), conditionNumber(A));
  }
}

TEST_CASE("pivoting: recovers the planted solution of non-symmetric P-matrix LCPs", "[lab06][pts=1][sec=3]") {
  for (int trial = 0; trial < 20; ++trial) {
    const Index n = static_cast<Index>(uniform(3, 20));
    const MatX A = randomPMatrix(n, 10.0, uniform(0.5, 3.0));
    checkPlanted(pivoting, plantSolution(A), conditionNumber(A));
  }
}

TEST_CASE("pivoting: duplicated contacts (singular PSD A) still get a valid solution", "[lab06][pts=1][sec=3]") {
  for (int trial = 0; trial < 20; ++trial) checkDuplicated(pivoting);
}

TEST_CASE("lemke: duplicated contacts (singular PSD A) still get a valid solution", "[lab06][pts=1][sec=4]") {
  for (int trial = 0; trial < 20; ++trial) checkDuplicated(lemke);
}

TEST_CASE("lemke: an LCP without a solution ends in ray termination (LcpFailure)", "[lab06][pts=2][sec=4]") {
  // PSD A = a [[1, -1], [-1, 1]], b < 0: w_0 + w_1 = b_0 + b_1 < 0 for every f, so no w >= 0
  const double a = uniform(0.1, 10.0);
  MatX A(2, 2);
  A << a, -a, -a, a;
  const VecX b = (VecX(2) << -uniform(0.1, 2.0), -uniform(0.1, 2.0)).finished();
  CHECK_THROWS_AS(solveLcpLemke(A, b), LcpFailure);
  CHECK_THROWS_WITH(solveLcpLemke(A, b), Contains("ray"));
  // A row with no positive entry and b_i < 0: w_i < 0 whatever f >= 0 is (any other rows)
  for (int trial = 0; trial < 20; ++trial) {
    const Index n = static_cast<Index>(uniform(2, 8)), row = static_cast<Index>(uniform(0, static_cast<double>(n)));
    MatX M = randomSpd(n, 10.0) + MatX::Identity(n, n) * uniform(0.0, 1.0);
    VecX q(n);
    for (Index i = 0; i < n; ++i) q(i) = uniform(-1.0, 1.0);
    for (Index j = 0; j < n; ++j) M(row, j) = -uniform(0.0, 1.0);
    q(row) = -uniform(0.1, 1.0);
    INFO("n " << n << ", infeasible row " << row);
    CHECK_THROWS_WITH(solveLcpLemke(M, q), Contains("ray"));
    CHECK_THROWS_AS(solveLcpLemke(M, q), LcpFailure);
  }
}

TEST_CASE("pivoting: a singular pivot throws LcpFailure instead of returning NaN", "[lab06][pts=1][sec=3]") {
  // 1 x 1, a = 0, b < 0: w = b whatever f is, no step can reach w = 0
  CHECK_THROWS_AS(solveLcpPivoting(MatX::Zero(1, 1), VecX::Constant(1, -uniform(0.1, 2.0))), LcpFailure);
  // Clamping contact 0 leaves contact 1 a zero Schur complement: driving f_1 moves nothing
  const double a = uniform(0.1, 10.0);
  MatX A(2, 2);
  A << a, -a, -a, a;
  const VecX b = (VecX(2) << -uniform(0.1, 2.0), -uniform(0.1, 2.0)).finished();
  CHECK_THROWS_AS(solveLcpPivoting(A, b), LcpFailure);
}

TEST_CASE("pivoting and lemke: a heavy box on a light one is held exactly, where 10 PGS sweeps are far off", "[lab06][pts=2][sec=3][sec=4]") {
  const Stack s = heavyOnLightLcp(100.0);
  LcpOptions few;
  few.max_iterations = 10;
  few.tolerance = 0.0;
  INFO("two point masses, the upper 100 times the lower: expected f = (" << s.f.transpose() << "), w = 0");
  const LcpSolution piv = solveLcpPivoting(s.A, s.b), lem = solveLcpLemke(s.A, s.b), pgs = solveLcpPgs(s.A, s.b, few);
  const double weight = s.f(0);
  const double error_pivoting = (piv.f - s.f).cwiseAbs().maxCoeff() / weight;
  const double error_lemke = (lem.f - s.f).cwiseAbs().maxCoeff() / weight;
  const double error_pgs = (pgs.f - s.f).cwiseAbs().maxCoeff() / weight;
  INFO("relative force errors: pivoting " << error_pivoting << ", lemke " << error_lemke << ", pgs(10) " << error_pgs);
  // cond(A) ~ 4 x 100 (mass ratio): exact solvers are off by round-off times that
  CHECK(error_pivoting <= 1e-12);
  CHECK(error_lemke <= 1e-12);
  // Both contacts held: w = 0 up to round-off on accelerations of size g
  CHECK(piv.w.cwiseAbs().maxCoeff() <= 1e-12 * std::abs(s.b(0)) * 100.0);
  CHECK(lem.w.cwiseAbs().maxCoeff() <= 1e-12 * std::abs(s.b(0)) * 100.0);
  // PGS contracts by m_h / (m_l + m_h) = 100/101 a sweep: after 10 most of the error remains
  CHECK(pgs.iterations == 10);
  CHECK(error_pgs >= 0.5);
  CHECK(error_pgs > 1e6 * std::max({error_pivoting, error_lemke, 1e-16}));
}

TEST_CASE("pivoting: the same LCP in other units (A and b times 1e-14 or 1e14) has the same solution", "[lab06][pts=1][sec=3]") {
  // w = s (A f + b): scaling A and b together scales w and leaves f unchanged, for any s > 0.
  // The sign test on w_d is relative to A's scale (pivot_tolerance times the largest |a_ij|): an
  // absolute pivot_tolerance would take every w of the problem scaled by 1e-14 for zero.
  for (const double s : {1e-14, 1e14}) {
    for (int trial = 0; trial < 10; ++trial) {
      const Index n = static_cast<Index>(uniform(3, 15));
      const double cond = std::exp(uniform(0.0, std::log(100.0)));
      const PlantedLcp p = plantSolution(randomSpd(n, cond));
      const LcpSolution r = solveLcpPivoting(s * p.A, s * p.b);
      INFO("scale " << s << ", n " << n << ", cond " << cond << ", active " << p.active << ", pivots " << r.iterations);
      // As in the planted test: eps * cond * |f*| per pivot with margin, f* and w* of order 1
      const double tol = 1e-13 * cond * static_cast<double>(n) * std::max(1.0, p.f.cwiseAbs().maxCoeff());
      CHECK((r.f - p.f).cwiseAbs().maxCoeff() <= tol);
      CHECK((r.w - s * p.w).cwiseAbs().maxCoeff() <= s * tol * p.A.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("pivoting and lemke: iterations count every pivot, counted by hand", "[lab06][pts=1][sec=3][sec=4]") {
  // 1 x 1, b < 0. Pivoting: one step of f_0, which d itself blocks (1 pivot). Lemke: z0 enters
  // in row 0, then f_0 enters and z0 leaves (2 pivots).
  const double a = uniform(0.1, 10.0), b1 = -uniform(0.1, 10.0);
  CHECK(solveLcpPivoting(MatX::Constant(1, 1, a), VecX::Constant(1, b1)).iterations == 1);
  CHECK(solveLcpLemke(MatX::Constant(1, 1, a), VecX::Constant(1, b1)).iterations == 2);
  // A = [[1, c], [c, 1]], b = (-1, -2), c = 0.9. Pivoting takes contact 1 first (w_1 = -2 is the
  // most negative): f_1 alone rises to 2, where w_1 = 0 (1 pivot; contact 0, not yet taken, is
  // in no ratio test); then w_0 = -1 + 2c = 0.8 >= 0 and contact 0 joins the free set with no
  // pivot. f = (0, 2). Lemke: z0 enters at row 1 (b_1 most negative): z0 = 2, w_0 = 1; f_1
  // enters, ratios 1/(1 - c) = 10 for w_0 and 2 for z0: z0 leaves (2 pivots), f = (0, 2).
  const double c = 0.9;
  MatX A(2, 2);
  A << 1.0, c, c, 1.0;
  const VecX b = (VecX(2) << -1.0, -2.0).finished();
  const LcpSolution piv = solveLcpPivoting(A, b), lem = solveLcpLemke(A, b);
  CHECK(piv.iterations == 1);
  CHECK(lem.iterations == 2);
  // A few operations on numbers of order 1: a few ulps
  const VecX f = (VecX(2) << 0.0, 2.0).finished();
  CHECK((piv.f - f).cwiseAbs().maxCoeff() <= 4e-15);
  CHECK((lem.f - f).cwiseAbs().maxCoeff() <= 4e-15);
  CHECK(piv.w(0) == Approx(2.0 * c - 1.0).epsilon(1e-14));
  // b = (-1, -0.95): contact 0 first, f_0 = 1 (pivot 1), leaving w_1 = -0.95 + c = -0.05. Driving
  // f_1 moves f_0 by -c (df = (-c, 1), dw_1 = 1 - c^2 = 0.19): w_1 reaches 0 at f_1 = 0.05 / 0.19,
  // before f_0 reaches 0 at 1 / c (pivot 2). f = A^-1 (1, 0.95) = (0.145, 0.05) / 0.19.
  const VecX b2 = (VecX(2) << -1.0, -0.95).finished();
  const LcpSolution two = solveLcpPivoting(A, b2);
  CHECK(two.iterations == 2);
  CHECK((two.f - (VecX(2) << 0.145, 0.05).finished() / 0.19).cwiseAbs().maxCoeff() <= 4e-15);
  // b >= 0: f = 0 solves it with no pivot at all
  CHECK(solveLcpPivoting(A, -b).iterations == 0);
  CHECK(solveLcpLemke(A, -b).iterations == 0);
  // b = (1, -1): contact 1 is taken first and driven alone (df = (0, 1)): 1 pivot, f = (0, 1),
  // and w_0 grows by c to 1 + c, so contact 0 joins the free set with f_0 never touched.
  const VecX free_first = (VecX(2) << 1.0, -1.0).finished();
  const LcpSolution one_free = solveLcpPivoting(A, free_first);
  CHECK(one_free.iterations == 1);
  CHECK(one_free.f(0) == 0.0);
  CHECK(std::abs(one_free.f(1) - 1.0) <= 4e-16);  // one quotient of 1s: exact, an ulp of margin
  CHECK(std::abs(one_free.w(0) - (1.0 + c)) <= 4e-16);  // one product and one sum
  // Lemke, z0 tied for leaving: A = [[2, 1], [1, 2]], b = (-2, -1). z0 enters at row 0 (z0 = 2,
  // w_1 = 1); f_0 enters with ratios 2 / 2 for z0 and 1 / (2 - 1) for w_1: a tie, and z0 leaves
  // (2 pivots) at f = (1, 0), w = (0, 0). Letting w_1 leave instead keeps z0 basic at 0 for a
  // third, degenerate pivot.
  MatX T(2, 2);
  T << 2.0, 1.0, 1.0, 2.0;
  const LcpSolution tie = solveLcpLemke(T, (VecX(2) << -2.0, -1.0).finished());
  CHECK(tie.iterations == 2);
  CHECK((tie.f - (VecX(2) << 1.0, 0.0).finished()).cwiseAbs().maxCoeff() <= 4e-16);  // halves and ones
  CHECK(tie.w.cwiseAbs().maxCoeff() <= 4e-16);
}

TEST_CASE("lemke: ties that the ratio and the first column of B^-1 leave are broken by the next column (hand-traced degenerate LCPs)", "[lab06][pts=1][sec=4]") {
  // In both LCPs z0 enters at row 0 (the most negative b) and leaves rows 1 and 2 with equal
  // values, so the entering f0 finds them tied in the ratio; their rows of B^-1 = I - e e_0^T,
  // (-1, 1, 0) and (-1, 0, 1) over equal entries of the column, tie in the first column too: only
  // the second tells them apart (0 < 1: row 2, w2 leaves), and it decides the run. Small
  // integers, halves and thirds: every tie is exact in floating point too.
  // A = [[1, -1, 1], [-2, 0, 0], [-2, 1, -1]] (not PSD), b = (-1, 1, 1): z0 = 1, w1 = w2 = 2; f0
  // enters with column (1, 3, 3): ratios 1, 2/3, 2/3; first column -1/3, -1/3; second 1/3, 0:
  // w2 leaves. f2 enters, z0 and f0 tie at ratio 1 and z0 leaves: 3 pivots, f = (0, 0, 1),
  // w = (0, 1, 0). Letting w1 leave instead puts z0, f0 and w2 (= 0) in the basis, and f1,
  // entering next, has no positive entry: ray termination on an LCP that has a solution.
  {
    MatX A(3, 3);
    A << 1.0, -1.0, 1.0, -2.0, 0.0, 0.0, -2.0, 1.0, -1.0;
    const VecX b = (VecX(3) << -1.0, 1.0, 1.0).finished();
    INFO("A = [[1, -1, 1], [-2, 0, 0], [-2, 1, -1]], b = (-1, 1, 1): expected 3 pivots, f = (0, 0, 1), w = (0, 1, 0)");
    const LcpSolution s = solveLcpLemke(A, b);
    CHECK(s.iterations == 3);
    // Thirds and their multiples, a few operations each: a few ulps
    CHECK((s.f - (VecX(3) << 0.0, 0.0, 1.0).finished()).cwiseAbs().maxCoeff() <= 1e-15);
    CHECK((s.w - (VecX(3) << 0.0, 1.0, 0.0).finished()).cwiseAbs().maxCoeff() <= 1e-15);
  }
  // A = [[1, 0, 0], [0, 2, 1], [0, 3, 2]] (a P-matrix: one solution), b = (-2, -1, -1): z0 = 2,
  // w1 = w2 = 1; f0 enters with column (1, 1, 1): ratios 2, 1, 1; first column -1, -1; second
  // 1, 0: w2 leaves (f0 = 1, w1 = 0). Then f2 enters and the degenerate w1 leaves (ratio 0), f1
  // enters and f2 leaves (ratio 0), w2 enters and z0 leaves: 5 pivots, f = (2, 1/2, 0),
  // w = (0, 0, 1/2). Letting w1 leave at the tie reaches the same f in 3.
  {
    MatX A(3, 3);
    A << 1.0, 0.0, 0.0, 0.0, 2.0, 1.0, 0.0, 3.0, 2.0;
    const VecX b = (VecX(3) << -2.0, -1.0, -1.0).finished();
    INFO("A = [[1, 0, 0], [0, 2, 1], [0, 3, 2]], b = (-2, -1, -1): expected 5 pivots, f = (2, 1/2, 0), w = (0, 0, 1/2)");
    const LcpSolution s = solveLcpLemke(A, b);
    CHECK(s.iterations == 5);
    // Halves and small integers: a few ulps
    CHECK((s.f - (VecX(3) << 2.0, 0.5, 0.0).finished()).cwiseAbs().maxCoeff() <= 1e-15);
    CHECK((s.w - (VecX(3) << 0.0, 0.0, 0.5).finished()).cwiseAbs().maxCoeff() <= 1e-15);
  }
}
