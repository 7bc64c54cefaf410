// Lab 1, section 7: curl noise, a divergence-free flow around a solid disc.
#include <cmath>

#include "physlab/curl_noise.hpp"
#include "physlab/error.hpp"

namespace physlab {

// ---- smooth ramp ----------------------------------------------------------------------------

double smoothRamp(double s) {
  // Refuse a NaN, clamp outside [-1, 1]
  if (std::isnan(s)) throw InvalidInput("smoothRamp argument s is NaN");
  if (s >= 1.0) return 1.0;
  if (s <= -1.0) return -1.0;
  // The odd quintic 15/8 s - 10/8 s^3 + 3/8 s^5, in Horner form
  const double s2 = s * s;
  return s * (15.0 / 8.0 + s2 * (-10.0 / 8.0 + s2 * (3.0 / 8.0)));
}

// ---- stream function ------------------------------------------------------------------------

double streamFunction(const CurlNoise& field, const Vec3& p) {
  requireFinite(p, "streamFunction point p");
  // Scale the noise by the ramp of the distance to the disc, so psi = 0 on its boundary
  return smoothRamp(field.distance(p) / field.ramp_width) * field.noise(p);
}

// ---- velocity -------------------------------------------------------------------------------

Vec3 curlNoiseVelocity(const CurlNoise& field, const Vec3& p) {
  requireFinite(p, "curlNoiseVelocity point p");
  // Central differences of psi along y and x with the field's step
  const double e = field.step;
  const Vec3 ex(e, 0.0, 0.0), ey(0.0, e, 0.0);
  const double dpsi_dy = (streamFunction(field, p + ey) - streamFunction(field, p - ey)) / (2.0 * e);
  const double dpsi_dx = (streamFunction(field, p + ex) - streamFunction(field, p - ex)) / (2.0 * e);
  // The curl of (0, 0, psi)
  return Vec3(dpsi_dy, -dpsi_dx, 0.0);
}

}  // namespace physlab
