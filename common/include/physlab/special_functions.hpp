/// \file special_functions.hpp
/// \brief Special functions that not every standard library has: C++17's mathematical special
/// functions (std::comp_ellint_1 and the rest) are in libstdc++ but not in libc++ (clang's, and
/// macOS's only one), so the demos and tests that need one use its version here.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include "physlab/error.hpp"

namespace physlab {

/// The complete elliptic integral of the first kind, K(k) = integral over 0 <= t <= pi/2 of
/// dt / sqrt(1 - k^2 sin^2 t), in std::comp_ellint_1's convention (the modulus k, not the
/// parameter k^2). By the arithmetic-geometric mean, K(k) = (pi/2) / AGM(1, sqrt(1 - k^2)), which
/// converges quadratically: to round-off within 6 steps for sqrt(1 - k^2) = 1e-3. InvalidInput
/// unless |k| < 1 (K is infinite at |k| = 1).
inline double completeEllipticK(double k) {
  if (!(std::abs(k) < 1.0)) throw InvalidInput("elliptic modulus k = " + std::to_string(k) + " must lie in (-1, 1)");
  double a = 1.0, g = std::sqrt((1.0 - k) * (1.0 + k));
  while (a - g > 2.0 * std::numeric_limits<double>::epsilon() * a) {
    const double mean = 0.5 * (a + g);
    g = std::sqrt(a * g);
    a = mean;
  }
  return std::acos(0.0) / a;
}

}  // namespace physlab
