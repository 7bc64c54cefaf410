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

TEST_CASE("pivoting: refuses a non-square A, a b of the wrong size and NaN or infinite entries", "[lab06][pts=1]") {
  checkRefusesBadInput(pivoting);
}

TEST_CASE("lemke: refuses a non-square A, a b of the wrong size and NaN or infinite entries", "[lab06][pts=1]") {
  checkRefusesBadInput(lemke);
}

TEST_CASE("pgs: refuses bad input, and a non-positive diagonal entry with LcpFailure", "[lab06][pts=1]") {
  checkRefusesBadInput(pgs);
  // Each update divides by a_ii: a zero there is a numerical failure, not a NaN in f
  MatX A = MatX::Identity(3, 3);
  A(1, 1) = 0.0;
  CHECK_THROWS_AS(solveLcpPgs(A, VecX::Constant(3, -1.0)), LcpFailure);
}

TEST_CASE("pgs cone: refuses bad input, a size not a multiple of 3, a wrong mu size and a negative mu", "[lab06][pts=1]") {
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
  CHECK_NOTHROW(solveLcpPgsCone(A, b, VecX::Zero(k)));
}

TEST_CASE("every solver refuses a negative tolerance or pivot_tolerance, and allows zero ones", "[lab06][pts=1]") {
  const Index n = 3 * static_cast<Index>(uniform(1, 4));
  const MatX A = randomSpd(n, 10.0);
  VecX b(n);
  for (Index i = 0; i < n; ++i) b(i) = uniform(-1.0, 1.0);
  const VecX mu = VecX::Constant(n / 3, 0.5);
  // The same options for every solver: LcpOptions' contract, "both tolerances must be >= 0"
  auto refusedByAll = [&](const LcpOptions& options, const std::string& words) {
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
  // Zero tolerances are allowed
  options = LcpOptions{};
  options.tolerance = 0.0;
  options.pivot_tolerance = 0.0;
  CHECK_NOTHROW(solveLcpPgs(A, b, options));
}
