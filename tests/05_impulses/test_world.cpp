// Lab 5 graded tests of the World with impulses: a bouncing ball, Newton's cradle (both solvers
// reach the velocity-level LCP answer), friction on a sliding box and a thrown sphere, and
// penalty springs.
#include <algorithm>
#include <cmath>

#include "impulse_support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

constexpr double kG = 9.81;

// Runs `world` for `steps` steps of h.
void run(World& world, double h, long steps) {
  for (long n = 0; n < steps; ++n) world.step(h);
}

// The heights of the ball's lowest point (radius r) at its first `count` apexes after the drop.
std::vector<double> apexHeights(World& world, double h, double r, int count) {
  std::vector<double> apexes;
  double previous_vz = 0.0;
  for (long n = 0; n < 200000 && static_cast<int>(apexes.size()) < count; ++n) {
    world.step(h);
    const double vz = world.velocity(1).z();
    if (previous_vz > 0.0 && vz <= 0.0) apexes.push_back(world.states()[1].x.z() - r);
    previous_vz = vz;
  }
  return apexes;
}

Settings noGravity(ResponseMethod method) {
  Settings settings;
  settings.gravity = Vec3::Zero();
  settings.method = method;
  return settings;
}

// The cradle's settings: no gravity, and sweeps enough for a chain of up to 6 balls to converge
// to the tolerance (the default 50 stop Gauss-Seidel at ~1e-6 of v0, Jacobi further away).
Settings cradleSettings(ResponseMethod method) {
  Settings settings = noGravity(method);
  settings.iterations = 10000;
  return settings;
}

// Velocities along x of the cradle's balls after the first ball hits the others.
std::vector<double> cradleAfter(int n, double v0, ResponseMethod method) {
  World world(newtonsCradle(n, v0), cradleSettings(method));
  world.step(1e-4);
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(world.velocity(i).x());
  return v;
}

}  // namespace

TEST_CASE("bouncing ball: apex heights fall by epsilon^2", "[lab05][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  const double epsilon = uniform(0.6, 0.9), H = uniform(0.5, 1.5), h = 1e-4;
  World world(bouncingBall(H, epsilon));
  const std::vector<double> apexes = apexHeights(world, h, 0.1, 3);
  REQUIRE(apexes.size() == 3);
  double height = H;
  for (double apex : apexes) {
    // The impact is seen up to one step late, at up to v h below the ground, and the apex is
    // sampled once per step: a few v h of error in each height, v = sqrt(2 g H).
    const double v = std::sqrt(2 * kG * height);
    CHECK(apex / height == Approx(epsilon * epsilon).margin(4 * v * h / apex));
    height = apex;
  }
}

TEST_CASE("Newton's cradle: sequential impulses reach the velocity-level LCP answer, not the cradle", "[lab05][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  // n touching balls of 1 kg, epsilon 1: the first contact approaches at v0 and aims at +v0, the
  // others touch at rest and aim at 0 (targets decided before the solve). The one answer with
  // j >= 0 everywhere: ball 1 at (2 - n)/n v0, the others together at 2 v0/n. Momentum and energy
  // are both conserved, (2 - n)^2 + 4 (n - 1) = n^2, yet only n = 2 is the real cradle's swap.
  const int n = static_cast<int>(uniform(3, 7));
  const double v0 = uniform(0.5, 3.0);
  const std::vector<double> v = cradleAfter(n, v0, ResponseMethod::Sequential);
  // Gauss-Seidel on a chain converges linearly; stopping at a 1e-9 m/s tolerance leaves a small
  // multiple of it: 1e-7 of v0.
  INFO(n << " balls, v0 " << v0);
  CHECK(v.front() == Approx((2.0 - n) / n * v0).margin(1e-7 * v0));
  for (int i = 1; i < n; ++i) CHECK(v[i] == Approx(2.0 * v0 / n).margin(1e-7 * v0));
  double P = 0.0, E = 0.0;
  for (double vi : v) {
    P += vi;
    E += 0.5 * vi * vi;
  }
  // Conserved up to the same margin (relative to v0 and 1/2 v0^2).
  CHECK(P == Approx(v0).epsilon(1e-6));
  CHECK(E == Approx(0.5 * v0 * v0).epsilon(1e-6));
  // Two balls: one contact, solved exactly in one sweep: the swap, up to round-off.
  const std::vector<double> two = cradleAfter(2, v0, ResponseMethod::Sequential);
  CHECK(std::abs(two[0]) <= 1e-12 * v0);
  CHECK(two[1] == Approx(v0).epsilon(1e-12));
}

