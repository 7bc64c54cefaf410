// Lab 6, section 9: the soft step's coefficients and its one-point normal impulse update.
#include <algorithm>
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/soft_step.hpp"

namespace physlab {

SoftCoefficients softCoefficients(double hertz, double zeta, double h) {
  // TODO(student): InvalidInput naming "hertz" when hertz < 0 or not finite, "zeta" when zeta < 0 or not finite,
  // TODO(student): "h" when h <= 0 or not finite (requireNonNegative, requirePositive).
  // No spring and no damper: the impulse lets go (and omega / a1 would be 0 / 0 at zeta = 0)
  // TODO(student): hertz == 0 returns {0, 0, 1} exactly.
  // Implicit Euler of the spring k = m omega^2 and damper c = 2 zeta m omega over h
  // TODO(student): omega = 2 pi hertz, a1 = 2 zeta + h omega, a2 = h omega a1; return {omega / a1, a2 / (1 + a2),
  // TODO(student): 1 / (1 + a2)}.
  notImplemented("softCoefficients", "Lab 6 handout, section 9", hertz, zeta, h);
}

double softNormalImpulse(double lambda, double v_n, double separation, double effective_mass,
                         const SoftCoefficients& soft, double h, double max_push, bool relax) {
  // TODO(student): InvalidInput naming the argument: lambda < 0 or not finite, v_n or separation not finite,
  // TODO(student): effective_mass or h not positive and finite, max_push < 0 or NaN (infinity is allowed),
  // TODO(student): soft.bias_rate < 0 or not finite, soft.mass_scale or soft.impulse_scale outside [0, 1].
  // Pick the row's bias and softness: apart (speculative), overlapping (soft), or relaxing (rigid)
  // TODO(student): separation > 0: change = -m_eff (v_n + separation / h);
  // TODO(student): else not relax: bias = max(bias_rate separation, -max_push),
  // TODO(student):   change = -m_eff mass_scale (v_n + bias) - impulse_scale lambda;
  // TODO(student): else (relax): change = -m_eff v_n.
  // Clamp the total, not the change: a later sweep may take back what an earlier one gave
  // TODO(student): return max(0, lambda + change).
  notImplemented("softNormalImpulse", "Lab 6 handout, section 9", lambda, v_n, separation, effective_mass, soft, h,
                 max_push, relax);
}

}  // namespace physlab
