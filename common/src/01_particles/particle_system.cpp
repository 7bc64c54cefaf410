// Framework half of Lab 1's particle code: construction, validation and Jacobian assembly.
// The physics (forces, derivative, diagnostics) is the student's, in labs/01_particles.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

bool Force::addJacobians(const ParticleView& /*s*/, MatX& /*dF_dx*/, MatX& /*dF_dv*/) const {
  return false;
}

std::optional<Vec3> Force::uniformAcceleration() const { return std::nullopt; }

UniformGravity::UniformGravity(const Vec3& g_) : g(g_) { requireFinite(g, "gravity g"); }

NBodyGravity::NBodyGravity(double G_, double softening_) : G(G_), softening(softening_) {
  requirePositive(G, "gravitational constant G");
  requireNonNegative(softening, "softening length");
}

ViscousDrag::ViscousDrag(double d_) : d(d_) { requireNonNegative(d, "drag coefficient d"); }

DampedSpring::DampedSpring(Index a_, Index b_, double rest_, double ks_, double kd_)
    : a(a_), b(b_), rest(rest_), ks(ks_), kd(kd_) {
  if (a < 0 || b < 0) throw InvalidInput("spring particle index is negative");
  if (a == b) {
    throw InvalidInput("spring joins particle " + std::to_string(a) + " to itself");
  }
  requireNonNegative(rest, "spring rest length");
  requireNonNegative(ks, "spring stiffness ks");
  requireNonNegative(kd, "spring damping kd");
}

LennardJones::LennardJones(double epsilon_, double sigma_) : epsilon(epsilon_), sigma(sigma_) {
  requirePositive(epsilon, "Lennard-Jones epsilon");
  requirePositive(sigma, "Lennard-Jones sigma");
}

ParticleSystem::ParticleSystem(VecX masses) : masses_(std::move(masses)) {
  if (masses_.size() == 0) throw InvalidInput("a particle system needs at least one particle");
  for (Index i = 0; i < masses_.size(); ++i) {
    const double m = masses_[i];
    // +infinity is the documented way to pin a particle; NaN, zero and negatives are errors.
    if (!(m > 0.0)) {
      throw InvalidInput("mass of particle " + std::to_string(i) + " must be positive, got " +
                         std::to_string(m));
    }
  }
  inverse_masses_ = masses_.cwiseInverse();  // 1 / inf = 0: a pinned particle never accelerates
}

void ParticleSystem::addForce(std::shared_ptr<const Force> force) {
  if (!force) throw InvalidInput("null force");
  if (const auto* spring = dynamic_cast<const DampedSpring*>(force.get())) {
    for (Index i : {spring->a, spring->b}) {
      if (i >= count()) {
        throw InvalidInput("spring names particle " + std::to_string(i) + " but the system has " +
                           std::to_string(count()));
      }
    }
  }
  if (const std::optional<Vec3> a = force->uniformAcceleration()) {
    uniform_acceleration_ += *a;
  } else {
    accumulated_forces_.push_back(force.get());
  }
  forces_.push_back(std::move(force));
}

VecX ParticleSystem::makeState(const Mat3X& x, const Mat3X& v) const {
  requireSize(x.cols(), count(), "positions (columns)");
  requireSize(v.cols(), count(), "velocities (columns)");
  VecX X(size());
  X.head(positionSize()) = x.reshaped();
  X.tail(velocitySize()) = v.reshaped();
  validateState(X);
  return X;
}

ParticleView ParticleSystem::view(const VecX& X) const {
  requireSize(X.size(), size(), "particle state");
  return ParticleView{positions(X), velocities(X), masses_};
}

bool ParticleSystem::computeJacobian(const VecX& X, MatX& J) const {
  // f = [v; M^-1 F(x, v)], so df/dX = [[0, 1], [M^-1 dF/dx, M^-1 dF/dv]].
  const Index n3 = positionSize();
  MatX dF_dx = MatX::Zero(n3, n3);
  MatX dF_dv = MatX::Zero(n3, n3);
  const ParticleView s = view(X);
  for (const auto& force : forces_) {
    if (!force->addJacobians(s, dF_dx, dF_dv)) return false;
  }
  J.topRightCorner(n3, n3).setIdentity();
  for (Index i = 0; i < n3; ++i) {
    J.bottomLeftCorner(n3, n3).row(i) = inverse_masses_[i / 3] * dF_dx.row(i);
    J.bottomRightCorner(n3, n3).row(i) = inverse_masses_[i / 3] * dF_dv.row(i);
  }
  return true;
}

}  // namespace physlab