TEST_CASE("Newton's cradle: simultaneous (Jacobi) impulses with enough sweeps reach the same velocities", "[lab05][pts=1][sec=2][sec=3][sec=4][sec=6]") {
  const int n = static_cast<int>(uniform(3, 7));
  const double v0 = uniform(0.5, 3.0);
  const std::vector<double> sequential = cradleAfter(n, v0, ResponseMethod::Sequential);
  const std::vector<double> simultaneous = cradleAfter(n, v0, ResponseMethod::Simultaneous);
  // The same fixed point, reached by both within small multiples of the 1e-9 m/s tolerance
  // (Jacobi with shares of 1/2 converges more slowly): 1e-6 of v0.
  INFO(n << " balls, v0 " << v0);
  for (int i = 0; i < n; ++i) CHECK(simultaneous[i] == Approx(sequential[i]).margin(1e-6 * v0));
  CHECK(simultaneous.front() == Approx((2.0 - n) / n * v0).margin(1e-6 * v0));
}

TEST_CASE("friction: a box sliding on the ground decelerates at mu g and stops after v0^2/(2 mu g)", "[lab05][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  const double v0 = uniform(1.0, 3.0), mu = uniform(0.2, 0.6), h = 1e-3;
  World world(slidingBox(v0, mu));
  const double t_stop = v0 / (mu * kG), d_stop = v0 * v0 / (2 * mu * kG);
  // Halfway in time the speed has halved
  run(world, h, std::lround(0.5 * t_stop / h));
  // The first step's contact and the sampling each cost up to mu g h of speed.
  CHECK(world.velocity(1).x() == Approx(0.5 * v0).margin(3 * mu * kG * h));
  run(world, h, std::lround(t_stop / h));
  // Stopped: friction sticks and holds it; what is left is below one step's friction impulse.
  // (The sudden stop may leave the box rocking on its edges a little: only sliding counts.)
  INFO("v = " << world.velocity(1).transpose() << ", omega = " << world.angularVelocity(1).transpose());
  CHECK(world.velocity(1).head<2>().norm() <= mu * kG * h);
  // Distance: speed errors of mu g h over the slide's time, plus one step at v0.
  CHECK(world.states()[1].x.x() == Approx(d_stop).margin(3 * v0 * h));
}

TEST_CASE("friction: a sphere thrown without spin rolls without slipping at 5/7 v0", "[lab05][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  const double v0 = uniform(1.0, 4.0), mu = uniform(0.1, 0.5), h = 1e-3, r = 0.1;
  World world(thrownSphere(v0, mu));
  // Sliding lasts 2 v0 / (7 mu g); run twice as long
  run(world, h, std::lround(4 * v0 / (7 * mu * kG) / h));
  const Vec3 v = world.velocity(1), omega = world.angularVelocity(1);
  // Friction changes the speed by at most mu g h per step: the last sliding step's overshoot.
  CHECK(v.x() == Approx(5.0 / 7.0 * v0).margin(2 * mu * kG * h));
  // Rolling: the contact point is at rest, v = omega r (sticking holds it to round-off).
  CHECK(std::abs(v.x() - omega.y() * r) <= 1e-9);
}

TEST_CASE("friction: with mu = 0 a sphere thrown without spin slides for ever", "[lab05][pts=1][sec=2][sec=3][sec=4][sec=5]") {
  const double v0 = uniform(1.0, 4.0), h = 1e-3;
  World world(thrownSphere(v0, 0.0));
  run(world, h, 2000);
  // No tangential impulse at all: the speed is kept to round-off and nothing spins.
  CHECK(world.velocity(1).x() == Approx(v0).epsilon(1e-12));
  CHECK(world.angularVelocity(1).norm() <= 1e-12);
  // The ground holds it: no more sinking than one step of gravity (g h^2).
  CHECK(world.diagnostics().max_penetration <= kG * h * h);
}

TEST_CASE("penalty: a resting sphere sinks to mg/k", "[lab05][pts=1][sec=7]") {
  const double m = uniform(0.5, 5.0), k = std::pow(10.0, uniform(3.0, 5.0)), h = 1e-4;
  Scene scene = bouncingBall(0.0, 0.5);
  scene.bodies[1] = BodyDescription::sphere(m, 0.1, 0.5, 0.0);
  Settings settings;
  settings.method = ResponseMethod::Penalty;
  settings.penalty_k = k;
  settings.penalty_d = std::sqrt(k * m);  // damping ratio 1/2
  World world(scene, settings);
  // Decays as exp(-omega t / 2), omega = sqrt(k / m) >= 10 /s: 4 s leave e^-20 of the start
  run(world, h, 40000);
  // At rest k depth + d g h = m g: the damper sees the step's gravity velocity g h, which
  // shifts the depth by d g h / k, omega h relative (omega = sqrt(k / m)).
  CHECK(world.diagnostics().max_penetration == Approx(m * kG / k).epsilon(2 * std::sqrt(k / m) * h));
}

