// Lab 6 graded tests of input checking: each solver refuses a malformed LCP with InvalidInput
// naming the problem (validateLcp is the framework's, but calling it is the student's job).
#include <cmath>
#include <limits>
#include <string>

#include "lcp_support.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

namespace {

using Solver = LcpSolution (*)(const MatX&, const VecX&);

// The malformed inputs every solver must refuse, with the words the message must contain.
void checkRefusesBadInput(Solver solve) {
  const Index n = 3 * static_cast<Index>(uniform(1, 4));
  const MatX A = randomSpd(n, 10.0);
  VecX b(n);
  for (Index i = 0; i < n; ++i) b(i) = uniform(-1.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(solve(MatX::Ones(n, n + 1), b), InvalidInput);
  CHECK_THROWS_WITH(solve(MatX::Ones(n, n + 1), b), Contains("not square"));
  CHECK_THROWS_AS(solve(A, VecX::Ones(n + 1)), InvalidInput);
  CHECK_THROWS_WITH(solve(A, VecX::Ones(n + 1)), Contains("vector b"));
  MatX A_nan = A;
  A_nan(static_cast<Index>(uniform(0, static_cast<double>(n))), static_cast<Index>(uniform(0, static_cast<double>(n)))) = nan;
  CHECK_THROWS_AS(solve(A_nan, b), InvalidInput);
  CHECK_THROWS_WITH(solve(A_nan, b), Contains("matrix A") && Contains("non-finite"));
  VecX b_nan = b;
  b_nan(static_cast<Index>(uniform(0, static_cast<double>(n)))) = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(solve(A, b_nan), InvalidInput);
  CHECK_THROWS_WITH(solve(A, b_nan), Contains("vector b") && Contains("non-finite"));
  // A valid LCP goes through
  CHECK_NOTHROW(solve(A, b));
}

LcpSolution pivoting(const MatX& A, const VecX& b) { return solveLcpPivoting(A, b); }
LcpSolution lemke(const MatX& A, const VecX& b) { return solveLcpLemke(A, b); }
LcpSolution pgs(const MatX& A, const VecX& b) { return solveLcpPgs(A, b); }
LcpSolution cone(const MatX& A, const VecX& b) {
  return solveLcpPgsCone(A, b, VecX::Constant(A.rows() / 3, 0.5));
}

}  // namespace

TEST_CASE("pivoting: refuses a non-square A, a b of the wrong size and NaN or infinite entries", "[lab06][pts=1][sec=3]") {
  checkRefusesBadInput(pivoting);
}

TEST_CASE("lemke: refuses a non-square A, a b of the wrong size and NaN or infinite entries", "[lab06][pts=1][sec=4]") {
  checkRefusesBadInput(lemke);
}

TEST_CASE("pgs: refuses bad input, and a non-positive diagonal entry with LcpFailure", "[lab06][pts=1][sec=5]") {
  checkRefusesBadInput(pgs);
  // Each update divides by a_ii: a zero there is a numerical failure, not a NaN in f
  MatX A = MatX::Identity(3, 3);
  A(1, 1) = 0.0;
  CHECK_THROWS_AS(solveLcpPgs(A, VecX::Constant(3, -1.0)), LcpFailure);
  // "a_ii <= pivot_tolerance" includes the boundary: a_ii equal to the tolerance, 0 with a zero one
  LcpOptions options;
  options.pivot_tolerance = 0.0;
  CHECK_THROWS_AS(solveLcpPgs(A, VecX::Constant(3, -1.0), options), LcpFailure);
  options.pivot_tolerance = uniform(0.1, 1.0);
  A(1, 1) = options.pivot_tolerance;
  CHECK_THROWS_AS(solveLcpPgs(A, VecX::Constant(3, -1.0), options), LcpFailure);
  A(1, 1) = 2.0 * options.pivot_tolerance;
  CHECK_NOTHROW(solveLcpPgs(A, VecX::Constant(3, -1.0), options));
}

TEST_CASE("pgs cone: refuses bad input, a size not a multiple of 3, a wrong mu size, a negative or infinite mu and a_ii <= pivot_tolerance", "[lab06][pts=1][sec=6]") {
  checkRefusesBadInput(cone);
  const Index k = static_cast<Index>(uniform(1, 4));
  const MatX A = randomSpd(3 * k, 10.0);
  const VecX b = VecX::Constant(3 * k, -1.0);
  // 3k + 1 unknowns are not blocks of three
  const MatX A4 = randomSpd(3 * k + 1, 10.0);
  CHECK_THROWS_AS(solveLcpPgsCone(A4, VecX::Constant(3 * k + 1, -1.0), VecX::Constant(k, 0.5)), InvalidInput);
  CHECK_THROWS_WITH(solveLcpPgsCone(A4, VecX::Constant(3 * k + 1, -1.0), VecX::Constant(k, 0.5)), Contains("multiple of 3"));
  CHECK_THROWS_AS(solveLcpPgsCone(A, b, VecX::Constant(k + 1, 0.5)), InvalidInput);
  CHECK_THROWS_WITH(solveLcpPgsCone(A, b, VecX::Constant(k + 1, 0.5)), Contains("mu"));
  VecX mu = VecX::Constant(k, 0.5);
  mu(k - 1) = -uniform(0.01, 1.0);
  CHECK_THROWS_AS(solveLcpPgsCone(A, b, mu), InvalidInput);
  CHECK_THROWS_WITH(solveLcpPgsCone(A, b, mu), Contains("mu(" + std::to_string(k - 1) + ")"));
  mu(k - 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(solveLcpPgsCone(A, b, mu), InvalidInput);
  mu(k - 1) = std::numeric_limits<double>::infinity();  // "not finite": infinity as well as NaN
  CHECK_THROWS_AS(solveLcpPgsCone(A, b, mu), InvalidInput);
  CHECK_THROWS_WITH(solveLcpPgsCone(A, b, mu), Contains("mu(" + std::to_string(k - 1) + ")"));
  CHECK_NOTHROW(solveLcpPgsCone(A, b, VecX::Zero(k)));
  // Every diagonal entry is divided by (normal) or bounds lambda (tangential): a_ii <= pivot_tolerance,
  // the boundary included, is an LcpFailure, in a normal row and in a tangential one
  LcpOptions options;
  options.pivot_tolerance = uniform(0.01, 0.05);  // below randomSpd's smallest eigenvalue 1, so below every a_ii
  for (const Index i : {Index{0}, 3 * k - 1}) {
    MatX bad = A;
    bad(i, i) = 0.0;
    CHECK_THROWS_AS(solveLcpPgsCone(bad, b, VecX::Constant(k, 0.5)), LcpFailure);
    bad(i, i) = options.pivot_tolerance;
    CHECK_THROWS_AS(solveLcpPgsCone(bad, b, VecX::Constant(k, 0.5), options), LcpFailure);
  }
  CHECK_NOTHROW(solveLcpPgsCone(A, b, VecX::Constant(k, 0.5), options));
}

TEST_CASE("every solver refuses a negative tolerance or pivot_tolerance, and allows zero ones", "[lab06][pts=1][sec=3][sec=4][sec=5][sec=6]") {
  const Index n = 3 * static_cast<Index>(uniform(1, 4));
  const MatX A = randomSpd(n, 10.0);
  VecX b(n);
  for (Index i = 0; i < n; ++i) b(i) = uniform(-1.0, 1.0);
  const VecX mu = VecX::Constant(n / 3, 0.5);
  // The same options for every solver: LcpOptions' contract, "both tolerances must be >= 0"
  auto refusedByAll = [&](const LcpOptions& options, const std::string& words) {
    INFO("n " << n << ", tolerance " << options.tolerance << ", pivot_tolerance " << options.pivot_tolerance);
    CHECK_THROWS_AS(solveLcpPivoting(A, b, options), InvalidInput);
    CHECK_THROWS_WITH(solveLcpPivoting(A, b, options), Contains(words));
    CHECK_THROWS_AS(solveLcpLemke(A, b, options), InvalidInput);
    CHECK_THROWS_WITH(solveLcpLemke(A, b, options), Contains(words));
    CHECK_THROWS_AS(solveLcpPgs(A, b, options), InvalidInput);
    CHECK_THROWS_WITH(solveLcpPgs(A, b, options), Contains(words));
    CHECK_THROWS_AS(solveLcpPgsCone(A, b, mu, options), InvalidInput);
    CHECK_THROWS_WITH(solveLcpPgsCone(A, b, mu, options), Contains(words));
  };
  LcpOptions options;
  options.tolerance = -uniform(1e-12, 1.0);
  refusedByAll(options, "tolerance");
  options = LcpOptions{};
  options.pivot_tolerance = -uniform(1e-12, 1.0);
  refusedByAll(options, "tolerance");
  // Zero tolerances are allowed, and each solver still solves a problem it can solve exactly:
  // A = [[2, 1, 0], [1, 2, 0], [0, 0, 4]], b = (-1, 1, -2) has f = (1/2, 0, 1/2), w = (0, 3/2, 0),
  // all in halves, so every solver lands on it exactly
  options = LcpOptions{};
  options.tolerance = 0.0;
  options.pivot_tolerance = 0.0;
  INFO("tolerance 0 and pivot_tolerance 0 are allowed; then A = [[2, 1, 0], [1, 2, 0], [0, 0, 4]], b = (-1, 1, -2): "
       "expected f = (1/2, 0, 1/2), w = (0, 3/2, 0)");
  CHECK_NOTHROW(solveLcpPgs(A, b, options));
  MatX H(3, 3);
  H << 2.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 4.0;
  const Vec3 q(-1.0, 1.0, -2.0), f(0.5, 0.0, 0.5), w(0.0, 1.5, 0.0);
  for (const LcpSolution& s : {solveLcpPivoting(H, q, options), solveLcpLemke(H, q, options), solveLcpPgs(H, q, options)}) {
    CAPTURE(s.f.transpose(), s.w.transpose(), s.iterations);
    // Sums and quotients of halves: exact, or off by an ulp at most
    CHECK((s.f - f).cwiseAbs().maxCoeff() <= 1e-15);
    CHECK((s.w - w).cwiseAbs().maxCoeff() <= 1e-15);
  }
  // Pivoting: contact 0 clamps (1 pivot), contact 1 stays free, contact 2 clamps (1 pivot); a w_d
  // that reached 0 exactly is not negative and is never driven again
  CHECK(solveLcpPivoting(H, q, options).iterations == 2);
  // PGS: the first sweep lands on f exactly (f_0 = 1/2, then w_1 = 3/2 keeps f_1 = 0, then f_2 = 1/2:
  // contact 2 does not couple to the others), and residual 0 <= 0 stops it
  CHECK(solveLcpPgs(H, q, options).iterations == 1);
  // The cone on the same numbers, one contact (n, t, o) with mu = 1/2: no failure, a cone point
  const LcpSolution c = solveLcpPgsCone(H, q, VecX::Constant(1, 0.5), options);
  CHECK(c.f(0) >= 0.0);
  CHECK(c.f.tail<2>().norm() <= 0.5 * c.f(0) * (1.0 + 1e-15));  // scaled onto the disc: round-off only
}

TEST_CASE("every solver takes an empty LCP (n = 0): empty f and w, no pivot, residual 0", "[lab06][pts=1][sec=3][sec=4][sec=5][sec=6]") {
  // No contact at all is a valid problem (LcpSolution's contract), not an error and not a read
  // past the end of an empty vector
  const MatX A(0, 0);
  const VecX b(0);
  INFO("n = 0: A is 0 x 0, b and mu are empty; expected empty f and w, 0 pivots, residual 0");
  const LcpSolution piv = solveLcpPivoting(A, b), lem = solveLcpLemke(A, b), pgs = solveLcpPgs(A, b);
  const LcpSolution cone = solveLcpPgsCone(A, b, VecX(0));
  for (const LcpSolution* s : {&piv, &lem, &pgs, &cone}) {
    CHECK(s->f.size() == 0);
    CHECK(s->w.size() == 0);
  }
  CHECK(piv.iterations == 0);
  CHECK(lem.iterations == 0);
  CHECK(piv.residual == 0.0);
  CHECK(lem.residual == 0.0);
  CHECK(pgs.residual == 0.0);
}
