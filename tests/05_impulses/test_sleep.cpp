// Lab 5 graded tests of sleeping (section 12): sleepTimer() against hand computations at every
// end of its contract and against the rule on seeded velocities, its bad input refused by name,
// and the World it serves: a body still for exactly sleep_time falls asleep on that step, and of
// three settled piles a ball dropped on one wakes that pile alone.
#include <cmath>
#include <limits>
#include <vector>

#include "physlab/error.hpp"
#include "physlab/world.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

namespace {

const double kNoLimit = std::numeric_limits<double>::infinity();
// A step whose multiples are exact in binary: four of them are exactly 0.5 s
const double kEighth = 0.125;

// The rule, written apart: still at or below both thresholds
double sleepTimerOracle(const Vec3& v, const Vec3& omega, double timer, double h, double linear, double angular) {
  return v.norm() <= linear && omega.norm() <= angular ? timer + h : 0.0;
}

// A ground plane, `piles` stacks of three 20 cm boxes 1 m apart along x (bodies 1 + 3 p .. 3 + 3 p),
// and a 10 cm ball resting on the ground 3 m away from them (the last body).
Scene sleepingPiles(int piles) {
  Scene scene;
  scene.bodies.push_back(BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.0, 0.5));
  scene.states.push_back(BodyState{});
  for (int p = 0; p < piles; ++p) {
    for (int level = 0; level < 3; ++level) {
      scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(0.1), 0.0, 0.5));
      BodyState s;
      s.x = Vec3(1.0 * p, 0.0, 0.1 + 0.2 * level);
      scene.states.push_back(s);
    }
  }
  scene.bodies.push_back(BodyDescription::sphere(1.0, 0.1, 0.0, 0.5));
  BodyState ball;
  ball.x = Vec3(-3.0, 0.0, 0.1);
  scene.states.push_back(ball);
  return scene;
}

}  // namespace

TEST_CASE("sleep timer: hand cases at every end of the contract", "[lab05][pts=2][sec=12]") {
  const Vec3 zero = Vec3::Zero();
  // At rest: the timer grows by exactly the step, from 0 or from where it was
  CHECK(sleepTimer(zero, zero, 0.0, kEighth, 0.05, 0.05) == kEighth);
  CHECK(sleepTimer(zero, zero, 0.375, kEighth, 0.05, 0.05) == 0.5);
  // Exactly at a threshold is still (both ends included), along any axis
  CHECK(sleepTimer(Vec3(0.05, 0.0, 0.0), zero, 0.25, kEighth, 0.05, 0.05) == 0.375);
  CHECK(sleepTimer(Vec3(0.0, 0.0, -0.05), Vec3(0.0, 0.05, 0.0), 0.25, kEighth, 0.05, 0.05) == 0.375);
  // Just above either threshold: the timer starts again at exactly 0
  const double above = std::nextafter(0.05, 1.0);
  CHECK(sleepTimer(Vec3(above, 0.0, 0.0), zero, 0.25, kEighth, 0.05, 0.05) == 0.0);
  CHECK(sleepTimer(zero, Vec3(0.0, 0.0, above), 0.25, kEighth, 0.05, 0.05) == 0.0);
  // The speed is the length of v, not a component: (0.04, 0.04, 0) is 0.057 m/s, above 0.05
  CHECK(sleepTimer(Vec3(0.04, 0.04, 0.0), zero, 0.25, kEighth, 0.05, 0.05) == 0.0);
  CHECK(sleepTimer(zero, Vec3(-0.04, 0.0, 0.04), 0.25, kEighth, 0.05, 0.05) == 0.0);
  // Each threshold gates its own speed: a fast spin with a slow centre, and the other way round
  CHECK(sleepTimer(zero, Vec3(0.0, 0.0, 1.0), 0.25, kEighth, 2.0, 0.05) == 0.0);
  CHECK(sleepTimer(Vec3(1.0, 0.0, 0.0), zero, 0.25, kEighth, 0.05, 2.0) == 0.0);
  // Zero thresholds: only a body exactly at rest is still
  CHECK(sleepTimer(zero, zero, 0.25, kEighth, 0.0, 0.0) == 0.375);
  CHECK(sleepTimer(Vec3(1e-100, 0.0, 0.0), zero, 0.25, kEighth, 0.0, 0.0) == 0.0);
  // A long rest keeps counting
  CHECK(sleepTimer(zero, zero, 1e6, 1.0, 0.05, 0.05) == 1e6 + 1.0);
}

