#include "lcp_support.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/QR>
#include <Eigen/SVD>

namespace physlab::test {

MatX randomOrthogonal(Index n) {
  MatX M(n, n);
  for (Index j = 0; j < n; ++j) {
    for (Index i = 0; i < n; ++i) M(i, j) = uniform(-1.0, 1.0);
  }
  return Eigen::HouseholderQR<MatX>(M).householderQ() * MatX::Identity(n, n);
}

MatX randomSpd(Index n, double cond, double scale) {
  const MatX Q = randomOrthogonal(n);
  VecX lambda(n);
  for (Index i = 0; i < n; ++i) lambda(i) = scale * std::exp(uniform(0.0, std::log(cond)));
  lambda(0) = scale;
  if (n > 1) lambda(1) = scale * cond;
  MatX A = Q * lambda.asDiagonal() * Q.transpose();
  return 0.5 * (A + A.transpose());  // symmetric to the last bit
}

MatX randomPMatrix(Index n, double cond, double skew) {
  MatX K(n, n);
  for (Index j = 0; j < n; ++j) {
    for (Index i = 0; i < n; ++i) K(i, j) = uniform(-skew, skew);
  }
  return randomSpd(n, cond) + (K - K.transpose()) * 0.5;
}

PlantedLcp plantSolution(const MatX& A) {
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

double qpObjective(const MatX& A, const VecX& b, const VecX& f) { return 0.5 * f.dot(A * f) + b.dot(f); }

double complementarity(const MatX& A, const VecX& b, const VecX& f) {
  const VecX w = A * f + b;
  return f.cwiseMin(w).cwiseAbs().maxCoeff();
}

double conditionNumber(const MatX& A) {
  const VecX sigma = Eigen::JacobiSVD<MatX>(A).singularValues();
  return sigma(0) / sigma(sigma.size() - 1);
}

}  // namespace physlab::test

namespace physlab::test {

std::vector<VecX> complementarySolutions(const MatX& A, const VecX& b, double tol) {
  const Index n = A.rows();
  std::vector<VecX> found;
  for (unsigned long set = 0; set < (1ul << n); ++set) {
    std::vector<Index> S;
    for (Index i = 0; i < n; ++i) {
      if (set & (1ul << i)) S.push_back(i);
    }
    VecX f = VecX::Zero(n);
    if (!S.empty()) {
      const Eigen::ColPivHouseholderQR<MatX> qr(A(S, S));
      if (qr.rank() < static_cast<Index>(S.size())) continue;
      const VecX f_S = qr.solve(-b(S));
      for (std::size_t k = 0; k < S.size(); ++k) f(S[k]) = f_S(static_cast<Index>(k));
    }
    const VecX w = A * f + b;
    if (f.minCoeff() >= -tol && w.minCoeff() >= -tol) found.push_back(f);
  }
  return found;
}

PlantedMurty murtyExample(Index n) {
  PlantedMurty m;
  m.A = MatX::Identity(n, n);
  for (Index i = 0; i < n; ++i) {
    for (Index j = i + 1; j < n; ++j) m.A(i, j) = 2.0;
  }
  m.b = VecX::Zero(n);
  for (Index i = 0; i < n; ++i) {
    for (Index j = i; j < n; ++j) m.b(i) -= std::ldexp(1.0, static_cast<int>(j) + 1);
  }
  m.f = VecX::Zero(n);
  m.f(n - 1) = std::ldexp(1.0, static_cast<int>(n));
  return m;
}

}  // namespace physlab::test
