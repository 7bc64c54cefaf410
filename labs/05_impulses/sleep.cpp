// Lab 5, section 12: sleeping: a body's time spent still, by which an island falls asleep.
#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

double sleepTimer(const Vec3& v, const Vec3& omega, double timer, double h, double linear, double angular) {
  // Refuse velocities that are not finite, a bad timer, step or threshold, naming it
  // TODO(student): requireFinite() on v and omega ("sleepTimer velocity v", "sleepTimer angular
  //   velocity omega"); requireNonNegative() on timer ("sleepTimer timer"), linear ("sleepTimer
  //   linear threshold") and angular ("sleepTimer angular threshold"); requirePositive(h, "sleepTimer step h").
  // Still at or below both thresholds: the timer grows by the step; else it starts again
  // TODO(student): still when |v| <= linear and |omega| <= angular (both ends count as still);
  //   return timer + h when still, else 0.
  notImplemented("sleepTimer", "Lab 5 handout, section 12", v, omega, timer, h, linear, angular);
}

}  // namespace physlab
