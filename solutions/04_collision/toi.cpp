// Lab 4, section 9: the time of impact of two moving bodies within a step, by bisection on the
// overlap test and by conservative advancement on the distance.
#include <algorithm>
#include <cmath>

#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {
namespace {

// InvalidInput naming the shape, pose or motion (of a or b) that validateShape(), validatePose() or
// validateMotion() refuses.
void validateBodies(const Shape& a, const Pose& pose_a, const Motion& motion_a, const Shape& b, const Pose& pose_b,
                    const Motion& motion_b) {
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateMotion(motion_a, "motion_a");
  validateShape(b, "shape b");
  validatePose(pose_b, "pose_b");
  validateMotion(motion_b, "motion_b");
}

}  // namespace

ToiResult toiBisection(const Shape& a, const Pose& pose_a, const Motion& motion_a, const Shape& b,
                       const Pose& pose_b, const Motion& motion_b, double h, double tolerance) {
  // Refuse a step or tolerance that is not positive: the bracket could never get short enough
  requirePositive(h, "time step h");
  requirePositive(tolerance, "time-of-impact tolerance");
  // Refuse bad shapes, poses and motions here, naming them, rather than at some later time's query
  validateBodies(a, pose_a, motion_a, b, pose_b, motion_b);
  ToiResult result;
  auto overlapAt = [&](double t) {
    ++result.queries;
    return distance(a, advance(pose_a, motion_a, t), b, advance(pose_b, motion_b, t)).overlap;
  };
  // Bound how fast any point can approach: the relative speed plus the spin of the far points
  const Vec3 relative = motion_b.v - motion_a.v;
  const double mu = approachSpeedBound(a, motion_a, b, motion_b,
                                       relative.squaredNorm() > 0.0 ? Vec3(relative.normalized()) : Vec3::UnitX());
  // Sample the step finely enough that a thin shape cannot be skipped
  const double spacing = innerRadius(a) + innerRadius(b), reach = std::max(mu, 0.0) * h;
  const int samples = reach > 0.0 ? static_cast<int>(std::clamp(std::ceil(reach / spacing), 1.0, 4096.0)) : 1;
  if (overlapAt(0.0)) {
    result.hit = true;
    return result;
  }
  double lo = 0.0;
  for (int k = 1; k <= samples; ++k) {
    double hi = h * k / samples;
    if (!overlapAt(hi)) {
      lo = hi;
      continue;
    }
    // Halve the bracket [lo, hi] (apart at lo, overlapping at hi) until it is short enough
    while (mu * (hi - lo) > tolerance) {
      const double mid = 0.5 * (lo + hi);
      (overlapAt(mid) ? hi : lo) = mid;
    }
    result.hit = true;
    result.time = lo;
    return result;
  }
  return result;
}

ToiResult toiConservativeAdvancement(const Shape& a, const Pose& pose_a, const Motion& motion_a, const Shape& b,
                                     const Pose& pose_b, const Motion& motion_b, double h, double tolerance) {
  // Refuse a step or tolerance that is not positive: the bracket could never get short enough
  requirePositive(h, "time step h");
  requirePositive(tolerance, "time-of-impact tolerance");
  // Refuse bad shapes, poses and motions here, naming them, rather than at some later time's query
  validateBodies(a, pose_a, motion_a, b, pose_b, motion_b);
  ToiResult result;
  double t = 0.0;
  while (result.queries < 100000) {
    // Measure the distance and the direction of the closest points at t
    ++result.queries;
    const DistanceResult d = distance(a, advance(pose_a, motion_a, t), b, advance(pose_b, motion_b, t));
    if (d.overlap || d.distance <= tolerance) {
      result.hit = true;
      result.time = t;
      return result;
    }
    // No point closes the gap faster than mu along n: advance by d / mu
    const Vec3 n = (d.point_a - d.point_b).normalized();
    const double mu = approachSpeedBound(a, motion_a, b, motion_b, n);
    if (mu <= 0.0) return result;
    t += d.distance / mu;
    if (t > h) return result;
  }
  throw NumericalFailure("conservative advancement took 100000 steps without reaching the tolerance");
}

}  // namespace physlab
