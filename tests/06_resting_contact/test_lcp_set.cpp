// Lab 6 graded tests: a standard set of small LCPs from the literature for the exact solvers
// (pivoting, section 3; Lemke, section 4). Murty's exponential example with the pivots counted,
// P-matrices against the enumeration of every complementary basis, degenerate problems (ties in
// the ratio test, contacts with f = w = 0), positive semidefinite singular problems that have a
// solution, and problems with none. Each answer is checked for what the solver reports against
// what it did: f >= 0, w = A f + b >= 0 and f^T w = 0 to a stated tolerance, the residual it
// returns, and its pivot count.
#include <cmath>
#include <string>

#include "lcp_support.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

// (a namespace of its own: the unity build compiles this file with the other LCP tests)
namespace lcp_set {

using LcpSolver = LcpSolution (*)(const MatX&, const VecX&, const LcpOptions&);

LcpSolution pivoting(const MatX& A, const VecX& b, const LcpOptions& options) { return solveLcpPivoting(A, b, options); }
LcpSolution lemke(const MatX& A, const VecX& b, const LcpOptions& options) { return solveLcpLemke(A, b, options); }

// What an exact solver reports is what it did: f >= 0 exactly (the contract clamps round-off),
// w is A f + b of that f, w >= -tol, |f^T w| <= tol (f w summed over the contacts), the
// residual is lcpResidual() of f, and the pivots stay within the limit max(100, 10 n).
void checkReport(const MatX& A, const VecX& b, const LcpSolution& s, double tol) {
  const Index n = b.size();
  INFO("n " << n << ", pivots " << s.iterations << ", residual " << s.residual);
  REQUIRE(s.f.size() == n);
  REQUIRE(s.w.size() == n);
  CHECK(s.f.minCoeff() >= 0.0);
  // w of the returned f, up to the rounding of one product A f + b
  const double size = std::max(1.0, b.cwiseAbs().maxCoeff() + A.cwiseAbs().maxCoeff() * s.f.cwiseAbs().sum());
  CHECK((s.w - (A * s.f + b)).cwiseAbs().maxCoeff() <= 1e-15 * static_cast<double>(n) * size);
  CHECK(s.w.minCoeff() >= -tol);
  CHECK(std::abs(s.f.dot(s.w)) <= tol * std::max(1.0, s.f.sum()));
  CHECK(complementarity(A, b, s.f) <= tol);
  CHECK(s.residual == Approx(complementarity(A, b, s.f)).epsilon(1e-9).margin(1e-300));
  CHECK(s.iterations >= 0);
  CHECK(s.iterations <= std::max(100, static_cast<int>(10 * n)));
}

// Murty's example for n = 1..10: the exact pivot count of the handout's rule, and the answer of
// the enumeration oracle (n <= 8) and of the closed form f = 2^n e_{n-1}.
void checkMurty(LcpSolver solve, long extra) {
  for (Index n = 1; n <= 10; ++n) {
    const PlantedMurty m = murtyExample(n);
    LcpOptions options;
    options.max_iterations = 1 << 11;  // past 10 n: the pivots grow like 2^n here
    INFO("Murty's example, n " << n << ": b = (" << m.b.transpose() << "), expected f = (" << m.f.transpose() << ")");
    const LcpSolution s = solve(m.A, m.b, options);
    INFO("pivots " << s.iterations);
    CHECK(s.iterations == (1l << n) - 1 + extra);
    // Integers below 2^12 on a triangular matrix: every operation is exact
    CHECK((s.f - m.f).cwiseAbs().maxCoeff() == 0.0);
    CHECK(s.residual == 0.0);
    if (n <= 8) {
      const std::vector<VecX> oracle = complementarySolutions(m.A, m.b, 1e-9);
      REQUIRE(oracle.size() == 1);  // a P-matrix: one solution
      CHECK((oracle[0] - m.f).cwiseAbs().maxCoeff() <= 1e-9);  // a QR solve of integers below 2^10
    }
  }
}

// A P-matrix LCP, n <= 8, against the one complementary basis the oracle finds.
void checkAgainstOracle(LcpSolver solve, const MatX& A, const VecX& b) {
  const Index n = b.size();
  // Entries O(1), condition up to 100: a feasible basis is feasible by far more than 1e-9
  const std::vector<VecX> oracle = complementarySolutions(A, b, 1e-9);
  REQUIRE(oracle.size() == 1);
  INFO("n " << n << ", b = (" << b.transpose() << "), the oracle's f = (" << oracle[0].transpose() << ")");
  const LcpSolution s = solve(A, b, {});
  INFO("pivots " << s.iterations << ", |f - oracle| " << (s.f - oracle[0]).cwiseAbs().maxCoeff());
  // Both are backward stable on condition <= 100 and |f| <= 10: a few hundred ulps of |f|
  CHECK((s.f - oracle[0]).cwiseAbs().maxCoeff() <= 1e-11 * std::max(1.0, oracle[0].cwiseAbs().maxCoeff()));
  checkReport(A, b, s, 1e-11);
}

void checkPMatrices(LcpSolver solve) {
  // Fixed: a non-symmetric P-matrix (symmetric part 2 I plus a skew part) where one contact
  // pulls on another, b of both signs
  MatX A(3, 3);
  A << 2.0, 1.0, 0.0, -1.0, 2.0, 1.0, 0.0, -1.0, 2.0;
  checkAgainstOracle(solve, A, (VecX(3) << -1.0, 1.0, -2.0).finished());
  // Seeded: random P-matrices with random b, n = 1..8
  for (int trial = 0; trial < 20; ++trial) {
    const Index n = static_cast<Index>(uniform(1, 9));
    const MatX P = randomPMatrix(n, 100.0, 0.5);
    VecX b(n);
    for (Index i = 0; i < n; ++i) b(i) = uniform(-2.0, 2.0);
    checkAgainstOracle(solve, P, b);
  }
}

// Degenerate problems: ties in the ratio test and contacts with f = w = 0 at the answer.
void checkDegenerate(LcpSolver solve) {
  // A cyclic P-matrix with b = -e: every row ties for the first pivot; f = e / 3, w = 0
  {
    MatX C(3, 3);
    C << 1.0, 2.0, 0.0, 0.0, 1.0, 2.0, 2.0, 0.0, 1.0;
    INFO("A = [[1, 2, 0], [0, 1, 2], [2, 0, 1]], b = (-1, -1, -1): expected f = (1/3, 1/3, 1/3), w = 0");
    const LcpSolution cyclic = solve(C, -VecX::Ones(3), {});
    CHECK((cyclic.f - VecX::Constant(3, 1.0 / 3.0)).cwiseAbs().maxCoeff() <= 4e-16);  // thirds: an ulp or two
    checkReport(C, -VecX::Ones(3), cyclic, 1e-15);
  }
  // Two identical contacts, b equal: the two ratios tie exactly; any split of f_0 + f_1 = 1
  {
    MatX D(2, 2);
    D << 1.0, 1.0, 1.0, 1.0;
    INFO("A = [[1, 1], [1, 1]], b = (-1, -1): expected f_0 + f_1 = 1, w = 0");
    const LcpSolution twin = solve(D, -VecX::Ones(2), {});
    CHECK(std::abs(twin.f.sum() - 1.0) <= 4e-16);  // sums and quotients of ones
    checkReport(D, -VecX::Ones(2), twin, 4e-16);
  }
  // b with zeros: contacts just touching (w = 0 with f = 0 allowed) tie at step 0
  for (int trial = 0; trial < 10; ++trial) {
    const Index n = static_cast<Index>(uniform(2, 9));
    const MatX A = randomSpd(n, 10.0);
    VecX b(n);
    for (Index i = 0; i < n; ++i) b(i) = i % 2 == 0 ? 0.0 : -uniform(0.5, 1.5);
    INFO("n " << n << ", b with zeros: b = (" << b.transpose() << ")");
    checkReport(A, b, solve(A, b, {}), 1e-12);  // condition 10, O(1) entries: round-off
  }
  // Planted: every contact degenerate (f* = w* = 0, so b = 0) but one active pair
  for (int trial = 0; trial < 10; ++trial) {
    const Index n = static_cast<Index>(uniform(3, 9));
    const MatX A = randomSpd(n, 10.0);
    VecX f = VecX::Zero(n);
    f(0) = uniform(0.5, 1.5);
    f(n - 1) = uniform(0.5, 1.5);
    VecX b = -A * f;  // w* = 0 everywhere: every other contact is degenerate
    INFO("n " << n << ", every contact degenerate but two: planted f* = (" << f.transpose() << "), w* = 0");
    const LcpSolution s = solve(A, b, {});
    CHECK((s.f - f).cwiseAbs().maxCoeff() <= 1e-12);  // SPD: unique; condition 10
    checkReport(A, b, s, 1e-12);
  }
}

// Positive semidefinite and singular, yet solvable: w is unique (A f is), f is not.
void checkPsdSingular(LcpSolver solve) {
  // Fixed: A = [[1, -1], [-1, 1]], b = (-1, 1): w = 0 for f_0 - f_1 = 1, e.g. f = (1, 0)
  {
    MatX A(2, 2);
    A << 1.0, -1.0, -1.0, 1.0;
    const VecX b = (VecX(2) << -1.0, 1.0).finished();
    INFO("A = [[1, -1], [-1, 1]], b = (-1, 1): expected f_0 - f_1 = 1, w = 0");
    const LcpSolution fixed = solve(A, b, {});
    CHECK(std::abs(fixed.f(0) - fixed.f(1) - 1.0) <= 4e-16);  // integers
    checkReport(A, b, fixed, 4e-16);
  }
  // Fixed: two rank-2 problems of that kind (below) where such a tie goes the wrong way by the
  // last bit unless it is taken within round-off: the reference without it ended the first on
  // a singular A_CC (pivoting) and the second on a false ray (Lemke)
  const MatX tie_A[2] = {
      (MatX(4, 4) << 0.18976717727456896, -0.17022862859666821, 0.24347639944347618, 0.15059361384480541,
       -0.17022862859666821, 0.26773714968653367, -0.30247336796644703, 0.041365485959415804,
       0.24347639944347618, -0.30247336796644703, 0.37382006099636828, 0.064266835613304679,
       0.15059361384480541, 0.041365485959415804, 0.064266835613304679, 0.39017098941879813).finished(),
      (MatX(4, 4) << 0.72877930038206262, -0.43662718839991049, -0.59817032070178755, -0.32669819038000725,
       -0.43662718839991049, 0.39234882249114539, 0.36054640602303423, -0.13881838198160246,
       -0.59817032070178755, 0.36054640602303423, 0.49100457963090138, 0.26259691428847387,
       -0.32669819038000725, -0.13881838198160246, 0.26259691428847387, 1.0024263946735013).finished()};
  const VecX tie_b[2] = {
      (VecX(4) << -0.24683537281195478, 0.1667929302993536, -0.27677534106322416, 1.5280916927443862).finished(),
      (VecX(4) << 0.56500761807199917, 0.33607377334666683, -0.46381924620060955, -0.24247629181134556).finished()};
  for (int k = 0; k < 2; ++k) {
    INFO("fixed tie " << k);
    checkReport(tie_A[k], tie_b[k], solve(tie_A[k], tie_b[k], {}), 1e-12);  // O(1) entries, a few pivots: round-off
  }
  // Seeded: A = B B^T of rank r < n, a planted complementary pair. A degenerate contact whose
  // row depends on others reaches 0 with the driven contact (pivoting) or with z0 (Lemke) in
  // exact arithmetic: the ties within round-off of the contract decide it (a comparison of the
  // last bit ended 2% of seeds on a singular A_CC or a false ray)
  for (int trial = 0; trial < 10; ++trial) {
    const Index n = static_cast<Index>(uniform(3, 9)), r = static_cast<Index>(uniform(1, static_cast<double>(n)));
    MatX B(n, r);
    for (Index i = 0; i < n; ++i) {
      for (Index j = 0; j < r; ++j) B(i, j) = uniform(-1.0, 1.0);
    }
    const PlantedLcp p = plantSolution(B * B.transpose());
    INFO("A of rank " << r << " of " << n << ", expected the unique w = (" << p.w.transpose() << ")");
    const LcpSolution s = solve(p.A, p.b, {});
    // Random rows in r dimensions are at times nearly dependent: round-off times a clamped
    // block's condition (up to ~1e6 here), while a wrong answer is off by O(1)
    CHECK((s.w - p.w).cwiseAbs().maxCoeff() <= 1e-8);
    checkReport(p.A, p.b, s, 1e-8);
  }
}

// No solution: the solver throws LcpFailure, never returns an answer.
void checkInfeasible(LcpSolver solve, const std::string& reason) {
  // Fixed: w_0 + w_1 = -2 whatever f is
  MatX A(2, 2);
  A << 1.0, -1.0, -1.0, 1.0;
  CHECK_THROWS_WITH(solve(A, -VecX::Ones(2), {}), Contains(reason));
  // 1 x 1 zero matrix with b < 0
  CHECK_THROWS_AS(solve(MatX::Zero(1, 1), -VecX::Ones(1), {}), LcpFailure);
  // Seeded, with a Farkas certificate: u > 0, A u = 0 (A = B B^T, B's columns orthogonal to u)
  // and u^T b < 0, so u^T w = (A u)^T f + u^T b < 0 for every f: no w >= 0
  for (int trial = 0; trial < 10; ++trial) {
    const Index n = static_cast<Index>(uniform(2, 9)), r = static_cast<Index>(uniform(1, static_cast<double>(n)));
    VecX u(n);
    for (Index i = 0; i < n; ++i) u(i) = uniform(0.5, 1.5);
    MatX B(n, r);
    for (Index i = 0; i < n; ++i) {
      for (Index j = 0; j < r; ++j) B(i, j) = uniform(-1.0, 1.0);
    }
    B -= u * (u.transpose() * B) / u.squaredNorm();
    const MatX P = B * B.transpose();
    VecX b(n);
    for (Index i = 0; i < n; ++i) b(i) = uniform(-1.0, 1.0);
    b -= u * ((u.dot(b) + 0.5) / u.squaredNorm());  // u^T b = -0.5
    INFO("n " << n << ", rank " << r);
    REQUIRE((P * u).cwiseAbs().maxCoeff() <= 1e-12);
    CHECK_THROWS_AS(solve(P, b, {}), LcpFailure);
  }
}

}  // namespace lcp_set

