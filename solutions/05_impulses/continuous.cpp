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
  requirePositive(h, "continuousAdvance step h");
  requireNonNegative(speed, "continuousAdvance speed");
  requireNonNegative(overlap, "continuousAdvance overlap");
  // The earliest hit after 0; a hit at 0 is a contact the solver answers
  double earliest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const double t = hits[k];
    if (!(t >= 0.0) || (t > h && !std::isinf(t))) {
      throw InvalidInput("continuousAdvance hit " + std::to_string(k) + " = " + std::to_string(t) +
                         " is not in [0, h] or +infinity");
    }
    if (t > 0.0 && t < earliest) earliest = t;
  }
  // Move on into the body by the overlap, never past the step
  if (std::isinf(earliest) || speed == 0.0) return h;
  return std::min(h, earliest + overlap / speed);
}

}  // namespace physlab
