// Lab 1, section 7: curl noise, a divergence-free flow around a solid disc.
#include <cmath>

#include "physlab/curl_noise.hpp"
#include "physlab/error.hpp"

namespace physlab {

// ---- smooth ramp ----------------------------------------------------------------------------

double smoothRamp(double s) {
  // Refuse a NaN, clamp outside [-1, 1]
  // TODO(student): throw InvalidInput on NaN; 1 for s >= 1, -1 for s <= -1.
  // The odd quintic 15/8 s - 10/8 s^3 + 3/8 s^5, in Horner form
  // TODO(student): s (15/8 + s^2 (-10/8 + s^2 3/8)).
  notImplemented("smoothRamp", "Lab 1 handout, section 7", s);
}

// ---- stream function ------------------------------------------------------------------------

double streamFunction(const CurlNoise& field, const Vec3& p) {
  // Scale the noise by the ramp of the distance to the disc, so psi = 0 on its boundary
  // TODO(student): requireFinite(p, ...); ramp(field.distance(p) / field.ramp_width) * field.noise(p).
  notImplemented("streamFunction", "Lab 1 handout, section 7", field, p);
}

// ---- velocity -------------------------------------------------------------------------------

Vec3 curlNoiseVelocity(const CurlNoise& field, const Vec3& p) {
  // Central differences of psi along y and x with the field's step
  // TODO(student): requireFinite(p, ...); (psi(p + e y) - psi(p - e y)) / 2e and the same along x.
  // The curl of (0, 0, psi)
  // TODO(student): v = (dpsi/dy, -dpsi/dx, 0).
  notImplemented("curlNoiseVelocity", "Lab 1 handout, section 7", field, p);
}

}  // namespace physlab
