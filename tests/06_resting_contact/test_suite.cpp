// Lab 6 graded tests: the World with the default resting-contact solver (velocity-level LCP, PGS
// on the friction cone, bounces included) on every textbook scene of contact_suite.hpp, each
// against its physical truth and the tolerance the suite explains.
#include <memory>
#include <string>

#include "physlab/contact_suite.hpp"
#include "physlab/resting.hpp"
#include "support.hpp"

using namespace physlab;

namespace {

// Checks every measure of the scenes whose names start with one of `names`, run in Lab 6's
// World with `resting` (default: the header's defaults); returns how many scenes ran.
int checkScenes(std::initializer_list<const char*> names, const RestingSettings& resting = RestingSettings{}) {
  const auto scenes = contactSuite(names);
  for (const auto& scene : scenes) {
    WorldEngine world(World(scene->scene(), restingWorldSettings(), std::make_shared<LcpContactSolver>(resting)));
    for (const Measure& m : runSuiteScene(*scene, world)) {
      CAPTURE(scene->name(), m.name, m.value, m.expected, m.tolerance, m.why, world.world().describe());
      CHECK(m.pass());
    }
  }
  return static_cast<int>(scenes.size());
}

}  // namespace

TEST_CASE("textbook scenes, resting contact: boxes and balls rebound to e^2 at any speed, flat boxes without turning", "[lab06][pts=3][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  // The slow drops hit at 0.9 m/s: a bounce below the old 1 m/s resting threshold
  CHECK(checkScenes({"flat drop", "slow", "ball", "tilted drop"}) == 6);
}

TEST_CASE("textbook scenes, resting contact: a ramp holds below atan(mu), slides at g(sin - mu cos) above; a thrown ball rolls at 5/7 v0", "[lab06][pts=2][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  CHECK(checkScenes({"ramp", "thrown ball"}) == 3);
}

TEST_CASE("textbook scenes, resting contact: a 100:1 heavy box stays on a light one, overlap is pushed out without a jump, dominoes fall in order", "[lab06][pts=2][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  CHECK(checkScenes({"heavy on light", "overlap recovery", "dominoes"}) == 3);
}

TEST_CASE("textbook scenes, resting contact: a stack of 10 cubes stands still for 10 s", "[lab06][pts=2][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  // Three runs: as it is, then every cube shifted by up to 1 nm (a swaying stack goes anywhere
  // from there; one that stands goes nowhere in any of them)
  INFO("the suite's stack of 10 cubes, default RestingSettings (" << lcpMethodName(RestingSettings{}.method) << ", "
       << RestingSettings{}.lcp.max_iterations << " sweeps), 10 s at 60 Hz, 3 runs: expected sway <= 1 mm, sinking <= 1 cm");
  const std::vector<SpreadMeasure> spread = runSuiteSceneShaken("stack of 10 cubes", [](const Scene& scene) {
    return std::make_unique<WorldEngine>(
        World(scene, restingWorldSettings(), std::make_shared<LcpContactSolver>(RestingSettings{})));
  }, 3);
  REQUIRE(spread.size() == 2);
  const SpreadMeasure& sunk = spread[0];
  const SpreadMeasure& sway = spread[1];
  CAPTURE(sunk.median.value, sunk.largest, sway.median.value, sway.largest);
  // 1 cm in any run: the Baumgarte term leaves each of the 10 contacts up to its 1 mm slop deep
  // (0.02 mm measured)
  CHECK(sunk.largest <= 10 * RestingSettings{}.slop);
  CHECK(sunk.median.value >= 0.0);
  // The suite's 1 mm in every run (0.01 um measured): with the World's shock propagation each
  // level stands on the one below; without it, 100 PGS sweeps sway the top by 2 to 13 cm
  CHECK(sway.largest <= sway.median.tolerance);
}

TEST_CASE("textbook scenes, resting contact: the stack of 10 stands still without shock propagation once PGS converges", "[lab06][pts=1][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  // The exact solvers hold the stack to 1e-8 m without help; PGS needs its sweeps: at 300 the
  // top sways by 0.9 cm on the median of 2000 shifted runs, at 100 by 2.4 cm
  RestingSettings converged;
  converged.lcp.max_iterations = 300;
  Settings unpropagated = restingWorldSettings();
  unpropagated.shock_propagation = false;
  INFO("the suite's stack of 10 cubes, " << lcpMethodName(converged.method) << " at 300 sweeps, no shock propagation, "
       "10 s at 60 Hz, 3 runs: expected sway <= 5 cm, sinking <= 1 cm");
  const std::vector<SpreadMeasure> spread = runSuiteSceneShaken("stack of 10 cubes", [&](const Scene& scene) {
    return std::make_unique<WorldEngine>(World(scene, unpropagated, std::make_shared<LcpContactSolver>(converged)));
  }, 3);
  REQUIRE(spread.size() == 2);
  const SpreadMeasure& sunk = spread[0];
  const SpreadMeasure& sway = spread[1];
  CAPTURE(sunk.median.value, sunk.largest, sway.median.value, sway.largest);
  // 5 cm in any run: still standing, a quarter of an edge (a toppled stack moves by metres)
  CHECK(sway.largest <= 0.05);
  // 1 cm in any run: the Baumgarte term leaves each of the 10 contacts up to its 1 mm slop deep
  CHECK(sunk.largest <= 10 * RestingSettings{}.slop);
  CHECK(sunk.median.value >= 0.0);
}

TEST_CASE("textbook scenes, resting contact: 1000:1, a small cube on a large one and a wide plate on a small cube stay up; a 100 kg box stays on a 3-2-1 pyramid", "[lab06][pts=2][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  // Without shock propagation the heavy cube sinks through (0.2 m) and the plate by 14 cm
  CHECK(checkScenes({"cube on cube", "plate on cube", "heavy on pyramid"}) == 3);
}

TEST_CASE("textbook scenes, resting contact: 5 cm spheres at 10, 40 and 100 m/s never pass through a 20 cm box; cubes meeting face on part at e times the approach speed", "[lab06][pts=1][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  CHECK(checkScenes({"fast sphere", "face-on"}) == 4);
}
