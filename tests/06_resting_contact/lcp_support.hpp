// Helpers of the Lab 6 LCP tests: random matrices with a known condition, LCPs with a planted
// solution, and the measures the tests compare, all computed here apart from the student's code.
// Defined in lcp_support.cpp, compiled once: inlined, their Eigen QR and SVD cost 8 s of compile
// time in every test file that includes this header.
#pragma once

#include <vector>

#include "physlab/lcp.hpp"
#include "support.hpp"

namespace physlab::test {

/// An LCP built backwards from a solution: b = w* - A f*.
struct PlantedLcp {
  MatX A;
  VecX b, f, w;  // f* and w* = A f* + b
  int active = 0, free = 0, degenerate = 0;  // how many contacts of each kind
};

/// A random orthogonal n x n matrix (Q of the QR factorization of a random matrix).
MatX randomOrthogonal(Index n);

/// A symmetric positive definite matrix with eigenvalues log-uniform in [scale, scale cond]
/// (both ends included, so its condition number is cond).
MatX randomSpd(Index n, double cond, double scale = 1.0);

/// A non-symmetric P-matrix: SPD plus a skew-symmetric part (x^T A x = x^T S x > 0), whose
/// every principal submatrix is again positive definite.
MatX randomPMatrix(Index n, double cond, double skew);

/// A random complementary pair (f*, w*): each contact active (f > 0, w = 0), free (f = 0,
/// w > 0) or degenerate (f = w = 0), at least one of each when n >= 3.
PlantedLcp plantSolution(const MatX& A);

/// The QP objective 1/2 f^T A f + b^T f that PGS decreases on symmetric A.
double qpObjective(const MatX& A, const VecX& b, const VecX& f);

/// Complementarity measured here, apart from the framework: max |min(f_i, w_i)|, w = A f + b.
double complementarity(const MatX& A, const VecX& b, const VecX& f);

/// The 2-norm condition number of A (ratio of extreme singular values).
double conditionNumber(const MatX& A);

}  // namespace physlab::test

namespace physlab::test {

/// Every complementary basic solution of LCP(A, b), found by enumerating the 2^n complementary
/// bases (n <= 16): for each set S, f_S solves A_SS f_S = -b_S (skipped when A_SS is singular),
/// f = 0 elsewhere, and the pair counts when f >= -tol and w = A f + b >= -tol. The oracle of
/// the LCP test set, apart from any pivoting rule: a P-matrix gives exactly one.
std::vector<VecX> complementarySolutions(const MatX& A, const VecX& b, double tol);

/// Murty's exponential example for pivoting methods (after K. G. Murty, "Computational
/// complexity of complementary pivot methods", 1978), in our index order: A upper triangular
/// with 1 on the diagonal and 2 above it (a P-matrix), b_i = -(2^{i+1} + 2^{i+2} + ... + 2^n)
/// for i = 0..n-1 (0-based). Its unique solution has f_{n-1} = 2^n and every other f_i = 0.
struct PlantedMurty {
  MatX A;
  VecX b, f;
};
PlantedMurty murtyExample(Index n);

}  // namespace physlab::test