namespace {

// Whether a sphere of mass m on penalty springs k (no damping), pressed 10% below its rest
// depth, leaves its rest height by more than 10 rest depths within 2000 steps of h. (A small
// push keeps it on the ground while the step is stable, so only the spring decides.)
bool penaltyUnstable(double m, double k, double h) {
  const double r = 0.1, rest = m * kG / k;
  Scene scene = bouncingBall(0.0, 0.5);
  scene.bodies[1] = BodyDescription::sphere(m, r, 0.5, 0.0);
  scene.states[1].x.z() = r - 1.1 * rest;
  Settings settings;
  settings.method = ResponseMethod::Penalty;
  settings.penalty_k = k;
  World world(scene, settings);
  for (int n = 0; n < 2000; ++n) {
    world.step(h);
    if (std::abs(world.states()[1].x.z() - (r - rest)) > 10 * rest) return true;
  }
  return false;
}

// The largest stable step, by bisection on log h between 0.1 / omega and 10 / omega.
double largestStableStep(double m, double k) {
  const double omega = std::sqrt(k / m);
  double lo = 0.1 / omega, hi = 10.0 / omega;
  REQUIRE_FALSE(penaltyUnstable(m, k, lo));
  REQUIRE(penaltyUnstable(m, k, hi));
  for (int i = 0; i < 30; ++i) {
    const double mid = std::sqrt(lo * hi);
    (penaltyUnstable(m, k, mid) ? hi : lo) = mid;
  }
  return lo;
}

}  // namespace

TEST_CASE("penalty: the largest stable step shrinks as sqrt(m/k)", "[lab05][pts=2][sec=7]") {
  const double m = uniform(0.5, 5.0), k = std::pow(10.0, uniform(3.0, 4.0));
  const double h1 = largestStableStep(m, k), h4 = largestStableStep(m, 4 * k);
  // In units of mg/k and 1/omega the scene is the same for every m and k, so the ratio is 2 up
  // to the bisection's resolution (30 halvings of a factor 100: ~1e-8) and round-off.
  CHECK(h1 / h4 == Approx(2.0).epsilon(1e-3));
  // Symplectic Euler on a spring is stable for h omega < 2, its orbit stretched by
  // 1 / sqrt(1 - (h omega / 2)^2), which reaches the test's factor 10 at h omega = 1.99.
  CHECK(h1 * std::sqrt(k / m) == Approx(2.0).epsilon(0.02));
}

TEST_CASE("box rain: sequential impulses keep every body in the container and add no energy", "[lab05][pts=1][sec=2][sec=3][sec=4][sec=5]") {
  // Without position correction: moving overlapping bodies apart lifts them, which is the
  // World's doing, not the impulses' (with it, 3 of 200 rains gained up to 1.2 times the bound)
  Settings settings;
  settings.position_correction = 0.0;
  const auto rain_seed = static_cast<std::uint64_t>(uniform(0, 1e9));
  INFO("a rain of 16 boxes (seed " << rain_seed << "), no position correction, 2000 steps of 1 ms");
  World world(boxRain(16, rain_seed), settings);
  const double h = 1e-3;
  world.step(h);
  double energy = world.diagnostics().kinetic_energy + world.diagnostics().potential_energy;
  const double start = energy;
  double largest_gain = 0.0;
  for (int n = 0; n < 2000; ++n) {
    world.step(h);
    const double now = world.diagnostics().kinetic_energy + world.diagnostics().potential_energy;
    largest_gain = std::max(largest_gain, now - energy);
    energy = now;
  }
  INFO("largest energy gain in a step " << largest_gain << " J");
  // Impulses with epsilon <= 1 and friction only remove energy; gravity integrated by symplectic
  // Euler adds at most m g^2 h^2 per body and step (16 bodies of 1 kg).
  CHECK(largest_gain <= 16 * kG * kG * h * h);
  CHECK(energy < start);
  for (std::size_t i = 5; i < world.states().size(); ++i) {
    const Vec3& x = world.states()[i].x;
    // Nothing leaves the container (walls at +-1 m) or sinks through the floor by more than 1 cm.
    CHECK(x.z() > 0.0);
    CHECK(x.head<2>().cwiseAbs().maxCoeff() < 1.0);
  }
}
