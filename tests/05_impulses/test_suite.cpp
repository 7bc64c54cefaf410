// Lab 5 graded tests: the World with sequential impulses on textbook scenes, each against the
// physical truth (contact_suite.hpp states every value and its tolerance's reason).
#include <memory>
#include <string>

#include "physlab/contact_suite.hpp"
#include "support.hpp"

using namespace physlab;

namespace {

// Runs the suite's scenes whose names start with one of `names` in Lab 5's World (default
// Settings: sequential impulses) and checks every measure; returns how many scenes ran.
int checkScenes(std::initializer_list<const char*> names) {
  const auto scenes = contactSuite(names);
  for (const auto& scene : scenes) {
    WorldEngine world(World(scene->scene(), Settings{}));
    for (const Measure& m : runSuiteScene(*scene, world)) {
      CAPTURE(scene->name(), m.name, m.value, m.expected, m.tolerance, m.why);
      CHECK(m.pass());
    }
  }
  return static_cast<int>(scenes.size());
}

}  // namespace

TEST_CASE("textbook scenes, sequential impulses: flat boxes and balls rebound to e^2 of their drop without turning", "[lab05][pts=3][sec=2][sec=3][sec=4][sec=5]") {
  // Flat drops at e = 0.5 and 0.9, a slow one at 0.9 m/s, balls at 0.9 m/s and from 1 m
  CHECK(checkScenes({"flat drop", "slow", "ball"}) == 5);
}

TEST_CASE("textbook scenes, sequential impulses: a tilted drop gains no energy and comes to rest", "[lab05][pts=1][sec=2][sec=3][sec=4][sec=5]") {
  CHECK(checkScenes({"tilted drop"}) == 1);
}

TEST_CASE("textbook scenes, sequential impulses: a ramp holds below atan(mu), slides at g(sin - mu cos) above; a thrown ball rolls at 5/7 v0", "[lab05][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  CHECK(checkScenes({"ramp", "thrown ball"}) == 3);
}

TEST_CASE("textbook scenes, sequential impulses: a 100:1 heavy box stays on a light one, a 5 cm overlap is pushed out without a jump, dominoes fall in order", "[lab05][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  CHECK(checkScenes({"heavy on light", "overlap recovery", "dominoes"}) == 3);
}

TEST_CASE("textbook scenes, sequential impulses: a stack of 10 cubes stands, sunk by its 10 slops", "[lab05][pts=1][sec=2][sec=3][sec=4][sec=5]") {
  // Lab 5's sink bar is the slop's, not the suite's (Lab 6 meets that): position correction
  // leaves each of the 10 contacts up to its 1 mm slop deep.
  for (const auto& scene : contactSuite({"stack"})) {
    WorldEngine world(World(scene->scene(), Settings{}));
    const std::vector<Measure> measures = runSuiteScene(*scene, world);
    REQUIRE(measures.size() == 2);
    CAPTURE(measures[0].value, measures[1].value);
    // Sunk: 10 contacts at the 1 mm slop, and a millimetre of round-off and sway.
    CHECK(measures[0].value <= 10 * Settings{}.slop + 0.001);
    CHECK(measures[0].value >= 0.0);
    CHECK(measures[1].pass());
  }
}
