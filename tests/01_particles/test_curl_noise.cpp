// Lab 1 graded tests of section 7: the smooth ramp, a velocity computed by hand, the divergence
// of the velocity field, the normal velocity on the solid's boundary, and tracers that never
// enter the solid.
#include "physlab/curl_noise.hpp"
#include "physlab/error.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

constexpr double kUnitRoundoff = 1.1102230246251565e-16;  // 2^-53

// A seeded noise of `count` waves with |kappa| in [1, 4] and amplitudes in [0.05, 0.2], around a
// disc of radius 0.5 at a random centre near the origin, ramp width 0.4, step 1e-4.
CurlNoise curlField(int count) {
  std::vector<NoiseWave> waves;
  for (int k = 0; k < count; ++k) {
    const double angle = uniform(0.0, 2.0 * M_PI), size = uniform(1.0, 4.0);
    waves.push_back({uniform(0.05, 0.2), size * Eigen::Vector2d(std::cos(angle), std::sin(angle)), uniform(0.0, 2.0 * M_PI)});
  }
  return CurlNoise(waves, Vec3(uniform(-0.2, 0.2), uniform(-0.2, 0.2), 0.0), 0.5, 0.4, 1e-4);
}

double curlAmplitudeSum(const CurlNoise& field) {
  double sum = 0.0;
  for (const NoiseWave& w : field.waves) sum += std::abs(w.amplitude);
  return sum;
}

// The discrete divergence of the student's velocity by central differences with step e.
double curlDivergence(const CurlNoise& field, const Vec3& p, double e) {
  const Vec3 ex(e, 0.0, 0.0), ey(0.0, e, 0.0);
  return (curlNoiseVelocity(field, p + ex).x() - curlNoiseVelocity(field, p - ex).x()) / (2.0 * e) +
         (curlNoiseVelocity(field, p + ey).y() - curlNoiseVelocity(field, p - ey).y()) / (2.0 * e);
}

// One classical RK4 step of dx/dt = v(x), written here.
Vec3 curlRK4(const CurlNoise& field, const Vec3& p, double h) {
  const Vec3 k1 = curlNoiseVelocity(field, p);
  const Vec3 k2 = curlNoiseVelocity(field, p + 0.5 * h * k1);
  const Vec3 k3 = curlNoiseVelocity(field, p + 0.5 * h * k2);
  const Vec3 k4 = curlNoiseVelocity(field, p + h * k3);
  return p + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

}  // namespace

TEST_CASE("curl noise: the smooth ramp at fixed points: 0 at 0, odd, clamped to +-1 from |s| = 1 on, a NaN refused", "[lab01][pts=1][sec=7]") {
  CHECK(smoothRamp(0.0) == 0.0);
  // 15/8 s - 10/8 s^3 + 3/8 s^5 at s = 1/2: 15/16 - 10/64 + 3/256 = 203/256, exact in binary.
  CHECK(smoothRamp(0.5) == Approx(203.0 / 256.0).epsilon(1e-15));
  CHECK(smoothRamp(-0.5) == Approx(-203.0 / 256.0).epsilon(1e-15));
  CHECK(smoothRamp(1.0) == 1.0);  // the end included, and the quintic reaches 1 there too
  CHECK(smoothRamp(-1.0) == -1.0);
  const double s = uniform(1.0, 100.0);
  CHECK(smoothRamp(s) == 1.0);
  CHECK(smoothRamp(-s) == -1.0);
  const double t = uniform(-1.0, 1.0);
  CHECK(smoothRamp(t) == Approx(15.0 / 8.0 * t - 10.0 / 8.0 * t * t * t + 3.0 / 8.0 * std::pow(t, 5)).margin(1e-15));
  CHECK_THROWS_AS(smoothRamp(std::numeric_limits<double>::quiet_NaN()), InvalidInput);
}

