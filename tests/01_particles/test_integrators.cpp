// Lab 1 graded tests: the integrators, checked against the harmonic oscillator's exact energy
// behaviour, measured convergence orders, stability boundaries and the Kepler problem.
#include "physlab/scenes.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

VecX randomOscillatorState() { return VecX(Eigen::Vector2d(uniform(0.5, 2.0), uniform(-2.0, 2.0))); }

// Ratio E_{n+1} / E_n on every one of `steps` steps of `method` at step h*omega = hw.
std::vector<double> energyRatios(Method method, double hw, int steps) {
  const HarmonicOscillator osc(uniform(0.5, 3.0));
  VecX X = randomOscillatorState();
  std::vector<double> ratios;
  double E = osc.energy(X);
  run(method, osc, X, hw / osc.omega, steps, [&](long, const VecX& Y) {
    ratios.push_back(osc.energy(Y) / E);
    E = osc.energy(Y);
  });
  return ratios;
}

// Largest |E - E0| / E0 over `steps` steps.
double maxEnergyError(Method method, double hw, long steps) {
  const HarmonicOscillator osc(uniform(0.5, 3.0));
  VecX X = randomOscillatorState();
  const double E0 = osc.energy(X);
  double worst = 0.0;
  run(method, osc, X, hw / osc.omega, steps,
      [&](long, const VecX& Y) { worst = std::max(worst, std::abs(osc.energy(Y) - E0) / E0); });
  return worst;
}

// Order p from three runs at h, h/2, h/4 on a Kepler orbit: the differences between successive
// results shrink by 2^p, so p = log2(|X_h - X_h/2| / |X_h/2 - X_h/4|) needs no exact solution.
double measuredOrder(Method method, double h) {
  const Kepler kepler(1.0);
  const double e = uniform(0.2, 0.5);
  const VecX X0 = kepler.perihelionState(1.0, e);
  const double T = 1.0;
  std::vector<VecX> results;
  for (int refine = 0; refine < 3; ++refine) {
    const double hr = h / (1 << refine);
    VecX X = X0;
    run(method, kepler, X, hr, std::lround(T / hr));
    results.push_back(X);
  }
  return std::log2((results[0] - results[1]).norm() / (results[1] - results[2]).norm());
}

void checkOrder(Method method, double h) {
  const double p = measuredOrder(method, h);
  INFO(methodName(method) << ": measured order " << p << ", expected " << methodOrder(method));
  // +-0.15: the step sizes sit in the asymptotic range, where higher-order terms shift the
  // measured slope by a few hundredths; a method one order off misses by 1.
  CHECK(p == Approx(methodOrder(method)).margin(0.15));
}

// Spectral radius of one step of `method` on the oscillator at h*omega = hw. The step is a
// linear map of the state, so applying it to the unit vectors gives its matrix.
double spectralRadius(Method method, double hw) {
  const HarmonicOscillator osc(1.0);
  Eigen::Matrix2d A;
  for (int j = 0; j < 2; ++j) {
    VecX X = VecX::Unit(2, j);
    run(method, osc, X, hw, 1);
    A.col(j) = X;
  }
  return physlab::spectralRadius(A);
}

// Unstable means the step map grows some state; 1e-9 is far above round-off in the radius
// (1e-15) and far below the growth of explicit Euler at the smallest scanned step (5e-7).
bool stable(Method method, double hw) { return spectralRadius(method, hw) <= 1.0 + 1e-9; }

