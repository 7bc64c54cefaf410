// Lab 1, section 4: energy and momentum of a particle system.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

double kineticEnergy(const ParticleSystem& sys, const VecX& X) {
  // Sum 1/2 m |v|^2 over the free particles
  // TODO(student): skip particles whose mass is infinite (pinned).
  notImplemented("kineticEnergy", "Lab 1 handout, section 4", sys, X);
}

double potentialEnergy(const ParticleSystem& sys, const VecX& X) {
  // Sum the potential of every force
  // TODO(student): sys.forces() lists them; each has potential(sys.view(X)).
  notImplemented("potentialEnergy", "Lab 1 handout, section 4", sys, X);
}

Vec3 linearMomentum(const ParticleSystem& sys, const VecX& X) {
  // Sum m v over the free particles
  // TODO(student): skip pinned particles (infinite mass).
  notImplemented("linearMomentum", "Lab 1 handout, section 4", sys, X);
}

Vec3 angularMomentum(const ParticleSystem& sys, const VecX& X) {
  // Sum x cross m v over the free particles
  // TODO(student): x.col(i).cross(m v.col(i)); skip pinned particles.
  notImplemented("angularMomentum", "Lab 1 handout, section 4", sys, X);
}

}  // namespace physlab
