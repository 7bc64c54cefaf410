// Framework tests for Lab 5: bad bodies, states, settings and steps are refused with a message
// naming them. They grade nothing (the checks live in common/), so they carry [common].
#include <cmath>
#include <sstream>

#include "physlab/error.hpp"
#include "physlab/world.hpp"
#include "support.hpp"

using namespace physlab;
using Catch::Matchers::Contains;

namespace {

Scene oneBall(const BodyDescription& ball) {
  Scene scene = bouncingBall(1.0, 0.5);
  scene.bodies[1] = ball;
  return scene;
}

}  // namespace

TEST_CASE("world validation: epsilon outside [0, 1] is refused", "[common]") {
  CHECK_THROWS_WITH(World(oneBall(BodyDescription::sphere(1.0, 0.1, 1.5, 0.0))), Contains("body 1 restitution epsilon"));
  CHECK_THROWS_WITH(World(oneBall(BodyDescription::sphere(1.0, 0.1, -0.1, 0.0))), Contains("body 1 restitution epsilon"));
  CHECK_THROWS_AS(World(oneBall(BodyDescription::sphere(1.0, 0.1, std::nan(""), 0.0))), InvalidInput);
  CHECK_NOTHROW(World(oneBall(BodyDescription::sphere(1.0, 0.1, 1.0, 0.0))));
}

TEST_CASE("world validation: negative friction is refused", "[common]") {
  CHECK_THROWS_WITH(World(oneBall(BodyDescription::sphere(1.0, 0.1, 0.5, -0.2))), Contains("body 1 friction mu"));
}

TEST_CASE("world validation: zero or negative mass on a moving body is refused", "[common]") {
  BodyDescription ball = BodyDescription::sphere(1.0, 0.1, 0.5, 0.0);
  ball.mass = 0.0;
  CHECK_THROWS_WITH(World(oneBall(ball)), Contains("body 1 mass"));
  ball.mass = -2.0;
  CHECK_THROWS_WITH(World(oneBall(ball)), Contains("body 1 mass"));
  ball.fixed = true;  // a fixed body's mass is never used
  CHECK_NOTHROW(World(oneBall(ball)));
  BodyDescription ground = BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.5, 0.0);
  ground.fixed = false;
  Scene scene = bouncingBall(1.0, 0.5);
  scene.bodies[0] = ground;
  CHECK_THROWS_WITH(World(scene), Contains("body 0 is a plane and must be fixed"));
}

TEST_CASE("world validation: a NaN in a state is refused", "[common]") {
  Scene scene = bouncingBall(1.0, 0.5);
  scene.states[1].P.y() = std::nan("");
  CHECK_THROWS_WITH(World(scene), Contains("body 1 state linear momentum P"));
  World world(bouncingBall(1.0, 0.5));
  BodyState bad = world.states()[1];
  bad.x.z() = std::nan("");
  CHECK_THROWS_WITH(world.setState(1, bad), Contains("body 1 state position x"));
  bad = world.states()[1];
  bad.q = Quat(0, 0, 0, 0);
  CHECK_THROWS_WITH(world.setState(1, bad), Contains("quaternion is zero"));
}

TEST_CASE("world validation: bad settings, a bad step and mismatched sizes are refused", "[common]") {
  Settings settings;
  settings.iterations = 0;
  CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), settings), Contains("iterations"));
  settings = Settings{};
  settings.penalty_k = 0.0;
  CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), settings), Contains("penalty stiffness k"));
  settings = Settings{};
  settings.position_correction = 1.5;
  CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), settings), Contains("position correction"));
  settings.position_correction = std::nan("");
  CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), settings), Contains("position correction"));
  settings = Settings{};
  settings.slop = -0.001;
  CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), settings), Contains("slop"));
  settings = Settings{};
  settings.correction_sweeps = 0;
  CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), settings), Contains("correction sweeps must be at least 1, got 0"));
  settings = Settings{};
  settings.shock_response_iterations = 0;
  CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), settings), Contains("shock_response_iterations must be at least 1"));
  // 1 is the least allowed
  settings.shock_response_iterations = 1;
  CHECK_NOTHROW(World(bouncingBall(1.0, 0.5), settings));
  World world(bouncingBall(1.0, 0.5));
  CHECK_THROWS_WITH(world.step(0.0), Contains("step size h"));
  CHECK_THROWS_AS(world.step(std::nan("")), InvalidInput);
  Scene scene = bouncingBall(1.0, 0.5);
  scene.states.pop_back();
  CHECK_THROWS_WITH(World(scene), Contains("world states has size 1, expected 2"));
}