TEST_CASE("sleep timer: seeded velocities about the thresholds against the rule", "[lab05][pts=1][sec=12]") {
  // A fixed case beside the random ones: 0.03 m/s and 0.06 rad/s, above the angular threshold
  CHECK(sleepTimer(Vec3(0.03, 0.0, 0.0), Vec3(0.0, 0.06, 0.0), 0.25, kEighth, 0.05, 0.05) == 0.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const double linear = uniform(0.0, 1.0) < 0.1 ? 0.0 : uniform(1e-3, 0.2);
    const double angular = uniform(0.0, 1.0) < 0.1 ? 0.0 : uniform(1e-3, 0.2);
    // Speeds from 0 to twice each threshold, so that about half the bodies are still
    const Vec3 v = randomVec3(1.0).normalized() * uniform(0.0, 2.0 * linear);
    const Vec3 omega = randomVec3(1.0).normalized() * uniform(0.0, 2.0 * angular);
    const double timer = uniform(0.0, 1.0) < 0.2 ? 0.0 : uniform(0.0, 2.0);
    const double h = uniform(1e-4, 0.1);
    CAPTURE(trial, v.transpose(), omega.transpose(), timer, h, linear, angular);
    // The same operations as the rule: the same double, bit for bit
    CHECK(sleepTimer(v, omega, timer, h, linear, angular) == sleepTimerOracle(v, omega, timer, h, linear, angular));
  }
}

TEST_CASE("sleep timer: bad velocities, timer, step or threshold are refused by name", "[lab05][pts=1][sec=12]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vec3 zero = Vec3::Zero();
  for (const double bad : {nan, kNoLimit, -kNoLimit}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(sleepTimer(Vec3(0.0, bad, 0.0), zero, 0.0, kEighth, 0.05, 0.05), InvalidInput);
    CHECK_THROWS_WITH(sleepTimer(Vec3(0.0, bad, 0.0), zero, 0.0, kEighth, 0.05, 0.05), Contains("velocity v"));
    CHECK_THROWS_WITH(sleepTimer(zero, Vec3(bad, 0.0, 0.0), 0.0, kEighth, 0.05, 0.05), Contains("angular velocity omega"));
  }
  for (const double timer : {-1e-300, kNoLimit, nan}) {
    CAPTURE(timer);
    CHECK_THROWS_AS(sleepTimer(zero, zero, timer, kEighth, 0.05, 0.05), InvalidInput);
    CHECK_THROWS_WITH(sleepTimer(zero, zero, timer, kEighth, 0.05, 0.05), Contains("timer"));
  }
  for (const double h : {0.0, -kEighth, kNoLimit, nan}) {
    CAPTURE(h);
    CHECK_THROWS_AS(sleepTimer(zero, zero, 0.0, h, 0.05, 0.05), InvalidInput);
    CHECK_THROWS_WITH(sleepTimer(zero, zero, 0.0, h, 0.05, 0.05), Contains("step h"));
  }
  for (const double threshold : {-1e-300, kNoLimit, nan}) {
    CAPTURE(threshold);
    CHECK_THROWS_AS(sleepTimer(zero, zero, 0.0, kEighth, threshold, 0.05), InvalidInput);
    CHECK_THROWS_WITH(sleepTimer(zero, zero, 0.0, kEighth, threshold, 0.05), Contains("linear threshold"));
    CHECK_THROWS_AS(sleepTimer(zero, zero, 0.0, kEighth, 0.05, threshold), InvalidInput);
    CHECK_THROWS_WITH(sleepTimer(zero, zero, 0.0, kEighth, 0.05, threshold), Contains("angular threshold"));
  }
}

