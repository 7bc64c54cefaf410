// Lab 5 scenes for the 3-D viewer (./physlab view 05): impulse-based Worlds, recorded frame by frame.
#include <string>

#include "physlab/replay.hpp"
#include "physlab/view.hpp"
#include "physlab/world.hpp"

using namespace physlab;

namespace {

// Runs `world` for `seconds` [s] at step h [s], a frame every `every` steps (none before the first
// step: a World's energies are its last step's).
Replay film(World world, const std::string& title, double h, double seconds, int every) {
  Replay replay = startReplay(world, title);
  const int steps = static_cast<int>(seconds / h + 0.5);
  for (int n = 1; n <= steps; ++n) {
    world.step(h);
    if (n % every == 0) recordFrame(world, replay);
  }
  return replay;
}

Replay rain() {
  return film(World(boxRain(40, 7)), "Lab 5: 40 boxes and spheres rain into a container (sequential impulses)", 0.005,
              5.0, 4);
}

Replay cradle() {
  Settings settings;
  settings.gravity = Vec3::Zero();
  return film(World(newtonsCradle(5, 1.0), settings), "Lab 5: Newton's cradle, 5 balls, epsilon = 1, no gravity",
              0.002, 2.0, 5);
}

Replay bouncing() {
  return film(World(bouncingBall(1.0, 0.8)), "Lab 5: a ball bouncing on the ground, epsilon = 0.8", 0.002, 4.0, 5);
}

// Three stacks of three 20 cm boxes and a ball on the ground, sleeping on: the stacks settle and
// fall asleep; at 3 s the ball is lifted above the middle stack (setState wakes the ball) and falls
// on it, which wakes that stack alone (Lab 5, section 12). The viewer draws a sleeping body in a
// pale shell.
Replay sleeping() {
  Scene scene;
  scene.bodies.push_back(BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.0, 0.5));
  scene.states.push_back(BodyState{});
  for (int p = 0; p < 3; ++p) {
    for (int level = 0; level < 3; ++level) {
      scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(0.1), 0.0, 0.5));
      BodyState s;
      s.x = Vec3(0.6 * (p - 1), 0.0, 0.1 + 0.2 * level);
      scene.states.push_back(s);
    }
  }
  scene.bodies.push_back(BodyDescription::sphere(1.0, 0.1, 0.3, 0.5));
  BodyState ball;
  ball.x = Vec3(0.0, 0.8, 0.1);
  scene.states.push_back(ball);
  Settings settings;
  settings.sleeping = true;
  World world(scene, settings);
  Replay replay = startReplay(world, "Lab 5: three stacks fall asleep; a ball dropped on the middle one wakes it alone");
  const double h = 1.0 / 100.0;
  const int ball_index = static_cast<int>(scene.bodies.size()) - 1;
  for (int n = 1; n <= 500; ++n) {
    if (n == 301) {
      world.setState(ball_index, BodyState::moving(world.bodies()[static_cast<std::size_t>(ball_index)], Vec3(0.0, 0.0, 1.2),
                                                   Quat::Identity(), Vec3::Zero(), Vec3::Zero()));
    }
    world.step(h);
    if (n % 4 == 0) recordFrame(world, replay);
  }
  return replay;
}

}  // namespace

int main(int argc, char** argv) {
  return runView(argc, argv,
                 {{"rain", "40 boxes and spheres rain into a container, sequential impulses", rain},
                  {"cradle", "Newton's cradle: 5 balls, the first at 1 m/s", cradle},
                  {"bouncing", "a ball bouncing on the ground, epsilon = 0.8", bouncing},
                  {"sleeping", "three stacks fall asleep; a ball dropped on the middle one wakes it alone", sleeping}});
}
