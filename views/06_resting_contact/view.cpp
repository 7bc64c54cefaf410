// Lab 6 scenes for the 3-D viewer (./physlab view 06): Worlds with a resting-contact LCP solver.
#include <memory>
#include <string>
#include <utility>

#include "physlab/replay.hpp"
#include "physlab/resting.hpp"
#include "physlab/soft_step.hpp"
#include "physlab/view.hpp"
#include "physlab/world.hpp"

using namespace physlab;

namespace {

// Runs `scene` with restingWorldSettings() and an LcpContactSolver of `settings` for `seconds` [s]
// at step h [s], a frame every `every` steps (none before the first step: a World's energies are
// its last step's), with the contacts on every `contacts_every`-th frame. The 55-cube pyramid's
// 320 contact points take 14 kB a frame, so it is filmed at 25 frames a second (3.6 MB for 10 s).
Replay film(Scene scene, const std::string& title, double seconds, int every, double h,
            std::shared_ptr<RestingContactSolver> solver, int contacts_every = 1) {
  World world(std::move(scene), restingWorldSettings(), std::move(solver));
  Replay replay = startReplay(world, title);
  const int steps = static_cast<int>(seconds / h + 0.5);
  for (int n = 1; n <= steps; ++n) {
    world.step(h);
    if (n % every == 0) recordFrame(world, replay, (n / every) % contacts_every == 0);
  }
  return replay;
}

// The same with an LcpContactSolver of `settings`.
Replay film(Scene scene, const std::string& title, double seconds, int every, double h = 0.01,
            const RestingSettings& settings = RestingSettings{}, int contacts_every = 1) {
  return film(std::move(scene), title, seconds, every, h, std::make_shared<LcpContactSolver>(settings), contacts_every);
}

// The benchmark's large pyramid (bench/06_resting_contact): 465 cubes in 30 rows for 10 s at
// h = 1/60 s, matrix-free cone PGS with 100 sweeps (it stands; 20 sweeps let it settle by more
// than 5 cm). Its 3,500 contact points would take 140 kB a frame, so the poses are filmed at
// 20 frames a second (13 kB each) and the contacts on one frame in 20 (once a second): 4.0 MB.
Replay pyramid465() {
  RestingSettings settings;
  settings.matrix_free = true;
  settings.lcp.max_iterations = 100;
  return film(cubePyramid(30), "Lab 6: a pyramid of 465 cubes standing for 10 s", 10.0, 3, 1.0 / 60.0, settings, 20);
}

Replay pyramid() { return film(cubePyramid(10), "Lab 6: a pyramid of 55 cubes standing on the ground", 3.0, 4); }
Replay stack() { return film(cubeStack(6), "Lab 6: a stack of 6 cubes", 3.0, 2); }
// The soft step (section 9) with its defaults on the tests' 10-cube stack at h = 1/60 s: it stands,
// its top sinking about 12 mm on the contact springs, where PGS with the same 8 sweeps falls.
Replay softStack() {
  return film(cubeStack(10), "Lab 6: the soft step holds a stack of 10 cubes (4 substeps, 60 Hz)", 4.0, 2, 1.0 / 60.0,
              std::make_shared<SoftStepSolver>(SoftStepSettings{}));
}
Replay plank() { return film(plankOnTwoSupports(0.3, 0.6), "Lab 6: a plank on two supports (lever rule)", 2.0, 2); }

}  // namespace

int main(int argc, char** argv) {
  return runView(argc, argv,
                 {{"pyramid", "a pyramid of 55 cubes (10 rows) standing on the ground, velocity-level PGS", pyramid},
                  {"pyramid465", "a pyramid of 465 cubes (30 rows) for 10 s, matrix-free PGS with 100 sweeps; contacts once a second", pyramid465},
                  {"stack", "a stack of 6 cubes on the ground", stack},
                  {"soft_stack", "a stack of 10 cubes held by the soft step (4 substeps of soft and relax sweeps, 60 Hz)", softStack},
                  {"plank", "a plank on two supports at 0.3 m and 0.6 m: the lever rule", plank}});
}