TEST_CASE("curl noise: the ramp is of d / L: widths below and above 1 reach +-1 at d = +-L exactly, bend the flow inside", "[lab01][pts=1][sec=7]") {
  // A constant noise psi_0 = a sin(pi/2) = 1/2 (kappa = 0) around the disc |p| <= 1/2: then
  // psi = ramp(d / L) / 2, and on the x axis d = x - 1/2 exactly. Binary fractions throughout:
  // s = d / L, the ramp's clamp and its value at s = +-1/2 (203/256) are exact.
  const double a = 0.5, R = 0.5;
  for (const double L : {0.375, 2.5}) {
    const CurlNoise field({{a, Eigen::Vector2d::Zero(), M_PI / 2.0}}, Vec3::Zero(), R, L, 1e-4);
    REQUIRE(field.noise(Vec3::Zero()) == a);
    CAPTURE(L);
    const auto psiAt = [&](double d) { return streamFunction(field, Vec3(R + d, 0.0, 0.3)); };
    CHECK(psiAt(0.0) == 0.0);                     // on the circle
    CHECK(psiAt(L) == a);                         // s = 1: the end of the band, included
    CHECK(psiAt(2.0 * L) == a);                   // beyond it, the noise itself
    // s = 1/2 and s = 3/4 inside the band: the quintic of s, not of d. Horner against the
    // expanded form: a few ulps.
    CHECK(psiAt(0.5 * L) == Approx(a * 203.0 / 256.0).epsilon(1e-15));
    const double s = 0.75, quintic = 15.0 / 8.0 * s - 10.0 / 8.0 * s * s * s + 3.0 / 8.0 * std::pow(s, 5);
    CHECK(psiAt(0.75 * L) == Approx(a * quintic).epsilon(1e-15));
    if (L < R) {
      CHECK(psiAt(-L) == -a);                     // s = -1 inside the disc: clamped to -1
      CHECK(psiAt(-0.5 * L) == Approx(-a * 203.0 / 256.0).epsilon(1e-15));  // odd: a few ulps
    } else {
      // The disc's centre is d = -R = -L / 5 deep: s = -1/5, inside the band
      const double c = -R / L, at_centre = 15.0 / 8.0 * c - 10.0 / 8.0 * c * c * c + 3.0 / 8.0 * std::pow(c, 5);
      CHECK(streamFunction(field, Vec3::Zero()) == Approx(a * at_centre).epsilon(1e-14));  // d and s rounded once each
    }
    // On the circle the flow runs along it at |v| = a ramp'(0) / L = 15 a / (8 L): 2.5 m/s for
    // L = 0.375, 0.375 m/s for L = 2.5. Central differences with e = 1e-4 err by e^2 / 6 times
    // psi's third derivative along x, a 7.5 / L^3 = 71 at most: 1.2e-7, relative 5e-8.
    const Vec3 v = curlNoiseVelocity(field, Vec3(R, 0.0, 0.0));
    CHECK(v.y() == Approx(-15.0 * a / (8.0 * L)).epsilon(1e-6));
    CHECK(std::abs(v.x()) <= 1e-12);  // psi is even in y here: the difference along y cancels but for rounding
  }
  // Seeded: a random width in [0.2, 5] (never 1 within 10 %), a random noise, points at seeded
  // s = d / L in [-min(1, R / L), 1.5], their psi the ramp of s times the field's own noise
  double L = uniform(0.2, 5.0);
  if (std::abs(L - 1.0) < 0.1) L += 0.25;
  std::vector<NoiseWave> waves;
  for (int k = 0; k < 3; ++k) {
    const double angle = uniform(0.0, 2.0 * M_PI), size = uniform(1.0, 4.0);
    waves.push_back({uniform(0.05, 0.2), size * Eigen::Vector2d(std::cos(angle), std::sin(angle)), uniform(0.0, 2.0 * M_PI)});
  }
  const CurlNoise field(waves, Vec3(uniform(-0.2, 0.2), uniform(-0.2, 0.2), 0.0), R, L, 1e-4);
  CAPTURE(L);
  for (int k = 0; k < 40; ++k) {
    const double angle = uniform(0.0, 2.0 * M_PI), s = uniform(-std::min(1.0, R / L), 1.5);
    const Vec3 p = field.centre + (R + s * L) * Vec3(std::cos(angle), std::sin(angle), 0.0);
    const double t = std::max(-1.0, std::min(1.0, field.distance(p) / L));
    const double expected = (15.0 / 8.0 * t - 10.0 / 8.0 * t * t * t + 3.0 / 8.0 * std::pow(t, 5)) * field.noise(p);
    CAPTURE(s);
    // The same product with the quintic in another order: a few ulps of |psi| <= sum |a_k| < 0.6.
    CHECK(streamFunction(field, p) == Approx(expected).margin(4e-15));
  }
}

TEST_CASE("curl noise: a velocity computed by hand for one sinusoid far from the solid", "[lab01][pts=1][sec=7]") {
  // psi_0 = a sin(kappa . p + phi); farther than L from the disc the ramp is 1, so
  // v = (dpsi/dy, -dpsi/dx) = a cos(kappa . p + phi) (kappa_y, -kappa_x).
  const double a = 0.3, phase = 0.4;
  const Eigen::Vector2d kappa(2.0, -1.0);
  const CurlNoise field({{a, kappa, phase}}, Vec3(10.0, 10.0, 0.0), 1.0, 1.0, 1e-4);
  const Vec3 p(0.25, -0.5, 0.7);  // kappa . p = 1, z ignored
  const double arg = 1.0 + phase;
  CHECK(streamFunction(field, p) == Approx(a * std::sin(arg)).epsilon(1e-14));
  const Vec3 v = curlNoiseVelocity(field, p);
  // Central differences of a sinusoid: relative error (e |kappa|)^2 / 6 = 8e-9, plus round-off
  // 1e-16 / e = 1e-12.
  CHECK(v.x() == Approx(a * std::cos(arg) * kappa.y()).epsilon(1e-8));
  CHECK(v.y() == Approx(-a * std::cos(arg) * kappa.x()).epsilon(1e-8));
  CHECK(v.z() == 0.0);
  CHECK_THROWS_AS(curlNoiseVelocity(field, Vec3(0.0, std::numeric_limits<double>::quiet_NaN(), 0.0)), InvalidInput);
}

