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

}  // namespace

int main(int argc, char** argv) {
  return runView(argc, argv,
                 {{"rain", "40 boxes and spheres rain into a container, sequential impulses", rain},
                  {"cradle", "Newton's cradle: 5 balls, the first at 1 m/s", cradle},
                  {"bouncing", "a ball bouncing on the ground, epsilon = 0.8", bouncing}});
}
