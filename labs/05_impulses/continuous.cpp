// Lab 5, section 10: continuous collision: how long a fast body moves in a step.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

double continuousAdvance(const std::vector<double>& hits, double h, double speed, double overlap) {
  // Refuse a step, speed or depth that is not a finite number of the right sign
  // TODO(student): requirePositive(h, "continuousAdvance step h"); requireNonNegative() on speed and
  //   on overlap ("continuousAdvance speed", "continuousAdvance overlap").
  // The earliest hit after 0; a hit at 0 is a contact the solver answers
  // TODO(student): refuse a hit that is NaN, negative or past h (but +infinity is a miss), naming
  //   its index; keep the smallest hit that is > 0.
  // Move on into the body by the overlap, never past the step
  // TODO(student): h when no hit came after 0 or speed is 0; else min(h, earliest + overlap / speed).
  notImplemented("continuousAdvance", "Lab 5 handout, section 10", hits, h, speed, overlap);
}

}  // namespace physlab
