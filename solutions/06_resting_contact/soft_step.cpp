// Lab 6, section 9: the soft step's coefficients and its one-point normal impulse update.
#include <algorithm>
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/soft_step.hpp"

namespace physlab {

SoftCoefficients softCoefficients(double hertz, double zeta, double h) {
  requireNonNegative(hertz, "softCoefficients frequency hertz");
  requireNonNegative(zeta, "softCoefficients damping ratio zeta");
  requirePositive(h, "softCoefficients substep h");
  // No spring and no damper: the impulse lets go (and omega / a1 would be 0 / 0 at zeta = 0)
  if (hertz == 0.0) return {0.0, 0.0, 1.0};
  // Implicit Euler of the spring k = m omega^2 and damper c = 2 zeta m omega over h
  const double omega = 2.0 * M_PI * hertz;
  const double a1 = 2.0 * zeta + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

double softNormalImpulse(double lambda, double v_n, double separation, double effective_mass,
                         const SoftCoefficients& soft, double h, double max_push, bool relax) {
  requireNonNegative(lambda, "softNormalImpulse accumulated impulse lambda");
  requireFinite(v_n, "softNormalImpulse normal velocity v_n");
  requireFinite(separation, "softNormalImpulse separation");
  requirePositive(effective_mass, "softNormalImpulse effective_mass");
  requirePositive(h, "softNormalImpulse substep h");
  requireInRange(max_push, 0.0, INFINITY, "softNormalImpulse max_push");
  requireNonNegative(soft.bias_rate, "softNormalImpulse soft bias_rate");
  requireInRange(soft.mass_scale, 0.0, 1.0, "softNormalImpulse soft mass_scale");
  requireInRange(soft.impulse_scale, 0.0, 1.0, "softNormalImpulse soft impulse_scale");
  // Pick the row's bias and softness: apart (speculative), overlapping (soft), or relaxing (rigid)
  double change = 0.0;
  if (separation > 0.0) {
    change = -effective_mass * (v_n + separation / h);
  } else if (!relax) {
    const double bias = std::max(soft.bias_rate * separation, -max_push);
    change = -effective_mass * soft.mass_scale * (v_n + bias) - soft.impulse_scale * lambda;
  } else {
    change = -effective_mass * v_n;
  }
  // Clamp the total, not the change: a later sweep may take back what an earlier one gave
  return std::max(0.0, lambda + change);
}

}  // namespace physlab
