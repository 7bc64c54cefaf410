// Lab 5, section 4: Coulomb friction at one contact point.
#include <limits>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

Vec3 frictionImpulse(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& n, double j_max) {
  // Refuse a normal that is not a unit vector and a bound that is negative or NaN (+infinity: none)
  requireUnit(n, "frictionImpulse normal n");
  requireInRange(j_max, 0.0, std::numeric_limits<double>::infinity(), "frictionImpulse bound j_max");
  // Project the relative velocity onto the tangent plane
  const Vec3 v = relativeVelocity(A, B, p);
  const Vec3 v_t = v - v.dot(n) * n;
  const double speed = v_t.norm();
  if (speed == 0.0) return Vec3::Zero();
  const Vec3 t = v_t / speed;
  // Find the impulse along -t that stops the sliding
  const double j_stop = speed / inverseEffectiveMass(A, B, p, t);
  // Clamp it to the friction cone: sticking below mu j, sliding at mu j
  return -std::min(j_stop, j_max) * t;
}

}  // namespace physlab
