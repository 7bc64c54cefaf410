// Lab 1, section 1: the forces of the lecture, each with its potential energy.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"

namespace physlab {

// ---- uniform gravity ------------------------------------------------------------------------

void UniformGravity::accumulate(const ParticleView& s, Points F) const {
  // Add m g to every free particle
  // TODO(student): F.col(i) += m_i g unless m_i is infinite.
  notImplemented("UniformGravity::accumulate", "Lab 1 handout, section 1", s, F);
}

double UniformGravity::potential(const ParticleView& s) const {
  // Sum -m g.x over the free particles
  // TODO(student): U = -sum m_i g . x_i, skipping pinned particles.
  notImplemented("UniformGravity::potential", "Lab 1 handout, section 1", s);
}

bool UniformGravity::addJacobians(const ParticleView& /*s*/, MatX& /*dF_dx*/,
                                  MatX& /*dF_dv*/) const {
  // A constant force has zero Jacobians
  // TODO(student): add nothing, but return true: the Jacobian is known (zero).
  notImplemented("UniformGravity::addJacobians", "Lab 1 handout, section 1");
}

// ---- N-body gravity -------------------------------------------------------------------------

void NBodyGravity::accumulate(const ParticleView& s, Points F) const {
  // Visit each pair once and apply equal and opposite forces
  // TODO(student): loop i < j; add f to i and -f to j (see the handout's table).
  notImplemented("NBodyGravity::accumulate", "Lab 1 handout, section 1", s, F);
}

double NBodyGravity::potential(const ParticleView& s) const {
  // Sum -G m_i m_j / r over the pairs
  // TODO(student): r is the softened distance sqrt(|x_j - x_i|^2 + eps^2).
  notImplemented("NBodyGravity::potential", "Lab 1 handout, section 1", s);
}

// ---- viscous drag ---------------------------------------------------------------------------

void ViscousDrag::accumulate(const ParticleView& s, Points F) const {
  // Oppose every velocity
  // TODO(student): F -= d v.
  notImplemented("ViscousDrag::accumulate", "Lab 1 handout, section 1", s, F);
}

double ViscousDrag::potential(const ParticleView& /*s*/) const {
  // Drag dissipates energy; it stores none
  // TODO(student): return 0.
  notImplemented("ViscousDrag::potential", "Lab 1 handout, section 1");
}

bool ViscousDrag::addJacobians(const ParticleView& /*s*/, MatX& /*dF_dx*/, MatX& dF_dv) const {
  // dF/dv = -d on the diagonal
  // TODO(student): subtract d from the diagonal of dF_dv and return true.
  notImplemented("ViscousDrag::addJacobians", "Lab 1 handout, section 1", dF_dv);
}

// ---- damped spring --------------------------------------------------------------------------

void DampedSpring::accumulate(const ParticleView& s, Points F) const {
  // Measure the spring: l = x_a - x_b and its rate of change
  // TODO(student): l, |l|, u = l/|l| and l_dot = v_a - v_b.
  // Combine the elastic and damping magnitudes along the spring
  // TODO(student): f_a = -(ks (|l| - r) + kd l_dot.u) u; add f_a to a and -f_a to b.
  notImplemented("DampedSpring::accumulate", "Lab 1 handout, section 1", s, F);
}

double DampedSpring::potential(const ParticleView& s) const {
  // Store 1/2 ks (|l| - r)^2
  // TODO(student): only the elastic part has a potential.
  notImplemented("DampedSpring::potential", "Lab 1 handout, section 1", s);
}

bool DampedSpring::addJacobians(const ParticleView& s, MatX& dF_dx, MatX& dF_dv) const {
  // Measure the spring as in accumulate()
  // TODO(student): l, |l|, u and l_dot as before.
  // Differentiate f_a with respect to l and l_dot
  // TODO(student): use the two formulas of the handout (section 1, Jacobians).
  // Scatter into the four blocks: l depends on x_a with +1 and on x_b with -1, f_b = -f_a
  // TODO(student): add sign_row * sign_col * block to dF_dx and dF_dv at (3a,3a), (3a,3b), (3b,3a), (3b,3b); return true.
  notImplemented("DampedSpring::addJacobians", "Lab 1 handout, section 1", s, dF_dx, dF_dv);
}

// ---- Lennard-Jones --------------------------------------------------------------------------

void LennardJones::accumulate(const ParticleView& s, Points F) const {
  // Visit each pair once and apply equal and opposite forces
  // TODO(student): loop i < j; add f to i and -f to j (see the handout's table).
  notImplemented("LennardJones::accumulate", "Lab 1 handout, section 1", s, F);
}

double LennardJones::potential(const ParticleView& s) const {
  // Sum 4 eps ((s/r)^12 - (s/r)^6) over the pairs
  // TODO(student): loop i < j.
  notImplemented("LennardJones::potential", "Lab 1 handout, section 1", s);
}

}  // namespace physlab
