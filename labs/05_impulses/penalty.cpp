// Lab 5, section 7: penalty springs at the contact points.
#include <algorithm>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

Vec3 penaltyForce(double depth, double v_rel, const Vec3& n, double k, double d) {
  // Refuse a negative or NaN depth, stiffness or damping, a NaN velocity and a normal that is not a unit vector
  // TODO(student): depth >= 0 and d >= 0 (requireNonNegative), v_rel finite, n unit (requireUnit), k > 0 (requirePositive).
  // Push along n with a spring on the depth and a damper on the normal velocity, never pulling
  // TODO(student): return max(0, k * depth - d * v_rel) * n (v_rel < 0 when approaching, so the damper pushes then).
  notImplemented("penaltyForce", "Lab 5 handout, section 7", depth, v_rel, n, k, d);
}

}  // namespace physlab