// Scans h*omega from 1e-3 to 1e4 and bisects the first stable->unstable change to 1e-9.
// Returns 0 when no scanned step is stable and infinity when every scanned step is.
double stabilityBoundary(Method method) {
  double lo = 1e-3;
  if (!stable(method, lo)) return 0.0;
  double hi = lo;
  while (hi < 1e4) {
    hi *= 1.1;
    if (!stable(method, hi)) break;
    lo = hi;
  }
  if (hi >= 1e4) return std::numeric_limits<double>::infinity();
  while (hi - lo > 1e-9) {
    const double mid = 0.5 * (lo + hi);
    (stable(method, mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

TEST_CASE("oscillator: explicit Euler's energy grows by exactly 1+(h omega)^2 per step", "[lab01][pts=2][sec=3]") {
  const double hw = uniform(0.01, 0.5);
  for (double ratio : energyRatios(Method::ExplicitEuler, hw, 50)) {
    // Exact algebra: only round-off (1e-15 per step) separates the ratio from 1+(h omega)^2.
    REQUIRE(ratio == Approx(1.0 + hw * hw).epsilon(1e-12));
  }
}

TEST_CASE("oscillator: implicit Euler's energy decays by exactly 1/(1+(h omega)^2) per step", "[lab01][pts=2][sec=3]") {
  const double hw = uniform(0.01, 0.5);
  for (double ratio : energyRatios(Method::ImplicitEuler, hw, 50)) {
    // Newton converges to 1e-12 relative on this linear system, so the ratio is exact to ~1e-11.
    REQUIRE(ratio == Approx(1.0 / (1.0 + hw * hw)).epsilon(1e-10));
  }
}

TEST_CASE("oscillator: symplectic Euler keeps the energy bounded over 10^4 steps", "[lab01][pts=2][sec=3]") {
  const double hw = uniform(0.05, 0.5);
  const double error = maxEnergyError(Method::SymplecticEuler, hw, 10000);
  INFO("h omega = " << hw << ", largest relative energy error " << error);
  // Symplectic Euler exactly conserves the modified energy E - (h omega^2 / 2) x v, and
  // |omega x v| <= E, so E stays within a factor (1 +- h omega / 2) of it: |E - E0| / E0 is at
  // most h omega / (1 - h omega / 2), for ever. Explicit Euler would reach 10^10 here.
  CHECK(error < 1.001 * hw / (1.0 - hw / 2.0));
  CHECK(error > 0.1 * hw);  // the known O(h omega) oscillation is there: the method is first order
}

TEST_CASE("oscillator: Verlet keeps the energy bounded over 10^4 steps", "[lab01][pts=2][sec=3]") {
  const double hw = uniform(0.05, 0.5);
  const double error = maxEnergyError(Method::Verlet, hw, 10000);
  INFO("h omega = " << hw << ", largest relative energy error " << error);
  // Velocity Verlet's energy error oscillates with amplitude ~ (h omega)^2 / 4 and never drifts.
  CHECK(error < 0.3 * hw * hw);
  CHECK(error > 0.05 * hw * hw);  // second order: the O((h omega)^2) oscillation is there
}

TEST_CASE("convergence: explicit Euler is first order", "[lab01][pts=1][sec=3]") {
  checkOrder(Method::ExplicitEuler, 1e-3);
}
TEST_CASE("convergence: symplectic Euler is first order", "[lab01][pts=1][sec=3]") {
  checkOrder(Method::SymplecticEuler, 1e-3);
}
TEST_CASE("convergence: midpoint is second order", "[lab01][pts=1][sec=3]") {
  checkOrder(Method::Midpoint, 5e-3);
}
TEST_CASE("convergence: trapezoid is second order", "[lab01][pts=1][sec=3]") {
  checkOrder(Method::Trapezoid, 5e-3);
}
TEST_CASE("convergence: RK4 is fourth order", "[lab01][pts=1][sec=3]") { checkOrder(Method::RK4, 2e-2); }
TEST_CASE("convergence: Verlet is second order", "[lab01][pts=1][sec=3]") {
  checkOrder(Method::Verlet, 5e-3);
}
TEST_CASE("convergence: implicit Euler is first order", "[lab01][pts=1][sec=3]") {
  checkOrder(Method::ImplicitEuler, 1e-3);
}

TEST_CASE("stability: explicit Euler is unstable for every step", "[lab01][pts=1][sec=3]") {
  // Its step map has spectral radius sqrt(1+(h omega)^2) > 1 for all h > 0.
  CHECK(stabilityBoundary(Method::ExplicitEuler) == 0.0);
}

TEST_CASE("stability: symplectic Euler is stable up to h omega = 2", "[lab01][pts=1][sec=3]") {
  // The bisection resolves 1e-9; the boundary is exact, so 1e-6 only absorbs round-off.
  CHECK(stabilityBoundary(Method::SymplecticEuler) == Approx(2.0).margin(1e-6));
}

TEST_CASE("stability: Verlet is stable up to h omega = 2", "[lab01][pts=1][sec=3]") {
  CHECK(stabilityBoundary(Method::Verlet) == Approx(2.0).margin(1e-6));
}

TEST_CASE("stability: RK4 is stable up to h omega = 2 sqrt 2", "[lab01][pts=1][sec=3]") {
  CHECK(stabilityBoundary(Method::RK4) == Approx(2.0 * std::sqrt(2.0)).margin(1e-6));
}

TEST_CASE("stability: implicit Euler is stable for every step", "[lab01][pts=1][sec=3]") {
  CHECK(stabilityBoundary(Method::ImplicitEuler) == std::numeric_limits<double>::infinity());
}

namespace {

// Largest |H - H0| over the first and over the last 10 of `orbits` orbits (e = 0.6, H0 = -0.5).
std::pair<double, double> keplerEnergyError(Method method, double h, int orbits) {
  const Kepler kepler(1.0);
  VecX X = kepler.perihelionState(1.0, 0.6);
  const Mat3 R = randomRotation();  // the orbit's plane is random; the physics is not
  X.head<3>() = R * X.head<3>();
  X.tail<3>() = R * X.tail<3>();
  const double H0 = kepler.energy(X);
  const long steps_per_orbit = std::lround(kepler.period(1.0) / h);
  const long steps = steps_per_orbit * orbits;
  double first = 0.0, last = 0.0;
  run(method, kepler, X, h, steps, [&](long n, const VecX& Y) {
    const double dH = std::abs(kepler.energy(Y) - H0);
    if (n <= 10 * steps_per_orbit) first = std::max(first, dH);
    if (n > steps - 10 * steps_per_orbit) last = std::max(last, dH);
  });
  return {first, last};
}

}  // namespace

TEST_CASE("Kepler: Verlet's energy error stays bounded over 1000 orbits", "[lab01][pts=2][sec=3]") {
  const auto [first, last] = keplerEnergyError(Method::Verlet, 0.05, 1000);
  INFO("max |dH| over the first 10 orbits " << first << ", over the last 10 " << last);
  // A symplectic method's error oscillates with the orbit: the last orbits' peak stays within
  // 1.5x of the first ones' (sampling moves the peak a little); a drifting method grows ~100x.
  CHECK(last < 1.5 * first);
  CHECK(first < 0.05);  // and it is small: O(h^2) at perihelion, where the orbit is fastest
}

TEST_CASE("Kepler: RK4's energy error grows over 1000 orbits", "[lab01][pts=2][sec=3]") {
  const auto [first, last] = keplerEnergyError(Method::RK4, 0.05, 1000);
  INFO("max |dH| over the first 10 orbits " << first << ", over the last 10 " << last);
  // RK4 is not symplectic: its energy error accumulates orbit after orbit, about linearly, so
  // after 1000 orbits it is tens of times the first 10 orbits' peak.
  CHECK(last > 20.0 * first);
}
