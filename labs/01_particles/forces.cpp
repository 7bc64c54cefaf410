// Lab 1, section 1: the forces of the lecture, each with its potential energy.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

// ---- uniform gravity ------------------------------------------------------------------------

void UniformGravity::accumulate(const ParticleView& s, Points F) const {
  // Add m g to every free particle
  // TODO(student): add m g to every free particle.
  notImplemented("UniformGravity::accumulate", "Lab 1 handout, section 1", s, F);
}

double UniformGravity::potential(const ParticleView& s) const {
  // Sum -m g.x over the free particles
  // TODO(student): sum -m g.x over the free particles.
  notImplemented("UniformGravity::potential", "Lab 1 handout, section 1", s);
}

bool UniformGravity::addJacobians(const ParticleView& /*s*/, MatX& /*dF_dx*/,
                                  MatX& /*dF_dv*/) const {
  // A constant force has zero Jacobians
  // TODO(student): a constant force has zero Jacobians.
  notImplemented("UniformGravity::addJacobians", "Lab 1 handout, section 1");
}

// ---- N-body gravity -------------------------------------------------------------------------

void NBodyGravity::accumulate(const ParticleView& s, Points F) const {
  // Visit each pair once and apply equal and opposite forces
  // TODO(student): visit each pair once and apply equal and opposite forces.
  notImplemented("NBodyGravity::accumulate", "Lab 1 handout, section 1", s, F);
}

double NBodyGravity::potential(const ParticleView& s) const {
  // Sum -G m_i m_j / r over the pairs
  // TODO(student): sum -G m_i m_j / r over the pairs.
  notImplemented("NBodyGravity::potential", "Lab 1 handout, section 1", s);
}

// ---- viscous drag ---------------------------------------------------------------------------

void ViscousDrag::accumulate(const ParticleView& s, Points F) const {
  // Oppose every velocity
  // TODO(student): oppose every velocity.
  notImplemented("ViscousDrag::accumulate", "Lab 1 handout, section 1", s, F);
}

double ViscousDrag::potential(const ParticleView& /*s*/) const {
  // Drag dissipates energy; it stores none
  // TODO(student): drag dissipates energy; it stores none.
  notImplemented("ViscousDrag::potential", "Lab 1 handout, section 1");
}

bool ViscousDrag::addJacobians(const ParticleView& /*s*/, MatX& /*dF_dx*/, MatX& dF_dv) const {
  // dF/dv = -d on the diagonal
  // TODO(student): dF/dv = -d on the diagonal.
  notImplemented("ViscousDrag::addJacobians", "Lab 1 handout, section 1", dF_dv);
}

// ---- damped spring --------------------------------------------------------------------------

void DampedSpring::accumulate(const ParticleView& s, Points F) const {
  // Measure the spring: l = x_a - x_b and its rate of change
  // TODO(student): measure the spring: l = x_a - x_b and its rate of change.
  // Combine the elastic and damping magnitudes along the spring
  // TODO(student): combine the elastic and damping magnitudes along the spring.
  notImplemented("DampedSpring::accumulate", "Lab 1 handout, section 1", s, F);
}

double DampedSpring::potential(const ParticleView& s) const {
  // Store 1/2 ks (|l| - r)^2
  // TODO(student): store 1/2 ks (|l| - r)^2.
  notImplemented("DampedSpring::potential", "Lab 1 handout, section 1", s);
}

bool DampedSpring::addJacobians(const ParticleView& s, MatX& dF_dx, MatX& dF_dv) const {
  // Measure the spring as in accumulate()
  // TODO(student): measure the spring as in accumulate().
  // Differentiate f_a with respect to l and l_dot
  // TODO(student): differentiate f_a with respect to l and l_dot.
  // Scatter into the four blocks: l depends on x_a with +1 and on x_b with -1, f_b = -f_a
  // TODO(student): scatter into the four blocks: l depends on x_a with +1 and on x_b with -1, f_b = -f_a.
  notImplemented("DampedSpring::addJacobians", "Lab 1 handout, section 1", s, dF_dx, dF_dv);
}

// ---- Lennard-Jones --------------------------------------------------------------------------

void LennardJones::accumulate(const ParticleView& s, Points F) const {
  // Visit each pair once and apply equal and opposite forces
  // TODO(student): visit each pair once and apply equal and opposite forces.
  notImplemented("LennardJones::accumulate", "Lab 1 handout, section 1", s, F);
}

double LennardJones::potential(const ParticleView& s) const {
  // Sum 4 eps ((s/r)^12 - (s/r)^6) over the pairs
  // TODO(student): sum 4 eps ((s/r)^12 - (s/r)^6) over the pairs.
  notImplemented("LennardJones::potential", "Lab 1 handout, section 1", s);
}

}  // namespace physlab
