// Lab 1, section 2: the derivative of a particle system, dX/dt = [v, F/m].
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

void ParticleSystem::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  // The positions change with the velocities
  // TODO(student): qdot is the velocity half of X: X.tail(velocitySize()).
  notImplemented("ParticleSystem::computePositionRate", "Lab 1 handout, section 2", X, qdot);
}

void ParticleSystem::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  // Accumulate every force into F
  // TODO(student): zero pdot, view it as Points F(pdot.data(), 3, count()), call accumulate() of each of accumulatedForces() on view(X).
  // Divide by the masses (multiply by 1/m, which is 0 for a pinned particle), and add the
  // uniform acceleration to the free particles
  // TODO(student): scale column i of F by inverseMasses()[i]; add uniformAcceleration() where inverseMasses()[i] > 0.
  notImplemented("ParticleSystem::computeVelocityRate", "Lab 1 handout, section 2", X, pdot);
}

}  // namespace physlab
