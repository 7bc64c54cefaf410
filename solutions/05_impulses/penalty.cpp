// Lab 5, section 7: penalty springs at the contact points.
#include <algorithm>
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

Vec3 penaltyForce(double depth, double v_rel, const Vec3& n, double k, double d) {
  // Refuse a negative or NaN depth, stiffness or damping, a NaN velocity and a normal that is not a unit vector
  requireNonNegative(depth, "penaltyForce depth");
  if (!std::isfinite(v_rel)) throw InvalidInput("penaltyForce normal velocity v_rel must be finite");
  requireUnit(n, "penaltyForce normal n");
  requirePositive(k, "penaltyForce stiffness k");
  requireNonNegative(d, "penaltyForce damping d");
  // Push along n with a spring on the depth and a damper on the normal velocity, never pulling
  return std::max(0.0, k * depth - d * v_rel) * n;
}

}  // namespace physlab
