// Lab 1, section 2: the derivative of a particle system, dX/dt = [v, F/m].
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

void ParticleSystem::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  // The positions change with the velocities
  qdot = X.tail(velocitySize());
}

void ParticleSystem::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  // Accumulate every force into F
  pdot.setZero();
  Points F(pdot.data(), 3, count());
  const ParticleView s = view(X);
  for (const Force* force : accumulated_forces_) force->accumulate(s, F);
  // Divide by the masses (multiply by 1/m, which is 0 for a pinned particle), and add the
  // uniform acceleration to the free particles
  for (Index i = 0; i < count(); ++i) {
    F.col(i) *= inverse_masses_[i];
    if (inverse_masses_[i] > 0.0) F.col(i) += uniform_acceleration_;
  }
}

}  // namespace physlab
