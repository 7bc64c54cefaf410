// Lab 6 scenes for the 3-D viewer (./physlab view 06): Worlds with a resting-contact LCP solver.
#include <memory>
#include <string>
#include <utility>

#include "physlab/replay.hpp"
#include "physlab/resting.hpp"
#include "physlab/view.hpp"
#include "physlab/world.hpp"

using namespace physlab;

namespace {

// Runs `scene` with restingWorldSettings() and an LcpContactSolver of the default RestingSettings
// (velocity level, projected Gauss-Seidel on the friction cone) for `seconds` [s] at h = 0.01 s,
// a frame every `every` steps (none before the first step: a World's energies are its last
// step's). The pyramid's 320 contact points take 14 kB a frame, so it is filmed at 25 frames a
// second (3.6 MB for 10 s).
Replay film(Scene scene, const std::string& title, double seconds, int every) {
  World world(std::move(scene), restingWorldSettings(), std::make_shared<LcpContactSolver>(RestingSettings{}));
  Replay replay = startReplay(world, title);
  const double h = 0.01;
  const int steps = static_cast<int>(seconds / h + 0.5);
  for (int n = 1; n <= steps; ++n) {
    world.step(h);
    if (n % every == 0) recordFrame(world, replay);
  }
  return replay;
}

Replay pyramid() { return film(cubePyramid(10), "Lab 6: a pyramid of 55 cubes standing on the ground", 3.0, 4); }
Replay stack() { return film(cubeStack(6), "Lab 6: a stack of 6 cubes", 3.0, 2); }
Replay plank() { return film(plankOnTwoSupports(0.3, 0.6), "Lab 6: a plank on two supports (lever rule)", 2.0, 2); }

}  // namespace

int main(int argc, char** argv) {
  return runView(argc, argv,
                 {{"pyramid", "a pyramid of 55 cubes (10 rows) standing on the ground, velocity-level PGS", pyramid},
                  {"stack", "a stack of 6 cubes on the ground", stack},
                  {"plank", "a plank on two supports at 0.3 m and 0.6 m: the lever rule", plank}});
}