TEST_CASE("sleeping: a body still for exactly sleep_time falls asleep on that step, one just faster never", "[lab05][pts=1][sec=2][sec=3][sec=4][sec=5][sec=12]") {
  // No gravity, nothing to touch: a ball drifting at exactly the threshold is still
  Settings settings;
  settings.gravity = Vec3::Zero();
  settings.sleeping = true;
  for (const double speed : {0.0, 0.05, std::nextafter(0.05, 1.0)}) {
    CAPTURE(speed);
    Scene scene;
    scene.bodies.push_back(BodyDescription::sphere(1.0, 0.1, 0.5, 0.0));
    BodyState s;
    s.P = Vec3(speed, 0.0, 0.0);
    scene.states.push_back(s);
    World world(scene, settings);
    // Still after 1, 2, 3 steps of 1/8 s: 0.375 s < 0.5 s, awake
    for (int n = 0; n < 3; ++n) world.step(kEighth);
    CHECK_FALSE(world.asleep(0));
    world.step(kEighth);
    if (speed <= 0.05) {
      // Four steps are 0.5 s exactly: asleep, stopped, and it stays where it fell asleep
      CHECK(world.asleep(0));
      CHECK(world.diagnostics().asleep == 1);
      CHECK(world.velocity(0) == Vec3::Zero());
      const Vec3 x = world.states()[0].x;
      for (int n = 0; n < 10; ++n) world.step(kEighth);
      CHECK(world.states()[0].x == x);
      // setState() wakes it
      world.setState(0, world.states()[0]);
      CHECK_FALSE(world.asleep(0));
    } else {
      for (int n = 0; n < 10; ++n) world.step(kEighth);
      CHECK_FALSE(world.asleep(0));
    }
  }
}

TEST_CASE("sleeping: three settled piles fall asleep, and a ball dropped on one wakes that pile alone", "[lab05][pts=2][sec=2][sec=3][sec=4][sec=5][sec=12]") {
  Settings settings;
  settings.sleeping = true;
  World world(sleepingPiles(3), settings);
  const double h = 1.0 / 60.0;
  const int ball = 10;
  // Three seconds: stacked boxes start touching, settle within a few steps, then 0.5 s still
  for (int n = 0; n < 180; ++n) world.step(h);
  for (int i = 1; i <= ball; ++i) CHECK(world.asleep(i));
  CHECK(world.diagnostics().asleep == 10);
  CHECK(world.diagnostics().contacts == 0);
  const std::vector<BodyState> settled = world.states();
  // The ball, dropped 0.5 m above the middle pile's top, wakes (setState) and falls on it
  world.setState(ball, BodyState::moving(world.bodies()[ball], Vec3(1.0, 0.0, 1.2), Quat::Identity(),
                                          Vec3::Zero(), Vec3::Zero()));
  bool middle_woke = false;
  for (int n = 0; n < 120; ++n) {
    world.step(h);
    for (int i = 4; i <= 6; ++i) middle_woke = middle_woke || !world.asleep(i);
    // The other piles sleep on, exactly where they were
    for (const int i : {1, 2, 3, 7, 8, 9}) {
      CAPTURE(n, i);
      REQUIRE(world.asleep(i));
      REQUIRE(world.states()[i].x == settled[i].x);
    }
  }
  CHECK(middle_woke);
  // The middle pile still stands under the ball: its top box within 1 cm of where it was (a
  // 1 kg ball landing at 3 m/s on 20 cm boxes presses them by millimetres, tips none)
  CHECK((world.states()[6].x - settled[6].x).norm() < 0.01);
  CHECK(world.states()[ball].x.z() > 0.6);
}
