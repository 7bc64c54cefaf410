// Lab 5, section 9: Timewarp: the time of impact of two spheres, the rollback rule, and the impulse at an impact.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "physlab/error.hpp"
#include "physlab/timewarp.hpp"
#include "physlab/world.hpp"

namespace physlab {

double sphereImpactTime(const Vec3& x_a, const Vec3& v_a, double r_a, const Vec3& x_b, const Vec3& v_b, double r_b) {
  // Refuse radii that are not positive and vectors that are not finite
  // TODO(student): requirePositive(r_a, "sphereImpactTime radius r_a"), the same for r_b; requireFinite on x_a, v_a, x_b, v_b.
  // Only an approach can end in an impact: d . w < 0
  // TODO(student): d = x_a - x_b, w = v_a - v_b; unless d.dot(w) < 0 return +infinity.
  // Touching or overlapping now: the impact is now
  // TODO(student): c = |d|^2 - (r_a + r_b)^2; when c <= 0 return 0.
  // Solve (w.w) s^2 + 2 (d.w) s + c = 0; a miss has no real root, a graze one double root
  // TODO(student): discriminant (d.w)^2 - (w.w) c; unless it is > 0 return +infinity.
  // The smaller root in the form without cancellation: -d.w > 0 and sqrt(disc) add
  // TODO(student): return c / (-(d.w) + sqrt(discriminant)).
  notImplemented("sphereImpactTime", "Lab 5 handout, section 9", x_a, v_a, r_a, x_b, v_b, r_b);
}

std::vector<double> rollbackTimes(const std::vector<TimewarpEvent>& events, int body_count, const std::vector<int>& seeds,
                                  double t_c) {
  // Refuse a negative count, a time that is not finite, bodies outside the scene and unsorted events
  // TODO(student): InvalidInput naming "rollbackTimes body_count", "... t_c", "... seed k", "... event e" (bad body, time, order).
  // The colliding pair goes back to the time of impact; everybody else keeps its state
  // TODO(student): r = body_count times +infinity; r[seed] = t_c for each seed.
  // In time order, undo each event that used a rolled-back state: both its bodies go back to it
  // TODO(student): for each event (t, a, b): when t > r[a] or t > r[b], r[a] = min(r[a], t) and r[b] = min(r[b], t).
  notImplemented("rollbackTimes", "Lab 5 handout, section 9", events, body_count, seeds, t_c);
}

double resolveSphereImpact(const Vec3& x_a, Vec3& v_a, double m_a, const Vec3& x_b, Vec3& v_b, double m_b, double r_b,
                           double epsilon) {
  // Refuse masses that are not positive and centres that coincide (no normal)
  // TODO(student): requirePositive on m_a, m_b and |x_a - x_b|, requireFinite on x_a, x_b, each naming its argument.
  // Build the two bodies and the contact: normal from B to A, point on B's surface
  // TODO(student): ContactBody A, B with x, v and inv_mass (no rotation); n = (x_a - x_b) normalised, p = x_b + r_b n.
  // Apply the Lab 5 impulse when the spheres approach
  // TODO(student): j = impulseMagnitude(A, B, p, n, epsilon); unless j > 0 return 0; applyImpulse(A, B, p, j n); copy v back; return j.
  notImplemented("resolveSphereImpact", "Lab 5 handout, section 9", x_a, v_a, m_a, x_b, v_b, m_b, r_b, epsilon);
}

}  // namespace physlab
