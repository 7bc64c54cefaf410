// Lab 1, section 2: the derivative of a particle system, dX/dt = [v, F/m].
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

void ParticleSystem::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  // The positions change with the velocities
  // TODO(student): the positions change with the velocities.
  notImplemented("ParticleSystem::computePositionRate", "Lab 1 handout, section 2", X, qdot);
}

void ParticleSystem::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  // Accumulate every force into F
  // TODO(student): accumulate every force into F.
  // Divide by the masses: multiply by 1/m, which is 0 for a pinned particle
  // TODO(student): divide by the masses: multiply by 1/m, which is 0 for a pinned particle.
  notImplemented("ParticleSystem::computeVelocityRate", "Lab 1 handout, section 2", X, pdot);
}

}  // namespace physlab