TEST_CASE("world settings: printed with every value", "[common]") {
  Settings settings;
  settings.method = ResponseMethod::Simultaneous;
  settings.iterations = 17;
  std::ostringstream out;
  out << settings;
  CHECK_THAT(out.str(), Contains("method=simultaneous") && Contains("iterations=17") && Contains("warm_start=on") &&
                            Contains("position_correction=0.2") && Contains("slop=0.0002") &&
                            Contains("correction_sweeps=8") && Contains("shock_response_iterations=20"));
  CHECK(out.str() == settings.toString());
  // The response's limit is printed only where it acts
  settings.shock_propagation = false;
  CHECK_THAT(settings.toString(), !Contains("shock_response_iterations"));
}

TEST_CASE("world: a scene without gravity or contacts skips those phases", "[common]") {
  Scene scene;
  scene.bodies = {BodyDescription::sphere(1.0, 0.1, 0.5, 0.0), BodyDescription::sphere(2.0, 0.1, 0.5, 0.0)};
  scene.states.resize(2);
  scene.states[1].x = Vec3(1.0, 0.0, 0.0);
  scene.states[0].P = Vec3(0.0, 1.0, 0.0);  // moving parallel to the other: never touching
  Settings settings;
  settings.gravity = Vec3::Zero();
  World world(scene, settings);
  for (int n = 0; n < 100; ++n) world.step(1e-3);
  // Skipped phases never start their timer: exactly zero.
  CHECK(world.times().forces == 0.0);
  CHECK(world.times().narrow_phase == 0.0);
  CHECK(world.times().respond == 0.0);
  CHECK(world.diagnostics().contacts == 0);
  CHECK(world.time() == Approx(0.1).epsilon(1e-12));  // 100 sums of 1e-3: round-off
}

TEST_CASE("world diagnostics: a falling ball keeps its energy and gains momentum m g t", "[common]") {
  Settings settings;
  World world(bouncingBall(10.0, 0.5), settings);
  world.step(1e-3);
  const double E0 = world.diagnostics().kinetic_energy + world.diagnostics().potential_energy;
  for (int n = 1; n < 1000; ++n) world.step(1e-3);
  const Diagnostics& d = world.diagnostics();
  // Symplectic Euler under constant gravity: the energy error stays at m g |v| h / 2 ~ 0.05 J.
  CHECK(d.kinetic_energy + d.potential_energy == Approx(E0).margin(0.1));
  // Gravity's impulse over 1 s (1000 steps of 1e-3): exact up to round-off of the sum.
  CHECK(d.linear_momentum.z() == Approx(-9.81).epsilon(1e-12));
  CHECK(d.angular_momentum.norm() <= 1e-12);  // falling straight through the origin's vertical
  CHECK(d.contacts == 0);
  CHECK(d.max_penetration == 0.0);
}

TEST_CASE("world position correction: an overlap beyond the slop shrinks by the set fraction per step", "[common]") {
  // A ball sunk 5 cm into the ground, at rest and without gravity: no impulse, only the correction.
  Scene scene = bouncingBall(0.0, 0.5);
  scene.states[1].x.z() -= 0.05;
  Settings settings;
  settings.gravity = Vec3::Zero();
  World world(scene, settings);
  world.step(0.01);
  // 0.2 of the 4.9 cm beyond the 1 mm slop, all of it on the ball (the ground is fixed), after
  // the step's integration (at rest: nothing moves it before the correction): one rounding.
  CHECK(world.states()[1].x.z() == Approx(0.1 - 0.05 + 0.2 * (0.05 - settings.slop)).epsilon(1e-14));
  for (int step = 0; step < 200; ++step) world.step(0.01);
  // Geometric approach to the slop: 0.8^200 of the excess is left.
  CHECK(world.states()[1].x.z() == Approx(0.1 - settings.slop).epsilon(1e-12));
  settings.method = ResponseMethod::Penalty;
  settings.penalty_k = 1e-9;
  World penalty(scene, settings);
  penalty.step(0.01);
  // Penalty springs push for themselves; a spring this soft barely moves the ball in one step.
  CHECK(penalty.states()[1].x.z() < 0.1 - 0.05 + 1e-9);
}

