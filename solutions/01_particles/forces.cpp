// Lab 1, section 1: the forces of the lecture, each with its potential energy.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

// ---- uniform gravity ------------------------------------------------------------------------

void UniformGravity::accumulate(const ParticleView& s, Points F) const {
  // Add m g to every free particle
  for (Index i = 0; i < s.x.cols(); ++i) {
    if (!std::isinf(s.m[i])) F.col(i) += s.m[i] * g;
  }
}

double UniformGravity::potential(const ParticleView& s) const {
  double U = 0.0;
  // Sum -m g.x over the free particles
  for (Index i = 0; i < s.x.cols(); ++i) {
    if (!std::isinf(s.m[i])) U -= s.m[i] * g.dot(s.x.col(i));
  }
  return U;
}

bool UniformGravity::addJacobians(const ParticleView& /*s*/, MatX& /*dF_dx*/,
                                  MatX& /*dF_dv*/) const {
  // A constant force has zero Jacobians
  return true;
}

// ---- N-body gravity -------------------------------------------------------------------------

void NBodyGravity::accumulate(const ParticleView& s, Points F) const {
  const double eps2 = softening * softening;
  // Visit each pair once and apply equal and opposite forces
  for (Index i = 0; i < s.x.cols(); ++i) {
    for (Index j = i + 1; j < s.x.cols(); ++j) {
      const Vec3 d = s.x.col(j) - s.x.col(i);
      const double r2 = d.squaredNorm() + eps2;
      const Vec3 f = (G * s.m[i] * s.m[j] / (r2 * std::sqrt(r2))) * d;
      F.col(i) += f;
      F.col(j) -= f;
    }
  }
}

double NBodyGravity::potential(const ParticleView& s) const {
  const double eps2 = softening * softening;
  double U = 0.0;
  // Sum -G m_i m_j / r over the pairs
  for (Index i = 0; i < s.x.cols(); ++i) {
    for (Index j = i + 1; j < s.x.cols(); ++j) {
      U -= G * s.m[i] * s.m[j] / std::sqrt((s.x.col(j) - s.x.col(i)).squaredNorm() + eps2);
    }
  }
  return U;
}

// ---- viscous drag ---------------------------------------------------------------------------

void ViscousDrag::accumulate(const ParticleView& s, Points F) const {
  // Oppose every velocity
  F -= d * s.v;
}

double ViscousDrag::potential(const ParticleView& /*s*/) const {
  // Drag dissipates energy; it stores none
  return 0.0;
}

bool ViscousDrag::addJacobians(const ParticleView& /*s*/, MatX& /*dF_dx*/, MatX& dF_dv) const {
  // dF/dv = -d on the diagonal
  dF_dv.diagonal().array() -= d;
  return true;
}

// ---- damped spring --------------------------------------------------------------------------

void DampedSpring::accumulate(const ParticleView& s, Points F) const {
  // Measure the spring: l = x_a - x_b and its rate of change
  const Vec3 l = s.x.col(a) - s.x.col(b);
  const Vec3 l_dot = s.v.col(a) - s.v.col(b);
  const double length = l.norm();
  const Vec3 u = l / length;
  // Combine the elastic and damping magnitudes along the spring
  const Vec3 f_a = -(ks * (length - rest) + kd * l_dot.dot(u)) * u;
  F.col(a) += f_a;
  F.col(b) -= f_a;
}

double DampedSpring::potential(const ParticleView& s) const {
  // Store 1/2 ks (|l| - r)^2
  const double stretch = (s.x.col(a) - s.x.col(b)).norm() - rest;
  return 0.5 * ks * stretch * stretch;
}

bool DampedSpring::addJacobians(const ParticleView& s, MatX& dF_dx, MatX& dF_dv) const {
  // Measure the spring as in accumulate()
  const Vec3 l = s.x.col(a) - s.x.col(b);
  const Vec3 l_dot = s.v.col(a) - s.v.col(b);
  const double length = l.norm();
  const Vec3 u = l / length;
  const double magnitude = ks * (length - rest) + kd * l_dot.dot(u);
  // Differentiate f_a with respect to l and l_dot
  const Mat3 P = Mat3::Identity() - u * u.transpose();
  const Mat3 df_dl = -(ks * u * u.transpose() + (kd / length) * u * (l_dot.transpose() * P) +
                       (magnitude / length) * P);
  const Mat3 df_dldot = -kd * u * u.transpose();
  // Scatter into the four blocks: l depends on x_a with +1 and on x_b with -1, f_b = -f_a
  for (const auto& [row, row_sign] : {std::pair{a, 1.0}, std::pair{b, -1.0}}) {
    for (const auto& [col, col_sign] : {std::pair{a, 1.0}, std::pair{b, -1.0}}) {
      dF_dx.block<3, 3>(3 * row, 3 * col) += (row_sign * col_sign) * df_dl;
      dF_dv.block<3, 3>(3 * row, 3 * col) += (row_sign * col_sign) * df_dldot;
    }
  }
  return true;
}

// ---- Lennard-Jones --------------------------------------------------------------------------

void LennardJones::accumulate(const ParticleView& s, Points F) const {
  // Visit each pair once and apply equal and opposite forces
  for (Index i = 0; i < s.x.cols(); ++i) {
    for (Index j = i + 1; j < s.x.cols(); ++j) {
      const Vec3 d = s.x.col(i) - s.x.col(j);
      const double r2 = d.squaredNorm();
      const double sr6 = std::pow(sigma * sigma / r2, 3);
      // -dU/dr / r = 24 eps (2 (s/r)^12 - (s/r)^6) / r^2, times the vector d
      const Vec3 f = (24.0 * epsilon * (2.0 * sr6 * sr6 - sr6) / r2) * d;
      F.col(i) += f;
      F.col(j) -= f;
    }
  }
}

double LennardJones::potential(const ParticleView& s) const {
  double U = 0.0;
  // Sum 4 eps ((s/r)^12 - (s/r)^6) over the pairs
  for (Index i = 0; i < s.x.cols(); ++i) {
    for (Index j = i + 1; j < s.x.cols(); ++j) {
      const double sr6 = std::pow(sigma * sigma / (s.x.col(i) - s.x.col(j)).squaredNorm(), 3);
      U += 4.0 * epsilon * (sr6 * sr6 - sr6);
    }
  }
  return U;
}

}  // namespace physlab