using lcp_set::checkMurty;
using lcp_set::checkPMatrices;
using lcp_set::checkDegenerate;
using lcp_set::checkPsdSingular;
using lcp_set::checkInfeasible;

TEST_CASE("pivoting: Murty's exponential example takes 2^n - 1 pivots (n = 1..10), and its answer is the oracle's", "[lab06][pts=1][sec=3]") {
  // The most negative w is driven first, ties to the driven contact: the handout's rule. Here it
  // is the index order: b_0 < b_1 < ... < 0, and the driven forces never reach a contact not yet
  // taken (column j of A is zero below row j), so each untaken w_i is still b_i. The count is
  // then the index order's: 2^k pivots to drive contact k (0-based), 2^n - 1 in all.
  checkMurty(lcp_set::pivoting, 0);
}

TEST_CASE("lemke: Murty's exponential example takes 2^n pivots (n = 1..10), and its answer is the oracle's", "[lab06][pts=1][sec=4]") {
  // z0 entering is one pivot more than pivoting's 2^n - 1.
  checkMurty(lcp_set::lemke, 1);
}

TEST_CASE("pivoting: P-matrix LCPs (n <= 8) get the one solution the enumeration of complementary bases finds", "[lab06][pts=1][sec=3]") {
  checkPMatrices(lcp_set::pivoting);
}

