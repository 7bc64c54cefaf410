// Lab 5, section 12: sleeping: a body's time spent still, by which an island falls asleep.
#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

double sleepTimer(const Vec3& v, const Vec3& omega, double timer, double h, double linear, double angular) {
  // Refuse velocities that are not finite, a bad timer, step or threshold, naming it
  requireFinite(v, "sleepTimer velocity v");
  requireFinite(omega, "sleepTimer angular velocity omega");
  requireNonNegative(timer, "sleepTimer timer");
  requirePositive(h, "sleepTimer step h");
  requireNonNegative(linear, "sleepTimer linear threshold");
  requireNonNegative(angular, "sleepTimer angular threshold");
  // Still at or below both thresholds: the timer grows by the step; else it starts again
  const bool still = v.norm() <= linear && omega.norm() <= angular;
  return still ? timer + h : 0.0;
}

}  // namespace physlab
