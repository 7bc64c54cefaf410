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
  requirePositive(r_a, "sphereImpactTime radius r_a");
  requirePositive(r_b, "sphereImpactTime radius r_b");
  requireFinite(x_a, "sphereImpactTime position x_a");
  requireFinite(v_a, "sphereImpactTime velocity v_a");
  requireFinite(x_b, "sphereImpactTime position x_b");
  requireFinite(v_b, "sphereImpactTime velocity v_b");
  // Only an approach can end in an impact: d . w < 0
  const Vec3 d = x_a - x_b, w = v_a - v_b;
  const double half_b = d.dot(w);
  constexpr double kNever = std::numeric_limits<double>::infinity();
  if (!(half_b < 0.0)) return kNever;
  // Touching or overlapping now: the impact is now
  const double R = r_a + r_b;
  const double c = d.squaredNorm() - R * R;
  if (c <= 0.0) return 0.0;
  // Solve (w.w) s^2 + 2 (d.w) s + c = 0; a miss has no real root, a graze one double root
  const double a = w.squaredNorm();
  const double discriminant = half_b * half_b - a * c;
  if (!(discriminant > 0.0)) return kNever;
  // The smaller root in the form without cancellation: -d.w > 0 and sqrt(disc) add
  return c / (-half_b + std::sqrt(discriminant));
}

std::vector<double> rollbackTimes(const std::vector<TimewarpEvent>& events, int body_count, const std::vector<int>& seeds,
                                  double t_c) {
  // Refuse a negative count, a time that is not finite, bodies outside the scene and unsorted events
  if (body_count < 0) throw InvalidInput("rollbackTimes body_count must be non-negative, got " + std::to_string(body_count));
  requireFinite(Vec3(t_c, 0.0, 0.0), "rollbackTimes time of impact t_c");
  const auto inScene = [body_count](int k) { return k >= 0 && k < body_count; };
  for (std::size_t s = 0; s < seeds.size(); ++s) {
    if (!inScene(seeds[s])) {
      throw InvalidInput("rollbackTimes seed " + std::to_string(s) + " names body " + std::to_string(seeds[s]) +
                         ", outside [0, body_count)");
    }
  }
  for (std::size_t e = 0; e < events.size(); ++e) {
    const std::string name = "rollbackTimes event " + std::to_string(e);
    if (!inScene(events[e].a) || !inScene(events[e].b)) throw InvalidInput(name + " names a body outside [0, body_count)");
    requireFinite(Vec3(events[e].t, 0.0, 0.0), name + " time t");
    if (e > 0 && events[e].t < events[e - 1].t) throw InvalidInput(name + " is earlier than the one before: events must be sorted by time");
  }
  // The colliding pair goes back to the time of impact; everybody else keeps its state
  std::vector<double> r(static_cast<std::size_t>(body_count), std::numeric_limits<double>::infinity());
  for (const int k : seeds) r[k] = std::min(r[k], t_c);
  // In time order, undo each event that used a rolled-back state: both its bodies go back to it
  for (const TimewarpEvent& event : events) {
    if (event.t > r[event.a] || event.t > r[event.b]) {
      r[event.a] = std::min(r[event.a], event.t);
      r[event.b] = std::min(r[event.b], event.t);
    }
  }
  return r;
}

double resolveSphereImpact(const Vec3& x_a, Vec3& v_a, double m_a, const Vec3& x_b, Vec3& v_b, double m_b, double r_b,
                           double epsilon) {
  // Refuse masses that are not positive and centres that coincide (no normal)
  requirePositive(m_a, "resolveSphereImpact mass m_a");
  requirePositive(m_b, "resolveSphereImpact mass m_b");
  requireFinite(x_a, "resolveSphereImpact position x_a");
  requireFinite(x_b, "resolveSphereImpact position x_b");
  const Vec3 d = x_a - x_b;
  requirePositive(d.norm(), "resolveSphereImpact distance between the centres |x_a - x_b|");
  // Build the two bodies and the contact: normal from B to A, point on B's surface
  ContactBody A, B;
  A.x = x_a;
  A.v = v_a;
  A.inv_mass = 1.0 / m_a;
  B.x = x_b;
  B.v = v_b;
  B.inv_mass = 1.0 / m_b;
  const Vec3 n = d / d.norm();
  const Vec3 p = x_b + r_b * n;
  // Apply the Lab 5 impulse when the spheres approach
  const double j = impulseMagnitude(A, B, p, n, epsilon);
  if (!(j > 0.0)) return 0.0;
  applyImpulse(A, B, p, j * n);
  v_a = A.v;
  v_b = B.v;
  return j;
}

}  // namespace physlab
