#include "physlab/system.hpp"

#include <cmath>
#include <limits>

#include "physlab/error.hpp"

namespace physlab {

namespace {

// The checks of every evaluation: one comparison, inlined; the message (with the system's name)
// is built only on failure, out of line, so that a step allocates nothing and calls nothing.
[[gnu::cold, gnu::noinline]] void reportSize(const System& sys, Index actual, Index expected, const char* what) {
  requireSize(actual, expected, sys.name() + " " + what);
}

void checkSize(const System& sys, Index actual, Index expected, const char* what) {
  if (actual != expected) reportSize(sys, actual, expected, what);
}

}  // namespace

void System::positionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  checkSize(*this, X.size(), size(), "state");
  checkSize(*this, qdot.size(), positionSize(), "position rate");
  computePositionRate(X, qdot);
}

Eigen::Map<const VecX> System::positionRateView(const VecX& X, Eigen::Ref<VecX> scratch) const {
  const Index nq = positionSize();
  checkSize(*this, X.size(), nq + velocitySize(), "state");
  if (positionRateIsVelocity()) return Eigen::Map<const VecX>(X.data() + nq, nq);
  checkSize(*this, scratch.size(), nq, "position rate");
  computePositionRate(X, scratch);
  return Eigen::Map<const VecX>(scratch.data(), nq);
}

void System::velocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  checkSize(*this, X.size(), size(), "state");
  checkSize(*this, pdot.size(), velocitySize(), "velocity rate");
  ++force_evaluations_;
  computeVelocityRate(X, pdot);
}

void System::derivative(const VecX& X, VecX& dXdt) const {
  const Index nq = positionSize(), nv = velocitySize();  // virtual: asked once per evaluation
  checkSize(*this, X.size(), nq + nv, "state");
  dXdt.resize(nq + nv);
  computePositionRate(X, dXdt.head(nq));
  ++force_evaluations_;
  computeVelocityRate(X, dXdt.tail(nv));
}

MatX System::jacobian(const VecX& X) const {
  validateState(X);
  MatX J = MatX::Zero(size(), size());
  if (computeJacobian(X, J)) return J;
  // Central differences: error O(eps^2) against round-off O(1e-16 / eps); eps ~ cbrt(machine
  // epsilon) balances the two at about 1e-11 relative.
  const double scale = std::cbrt(std::numeric_limits<double>::epsilon());
  VecX Xp = X;
  VecX fp(size());
  VecX fm(size());
  for (Index j = 0; j < size(); ++j) {
    const double eps = scale * std::max(1.0, std::abs(X[j]));
    Xp[j] = X[j] + eps;
    derivative(Xp, fp);
    Xp[j] = X[j] - eps;
    derivative(Xp, fm);
    Xp[j] = X[j];
    J.col(j) = (fp - fm) / (2.0 * eps);
  }
  return J;
}

void System::project(VecX& /*X*/) const {}

bool System::computeJacobian(const VecX& /*X*/, MatX& /*J*/) const { return false; }

void System::validateState(const VecX& X, std::string_view what) const {
  if (X.size() != size()) requireSize(X.size(), size(), name() + " " + std::string(what));
  if (!X.allFinite()) requireFinite(X, name() + " " + std::string(what));
}

}  // namespace physlab
