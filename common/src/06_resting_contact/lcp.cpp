// Lab 6 framework: checking an LCP's input and measuring how far an f is from solving it.
#include <algorithm>
#include <cmath>

#include "physlab/lcp.hpp"

namespace physlab {

void validateLcp(const MatX& A, const VecX& b, const std::string& what) {
  if (A.rows() != A.cols()) {
    throw InvalidInput(what + " matrix A is " + std::to_string(A.rows()) + " x " + std::to_string(A.cols()) +
                       ", not square");
  }
  if (b.size() != A.rows()) {
    throw InvalidInput(what + " vector b has " + std::to_string(b.size()) + " entries, A is " +
                       std::to_string(A.rows()) + " x " + std::to_string(A.cols()));
  }
  requireFinite(A, what + " matrix A");
  requireFinite(b, what + " vector b");
}

double lcpResidual(const MatX& A, const VecX& b, const VecX& f) {
  validateLcp(A, b, "lcpResidual");
  requireSize(f.size(), b.size(), "lcpResidual forces f");
  requireFinite(f, "lcpResidual forces f");
  const VecX w = A * f + b;
  double residual = 0.0;
  for (Index i = 0; i < f.size(); ++i) residual = std::max(residual, std::abs(std::min(f(i), w(i))));
  return residual;
}

}  // namespace physlab