TEST_CASE("lemke: P-matrix LCPs (n <= 8) get the one solution the enumeration of complementary bases finds", "[lab06][pts=1][sec=4]") {
  checkPMatrices(lcp_set::lemke);
}

TEST_CASE("pivoting: degenerate LCPs (ties in the ratio test, f = w = 0 at the answer) end with a solution", "[lab06][pts=1][sec=3]") {
  checkDegenerate(lcp_set::pivoting);
}

TEST_CASE("lemke: degenerate LCPs (ties in the ratio test, f = w = 0 at the answer) end with a solution", "[lab06][pts=1][sec=4]") {
  checkDegenerate(lcp_set::lemke);
}

TEST_CASE("pivoting: singular positive semidefinite LCPs that have a solution are solved, w the unique one", "[lab06][pts=1][sec=3]") {
  checkPsdSingular(lcp_set::pivoting);
}

TEST_CASE("lemke: singular positive semidefinite LCPs that have a solution are solved, w the unique one", "[lab06][pts=1][sec=4]") {
  checkPsdSingular(lcp_set::lemke);
}

TEST_CASE("pivoting: LCPs without a solution (a Farkas certificate) throw LcpFailure, never an answer", "[lab06][pts=1][sec=3]") {
  checkInfeasible(lcp_set::pivoting, "singular pivot");
}

TEST_CASE("lemke: LCPs without a solution (a Farkas certificate) throw LcpFailure, never an answer", "[lab06][pts=1][sec=4]") {
  checkInfeasible(lcp_set::lemke, "ray");
}
