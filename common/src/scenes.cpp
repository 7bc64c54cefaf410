#include "physlab/scenes.hpp"

#include <cmath>

#include "physlab/error.hpp"

namespace physlab {

HarmonicOscillator::HarmonicOscillator(double omega_) : omega(omega_) {
  requirePositive(omega, "oscillator frequency omega");
}

double HarmonicOscillator::energy(const VecX& X) const {
  return 0.5 * (X[1] * X[1] + omega * omega * X[0] * X[0]);
}

VecX HarmonicOscillator::exact(const VecX& X0, double t) const {
  const double c = std::cos(omega * t);
  const double s = std::sin(omega * t);
  VecX X(2);
  X << X0[0] * c + X0[1] / omega * s, -X0[0] * omega * s + X0[1] * c;
  return X;
}

void HarmonicOscillator::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  qdot[0] = X[1];
}

void HarmonicOscillator::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  pdot[0] = -omega * omega * X[0];
}

bool HarmonicOscillator::computeJacobian(const VecX& /*X*/, MatX& J) const {
  J << 0.0, 1.0, -omega * omega, 0.0;
  return true;
}

Kepler::Kepler(double mu_) : mu(mu_) { requirePositive(mu, "gravitational parameter mu"); }

double Kepler::energy(const VecX& X) const {
  return 0.5 * X.tail<3>().squaredNorm() - mu / X.head<3>().norm();
}

VecX Kepler::perihelionState(double a, double e) const {
  requirePositive(a, "semi-major axis");
  if (!(e >= 0.0 && e < 1.0)) throw InvalidInput("eccentricity must lie in [0, 1)");
  VecX X = VecX::Zero(6);
  X[0] = a * (1.0 - e);
  X[4] = std::sqrt(mu * (1.0 + e) / (a * (1.0 - e)));
  return X;
}

double Kepler::period(double a) const { return 2.0 * M_PI * std::sqrt(a * a * a / mu); }

void Kepler::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  qdot = X.tail<3>();
}

void Kepler::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  const double r = X.head<3>().norm();
  pdot = (-mu / (r * r * r)) * X.head<3>();
}

}  // namespace physlab