namespace {

// Box half extents (0.2, 0.2, 0.1), 1 kg, at rest, no gravity: only the position correction moves it
BodyDescription slab() { return BodyDescription::box(1.0, Vec3(0.2, 0.2, 0.1), 0.0, 0.5); }

}  // namespace

TEST_CASE("world position correction: a box sunk at one edge is turned level, and gains no velocity", "[common]") {
  Scene scene = bouncingBall(0.0, 0.5);
  scene.bodies[1] = slab();
  // Tilted by 0.1 rad about y: its low edge 0.2 sin 0.1 = 2 cm below its high edge; 1 cm deep there
  const double tilt = 0.1;
  scene.states[1].q = Quat(Eigen::AngleAxisd(tilt, Vec3::UnitY()));
  scene.states[1].x = Vec3(0.0, 0.0, 0.1 * std::cos(tilt) + 0.2 * std::sin(tilt) - 0.01);
  Settings settings;
  settings.gravity = Vec3::Zero();
  World world(scene, settings);
  for (int step = 0; step < 100; ++step) world.step(0.01);
  const Eigen::AngleAxisd left(world.states()[1].q);
  CAPTURE(left.angle(), world.depth(1, 0));
  // Pushes at the sunk edge turn the box towards level as they lift it (0.068 rad left); a lift
  // of the pair as a whole would keep the 0.1 rad
  CHECK(left.angle() < 0.9 * tilt);
  // 0.8^100 of the overlap beyond the slop is left
  CHECK(world.depth(1, 0) <= settings.slop + 1e-9);
  // Positions and orientations only: momentum and angular momentum stay exactly 0
  CHECK(world.states()[1].P.isZero(0.0));
  CHECK(world.states()[1].L.isZero(0.0));
}

TEST_CASE("world position correction: a box wedged between the ground and a box above comes out of both at once", "[common]") {
  Scene scene = bouncingBall(0.0, 0.5);
  scene.bodies[1] = slab();
  scene.states[1].x = Vec3(0.0, 0.0, 0.1 - 0.03);  // 3 cm into the ground
  scene.bodies.push_back(slab());
  BodyState above;
  above.x = Vec3(0.0, 0.0, 0.3 - 0.06);  // 3 cm into the box below
  scene.states.push_back(above);
  // Each pair moved apart on its own (the World's correction before 2026-11-26), all of the
  // overlap in one step: the lower box goes up by its ground pair's push and down by half the
  // upper pair's, so the upper overlap stays 3 cm and the ground's 1.5 cm. Gauss-Seidel sees the
  // lower box leave the ground while it pushes the upper one away.
  for (const int sweeps : {8, 32}) {
    Settings settings;
    settings.gravity = Vec3::Zero();
    settings.position_correction = 1.0;  // all of the overlap beyond the slop, in one step
    settings.correction_sweeps = sweeps;
    World world(scene, settings);
    world.step(0.01);
    world.step(0.01);  // the second step's contacts show what the first step's correction left
    CAPTURE(sweeps, world.depth(1, 0), world.depth(2, 1));
    if (sweeps == 8) {
      // The default's 8 sweeps (4 corners a face): 6.5 and 6.8 mm left of 3 cm
      CHECK(world.depth(1, 0) < 0.01);
      CHECK(world.depth(2, 1) < 0.01);
    } else {
      // Converged: both at the slop
      CHECK(world.depth(1, 0) == Approx(settings.slop).margin(1e-4));
      CHECK(world.depth(2, 1) == Approx(settings.slop).margin(1e-4));
    }
    CHECK(world.states()[1].P.isZero(0.0));
    CHECK(world.states()[2].P.isZero(0.0));
  }
}
