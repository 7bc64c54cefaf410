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

TEST_CASE("textbook scenes, resting contact: a stack of 10 cubes stands and settles under 5 mm", "[lab06][pts=2][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  CHECK(checkScenes({"stack"}) == 1);
}

TEST_CASE("textbook scenes, resting contact: with converged PGS the stack of 10 stands still", "[lab06][pts=1][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  // The suite's bar is 'stands'; 'still' needs PGS converged: 100 sweeps sway the top by about
  // 3 cm, 300 by under 1 cm (the exact solvers hold it to 1e-8 m, but Lemke cannot take every
  // scene of the suite: the dominoes' degenerate corners end it on a ray).
  RestingSettings converged;
  converged.lcp.max_iterations = 300;
  for (const auto& scene : contactSuite({"stack"})) {
    WorldEngine world(World(scene->scene(), restingWorldSettings(), std::make_shared<LcpContactSolver>(converged)));
    const std::vector<Measure> measures = runSuiteScene(*scene, world);
    REQUIRE(measures.size() == 2);
    CAPTURE(measures[0].value, measures[1].value);
    // 1 cm: a twentieth of an edge, a tenth of a degree of lean over the stack's 2 m
    CHECK(measures[1].value <= 0.01);
    CHECK(measures[0].pass());
  }
}
