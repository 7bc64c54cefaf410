// Lab 5, section 4: Coulomb friction at one contact point.
#include <limits>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

Vec3 frictionImpulse(const ContactBody& A, const ContactBody& B, const Vec3& p, const Vec3& n, double j_max) {
  // Refuse a normal that is not a unit vector and a bound that is negative or NaN (+infinity: none)
  // TODO(student): requireUnit(n, "... normal n"); requireInRange(j_max, 0, +infinity, "... bound j_max").
  // Project the relative velocity onto the tangent plane
  // TODO(student): v = relativeVelocity(A, B, p); v_t = v - (v . n) n; return zero when |v_t| == 0; t = v_t / |v_t|.
  // Find the impulse along -t that stops the sliding
  // TODO(student): j_stop = |v_t| / inverseEffectiveMass(A, B, p, t).
  // Clamp it to the friction cone: sticking below mu j, sliding at mu j
  // TODO(student): return -min(j_stop, j_max) * t.
  notImplemented("frictionImpulse", "Lab 5 handout, section 4", A, B, p, n, j_max);
}

}  // namespace physlab
