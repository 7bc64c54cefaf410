// Helpers of the Lab 6 LCP tests: random matrices with a known condition, LCPs with a planted
// solution, and the measures the tests compare, all computed here apart from the student's code.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/QR>
#include <Eigen/SVD>

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
inline MatX randomOrthogonal(Index n) {
  MatX M(n, n);
  for (Index j = 0; j < n; ++j) {
    for (Index i = 0; i < n; ++i) M(i, j) = uniform(-1.0, 1.0);
  }
  return Eigen::HouseholderQR<MatX>(M).householderQ() * MatX::Identity(n, n);
}

/// A symmetric positive definite matrix with eigenvalues log-uniform in [scale, scale cond]
/// (both ends included, so its condition number is cond).
inline MatX randomSpd(Index n, double cond, double scale = 1.0) {
  const MatX Q = randomOrthogonal(n);
  VecX lambda(n);
  for (Index i = 0; i < n; ++i) lambda(i) = scale * std::exp(uniform(0.0, std::log(cond)));
  lambda(0) = scale;
  if (n > 1) lambda(1) = scale * cond;
  MatX A = Q * lambda.asDiagonal() * Q.transpose();
  return 0.5 * (A + A.transpose());  // symmetric to the last bit
}

/// A non-symmetric P-matrix: SPD plus a skew-symmetric part (x^T A x = x^T S x > 0), whose
/// every principal submatrix is again positive definite.
inline MatX randomPMatrix(Index n, double cond, double skew) {
  MatX K(n, n);
  for (Index j = 0; j < n; ++j) {
    for (Index i = 0; i < n; ++i) K(i, j) = uniform(-skew, skew);
  }
  return randomSpd(n, cond) + (K - K.transpose()) * 0.5;
}

/// A random complementary pair (f*, w*): each contact active (f > 0, w = 0), free (f = 0,
/// w > 0) or degenerate (f = w = 0), at least one of each when n >= 3.
inline PlantedLcp plantSolution(const MatX& A) {
  const Index n = A.rows();
  PlantedLcp p;
  p.A = A;
  p.f = VecX::Zero(n);
  p.w = VecX::Zero(n);
  std::vector<int> kind(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    const double u = uniform(0.0, 1.0);
    kind[static_cast<std::size_t>(i)] = i < 3 ? static_cast<int>(i) : (u < 0.5 ? 0 : (u < 0.8 ? 1 : 2));
  }
  std::shuffle(kind.begin(), kind.end(), rng());
  for (Index i = 0; i < n; ++i) {
    switch (kind[static_cast<std::size_t>(i)]) {
      case 0: p.f(i) = uniform(0.1, 2.0); ++p.active; break;
      case 1: p.w(i) = uniform(0.1, 2.0); ++p.free; break;
      default: ++p.degenerate; break;
    }
  }
  p.b = p.w - A * p.f;
  return p;
}

/// The QP objective 1/2 f^T A f + b^T f that PGS decreases on symmetric A.
inline double qpObjective(const MatX& A, const VecX& b, const VecX& f) { return 0.5 * f.dot(A * f) + b.dot(f); }

/// Complementarity measured here, apart from the framework: max |min(f_i, w_i)|, w = A f + b.
inline double complementarity(const MatX& A, const VecX& b, const VecX& f) {
  const VecX w = A * f + b;
  return f.cwiseMin(w).cwiseAbs().maxCoeff();
}

/// The 2-norm condition number of A (ratio of extreme singular values).
inline double conditionNumber(const MatX& A) {
  const VecX sigma = Eigen::JacobiSVD<MatX>(A).singularValues();
  return sigma(0) / sigma(sigma.size() - 1);
}

}  // namespace physlab::test