TEST_CASE("curl noise: divergence-free: the central-difference divergence at seeded points and a fixed point is zero to round-off", "[lab01][pts=2][sec=7]") {
  const CurlNoise field = curlField(5);
  const double e = field.step;
  // With the field's own step, the two halves of the divergence evaluate psi at the same four
  // corners p +- e x +- e y and cancel exactly but for rounding: four differences of psi values
  // (each rounded by at most 2u max|psi|, max|psi| <= sum |a_k|) over 2e, then over 2e again,
  // and the divisions: 8 u max|psi| / e^2 bounds it (2e-7 here; a gradient instead of a curl
  // gives the Laplacian, |kappa|^2 psi ~ 0.1 to 3).
  const double bound = 8.0 * kUnitRoundoff * curlAmplitudeSum(field) / (e * e);
  std::vector<Vec3> points{field.centre + Vec3(0.6, 0.3, 0.0)};  // fixed: inside the ramp band
  for (int k = 0; k < 40; ++k) points.push_back(Vec3(uniform(-2.0, 2.0), uniform(-2.0, 2.0), uniform(-1.0, 1.0)));
  double fastest = 0.0;
  for (const Vec3& p : points) {
    CAPTURE(p.transpose());
    CHECK(std::abs(curlDivergence(field, p, e)) <= bound);
    fastest = std::max(fastest, curlNoiseVelocity(field, p).norm());
  }
  CHECK(fastest > 0.05);  // the field does flow: a zero velocity has no divergence either
}

TEST_CASE("curl noise: zero normal velocity on the solid's boundary, the flow along it", "[lab01][pts=2][sec=7]") {
  const CurlNoise field = curlField(4);
  double along = 0.0;
  for (int k = 0; k < 60; ++k) {
    const double angle = uniform(0.0, 2.0 * M_PI);
    const Vec3 n(std::cos(angle), std::sin(angle), 0.0);
    const Vec3 p = field.centre + field.radius * n + Vec3(0.0, 0.0, uniform(-1.0, 1.0));
    CAPTURE(angle);
    // psi = ramp(d / L) psi_0 with d ~ 1e-16 on the circle: round-off of d only.
    CHECK(std::abs(streamFunction(field, p)) < 1e-14);
    const Vec3 v = curlNoiseVelocity(field, p);
    // Exactly zero for the exact curl; the central differences err by O(e^2) times third
    // derivatives of psi (ramp slope 15/8 / L ~ 5, |kappa| <= 4, curvature 1 / R = 2): below 1e-5.
    CHECK(std::abs(v.dot(n)) < 1e-5);
    along = std::max(along, std::abs(v.y() * n.x() - v.x() * n.y()));
  }
  CHECK(along > 1e-2);  // the boundary is a streamline, not a place where the flow stops
}

TEST_CASE("curl noise: tracers advected by RK4 never enter the solid", "[lab01][pts=2][sec=7]") {
  const CurlNoise field = curlField(4);
  const double h = 0.01;
  const long steps = 1500;
  for (int k = 0; k < 12; ++k) {
    const double angle = uniform(0.0, 2.0 * M_PI), start = uniform(0.01, 0.3);
    Vec3 p = field.centre + (field.radius + start) * Vec3(std::cos(angle), std::sin(angle), 0.0);
    CAPTURE(k, angle, start);
    const Vec3 p0 = p;
    double closest = field.distance(p), travelled = 0.0;
    for (long n = 0; n < steps; ++n) {
      const Vec3 next = curlRK4(field, p, h);
      travelled += (next - p).norm();
      p = next;
      closest = std::min(closest, field.distance(p));
    }
    // A tracer keeps its value of psi, which is zero only on the circle (and on the noise's own
    // zero curves, which keep it out as well): it never reaches the boundary.
    CHECK(closest > 0.0);
    CHECK(std::isfinite(p.sum()));
    CHECK(travelled > 0.05);  // and it does move
    CHECK(p.z() == p0.z());   // the flow is planar
  }
}
