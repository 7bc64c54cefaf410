// Lab 1, section 4: energy and momentum of a particle system.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

double kineticEnergy(const ParticleSystem& sys, const VecX& X) {
  // Sum 1/2 m |v|^2 over the free particles
  // TODO(student): sum 1/2 m |v|^2 over the free particles.
  notImplemented("kineticEnergy", "Lab 1 handout, section 4", sys, X);
}

double potentialEnergy(const ParticleSystem& sys, const VecX& X) {
  // Sum the potential of every force
  // TODO(student): sum the potential of every force.
  notImplemented("potentialEnergy", "Lab 1 handout, section 4", sys, X);
}

Vec3 linearMomentum(const ParticleSystem& sys, const VecX& X) {
  // Sum m v over the free particles
  // TODO(student): sum m v over the free particles.
  notImplemented("linearMomentum", "Lab 1 handout, section 4", sys, X);
}

Vec3 angularMomentum(const ParticleSystem& sys, const VecX& X) {
  // Sum x cross m v over the free particles
  // TODO(student): sum x cross m v over the free particles.
  notImplemented("angularMomentum", "Lab 1 handout, section 4", sys, X);
}

}  // namespace physlab
