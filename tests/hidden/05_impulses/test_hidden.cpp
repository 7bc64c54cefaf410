// Lab 5 hidden tests (instructor only, shown after grades are published).
#include <cmath>

#include "physlab/timewarp.hpp"
#include "physlab/world.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// A random moving body touching a fixed one at p; the fixed one is A or B as asked.
struct FixedPair {
  ContactBody moving, fixed;
  double m = 1.0;
  Vec3 p, n;
};

FixedPair randomFixedPair() {
  FixedPair s;
  s.m = uniform(0.2, 5.0);
  const Mat3 R = randomRotation();
  const Mat3 I = R * Vec3(uniform(0.2, 2.0), uniform(0.2, 2.0), uniform(0.2, 2.0)).asDiagonal() * R.transpose();
  s.moving.x = randomVec3(1.0);
  s.moving.v = randomVec3(2.0);
  s.moving.omega = randomVec3(2.0);
  s.moving.inv_mass = 1.0 / s.m;
  s.moving.I_inv_world = I.inverse();
  s.fixed.x = randomVec3(1.0);
  s.p = randomVec3(1.0);
  s.n = randomVec3(1.0).normalized();
  return s;
}

// Mean solver sweeps per step of a box resting on the ground, after it has settled.
double meanSweeps(bool warm_start) {
  Settings settings;
  settings.method = ResponseMethod::Simultaneous;
  settings.warm_start = warm_start;
  settings.tolerance = 1e-6;
  World world(slidingBox(0.0, 0.5), settings);
  for (int n = 0; n < 200; ++n) world.step(1e-3);
  double sweeps = 0.0;
  for (int n = 0; n < 100; ++n) {
    world.step(1e-3);
    sweeps += world.diagnostics().iterations;
  }
  return sweeps / 100;
}

}  // namespace

TEST_CASE("hidden: a fixed body as A leaves the moving B bouncing with -epsilon v_n", "[lab05][pts=1][hidden][sec=2][sec=3]") {
  FixedPair s = randomFixedPair();
  // With the fixed body as A the normal points into the moving body: it approaches when
  // n . (0 - pdot_B) < 0
  const Vec3 pdot = s.moving.v + s.moving.omega.cross(s.p - s.moving.x);
  if (s.n.dot(pdot) < 0) s.n = -s.n;
  const double epsilon = uniform(0.0, 1.0), before = -s.n.dot(pdot);
  applyImpulse(s.fixed, s.moving, s.p, impulseMagnitude(s.fixed, s.moving, s.p, s.n, epsilon) * s.n);
  // Zero inverses: the fixed body does not move at all (exactly).
  CHECK(s.fixed.v == Vec3::Zero());
  CHECK(s.fixed.omega == Vec3::Zero());
  const double after = -s.n.dot(s.moving.v + s.moving.omega.cross(s.p - s.moving.x));
  // v_rel is linear in j: round-off relative to the speeds involved.
  CHECK(after == Approx(-epsilon * before).margin(1e-10 * (1.0 + std::abs(before))));
}

TEST_CASE("hidden: warm starting cuts the simultaneous solver's sweeps on a resting box", "[lab05][pts=1][hidden][sec=6]") {
  const double cold = meanSweeps(false), warm = meanSweeps(true);
  INFO("sweeps per step: cold " << cold << ", warm " << warm);
  // Last step's impulses are nearly this step's: far fewer sweeps (a factor, not a few percent).
  CHECK(warm < 0.5 * cold);
}

TEST_CASE("hidden: the simultaneous solver bounces a ball by epsilon^2 too", "[lab05][pts=1][hidden][sec=2][sec=3][sec=4][sec=6]") {
  const double epsilon = uniform(0.6, 0.9), H = uniform(0.5, 1.5), h = 1e-4, r = 0.1;
  Settings settings;
  settings.method = ResponseMethod::Simultaneous;
  World world(bouncingBall(H, epsilon), settings);
  double previous_vz = 0.0, apex = -1.0;
  for (long n = 0; n < 100000 && apex < 0; ++n) {
    world.step(h);
    const double vz = world.velocity(1).z();
    if (previous_vz > 0.0 && vz <= 0.0) apex = world.states()[1].x.z() - r;
    previous_vz = vz;
  }
  // The impact is seen up to one step late, at up to v h below the ground, and the apex is
  // sampled once per step: a few v h of error, v = sqrt(2 g H).
  CHECK(apex / H == Approx(epsilon * epsilon).margin(4 * std::sqrt(2 * 9.81 * H) * h / apex));
}

TEST_CASE("hidden: timewarp under gravity keeps the row's event times, and restitution 1/2 leaves the speeds by hand", "[lab05][pts=1][hidden][sec=9]") {
  // Gravity accelerates every sphere alike, so relative motion and the impact times do not change:
  // the ball hits sphere k + 1 at (0.8 + k gap) / v0 as without it
  const double gap = uniform(0.1, 0.5), v0 = uniform(2.0, 6.0);
  std::vector<TimewarpSphere> spheres;
  std::vector<SphereState> states;
  fastBallThroughRow(4, gap, v0, 0, 3u, spheres, states);
  TimewarpSettings settings;
  settings.gravity = Vec3(0.0, 0.0, -9.81);
  settings.max_step = 0.5;
  TimewarpWorld world(spheres, states, settings);
  world.run(2.0);
  REQUIRE(world.events().size() == 4);
  for (int k = 0; k < 4; ++k) {
    // Closed-form roots from states carried through free flights: round-off only
    CHECK(world.events()[k].t == Approx((0.8 + k * gap) / v0).epsilon(1e-11));
  }
  // By hand: 1 kg at 2 m/s into 3 kg at rest, epsilon 1/2: j = 1.5 * 2 / (1 + 1/3) = 2.25 N s,
  // so 2 - 2.25 = -0.25 m/s and 2.25 / 3 = 0.75 m/s (relative speed -1 = -epsilon 2)
  std::vector<SphereState> pair(2);
  pair[0].v = Vec3(2.0, 0.0, 0.0);
  pair[1].x = Vec3(1.0, 0.0, 0.0);
  TimewarpWorld bounce({TimewarpSphere{1.0, 0.1, 0.5}, TimewarpSphere{3.0, 0.1, 1.0}}, pair);
  bounce.run(1.0);
  REQUIRE(bounce.events().size() == 1);
  CHECK(bounce.events()[0].t == Approx(0.4).epsilon(1e-14));  // 0.8 m at 2 m/s: round-off only
  CHECK(bounce.events()[0].j == Approx(2.25).epsilon(1e-14));
  CHECK(bounce.state(0).v.isApprox(Vec3(-0.25, 0.0, 0.0), 1e-14));
  CHECK(bounce.state(1).v.isApprox(Vec3(0.75, 0.0, 0.0), 1e-14));
}
