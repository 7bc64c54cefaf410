// Lab 1, section 4: energy and momentum of a particle system.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

double kineticEnergy(const ParticleSystem& sys, const VecX& X) {
  const ParticleView s = sys.view(X);
  double T = 0.0;
  // Sum 1/2 m |v|^2 over the free particles
  for (Index i = 0; i < sys.count(); ++i) {
    if (!std::isinf(s.m[i])) T += 0.5 * s.m[i] * s.v.col(i).squaredNorm();
  }
  return T;
}

double potentialEnergy(const ParticleSystem& sys, const VecX& X) {
  const ParticleView s = sys.view(X);
  double U = 0.0;
  // Sum the potential of every force
  for (const auto& force : sys.forces()) U += force->potential(s);
  return U;
}

Vec3 linearMomentum(const ParticleSystem& sys, const VecX& X) {
  const ParticleView s = sys.view(X);
  Vec3 P = Vec3::Zero();
  // Sum m v over the free particles
  for (Index i = 0; i < sys.count(); ++i) {
    if (!std::isinf(s.m[i])) P += s.m[i] * s.v.col(i);
  }
  return P;
}

Vec3 angularMomentum(const ParticleSystem& sys, const VecX& X) {
  const ParticleView s = sys.view(X);
  Vec3 L = Vec3::Zero();
  // Sum x cross m v over the free particles
  for (Index i = 0; i < sys.count(); ++i) {
    if (!std::isinf(s.m[i])) L += s.x.col(i).cross(s.m[i] * s.v.col(i));
  }
  return L;
}

}  // namespace physlab
