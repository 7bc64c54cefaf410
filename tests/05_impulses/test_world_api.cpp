// Framework tests for Lab 5's World API: states from velocities, per-pair depths, body indices,
// the pipeline's classification before gravity, and the contact suite's selection and report. They grade nothing (the code lives in
// common/), so they carry [common].
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <vector>

#include "physlab/contact_suite.hpp"
#include "physlab/error.hpp"
#include "physlab/rigid.hpp"
#include "physlab/suite_report.hpp"
#include "physlab/world.hpp"
#include "support.hpp"

using namespace physlab;
using Catch::Matchers::Contains;

TEST_CASE("world api: BodyState::moving gives P = m v and L = R I R^T omega, zero for a fixed body", "[common]") {
  const BodyDescription box = BodyDescription::box(2.0, Vec3(0.3, 0.2, 0.1), 0.5, 0.5);
  const Quat q(test::randomRotation());
  const Vec3 x = test::randomVec3(1.0), v = test::randomVec3(2.0), omega = test::randomVec3(2.0);
  const BodyState s = BodyState::moving(box, x, q, v, omega);
  const Mat3 R = q.toRotationMatrix();
  CHECK(s.x == x);
  // A rotation matrix and two products: round-off on values of order 1.
  CHECK((s.P - 2.0 * v).norm() <= 1e-14);
  CHECK((s.L - R * box.inertia_body * R.transpose() * omega).norm() <= 1e-13);
  // The World reads the same velocities back
  Scene scene;
  scene.bodies = {box};
  scene.states = {s};
  const World world(scene);
  CHECK((world.velocity(0) - v).norm() <= 1e-13);
  CHECK((world.angularVelocity(0) - omega).norm() <= 1e-12);
  // A fixed body has no momentum, whatever it is given; the quaternion comes back normalised
  BodyDescription wall = BodyDescription::fixedBox(Vec3::Constant(1.0), 0.5, 0.5);
  const BodyState still = BodyState::moving(wall, x, Quat(2.0, 0.0, 0.0, 0.0), v, omega);
  CHECK(still.P == Vec3::Zero());
  CHECK(still.L == Vec3::Zero());
  CHECK(still.q.norm() == Approx(1.0).epsilon(1e-15));
  CHECK_THROWS_WITH(BodyState::moving(box, x, q, Vec3(std::nan(""), 0.0, 0.0), omega), Contains("velocity v"));
  CHECK_THROWS_WITH(BodyState::moving(box, x, Quat(0.0, 0.0, 0.0, 0.0), v, omega), Contains("quaternion is zero"));
}

TEST_CASE("world api: a body index outside the world is refused with InvalidInput naming it", "[common]") {
  const World world(bouncingBall(1.0, 0.5));
  for (const int i : {-1, 2}) {
    CHECK_THROWS_WITH(world.velocity(i), Contains("body index " + std::to_string(i)) && Contains("2 bodies"));
    CHECK_THROWS_AS(world.angularVelocity(i), InvalidInput);
    CHECK_THROWS_AS(world.depth(0, i), InvalidInput);
    CHECK_THROWS_AS(world.depth(i, 0), InvalidInput);
  }
  // Both ends of the range are bodies
  CHECK_NOTHROW(world.velocity(0));
  CHECK_NOTHROW(world.velocity(1));
}

TEST_CASE("world api: depth(i, j) is the deepest point of the pair in either order, 0 apart", "[common]") {
  // A box resting 3 mm deep in the ground, tilted so that its corners have different depths
  Scene scene = bouncingBall(1.0, 0.0);
  scene.bodies[1] = BodyDescription::box(1.0, Vec3(0.2, 0.2, 0.1), 0.0, 0.5);
  scene.states[1].q = Quat(Eigen::AngleAxisd(0.01, Vec3::UnitX()));
  scene.states[1].x = Vec3(0.0, 0.0, 0.1 - 0.003);
  World world(scene);
  CHECK(world.depth(0, 1) == 0.0);  // no step yet: no contacts
  world.step(1.0 / 60.0);
  double deepest = 0.0;
  for (const Contact& c : world.contacts()) deepest = std::max(deepest, c.depth);
  REQUIRE(world.contacts().size() == 4);
  CHECK(world.depth(0, 1) == deepest);
  CHECK(world.depth(1, 0) == deepest);
  CHECK(world.depth(1, 1) == 0.0);  // a body never touches itself
  // The tilt puts one edge deeper: 0.2 m x sin(0.01) = 2 mm more than the centre's 3 mm
  CHECK(deepest == Approx(0.003 + 0.2 * std::sin(0.01)).epsilon(1e-3));
}

TEST_CASE("world api: a body at rest on the ground is resting, not colliding, at any step size", "[common]") {
  // Classified with the velocity before gravity: 0, whatever g h is
  for (const double h : {1.0 / 240.0, 1.0 / 60.0, 1.0 / 10.0}) {
    Scene scene = bouncingBall(0.0, 0.9);
    scene.states[1].x.z() -= 1e-6;  // touching by a hair
    World world(scene);
    world.step(h);
    CAPTURE(h);
    REQUIRE(world.diagnostics().contacts == 1);
    CHECK(world.contacts()[0].kind == ContactKind::Resting);
    CHECK(world.contacts()[0].v_rel_minus == 0.0);
    // It stays: the resting point takes gravity's impulse, no bounce
    CHECK(std::abs(world.velocity(1).z()) <= 1e-12);
  }
}

TEST_CASE("contact suite: scenes picked by name prefix, and a report or a drift chart refuses a missing engine", "[common]") {
  const auto all = contactSuite();
  REQUIRE(all.size() == 20);
  CHECK(contactSuite({"stack", "dominoes"}).size() == 2);
  CHECK(contactSuite({"fast sphere"}).size() == 3);
  CHECK(contactSuite({"flat drop"}).size() == 2);  // "slow flat drop" does not start with it
  CHECK(contactSuite({"no such scene"}).empty());
  CHECK_THROWS_WITH(contactSuiteReport({}, "heading", "/tmp/unused", std::cout), Contains("no engine"));
  CHECK_THROWS_WITH(contactSuiteReport({SuiteColumn{"name", "label", "points", nullptr}}, "heading", "/tmp/unused", std::cout),
                    Contains("'label' has no make function"));
  CHECK_THROWS_WITH(stackDriftChart({}, "/tmp/unused", std::cout), Contains("stack drift chart: no engine"));
  CHECK_THROWS_WITH(stackDriftChart({SuiteColumn{"name", "label", "lines", nullptr}}, "/tmp/unused", std::cout),
                    Contains("'label' has no make function"));
}

namespace {

// An engine that never moves: every step leaves the start it was made from
class Frozen : public SuiteEngine {
 public:
  explicit Frozen(Scene scene) : scene_(std::move(scene)) {}
  void step(double) override {}
  std::vector<BodyState> states() const override { return scene_.states; }

 private:
  Scene scene_;
};

}  // namespace

TEST_CASE("contact suite: shaken runs shift only the moving bodies, by at most the shift, and report median and largest", "[common]") {
  std::vector<Scene> starts;
  const SuiteEngineMaker frozen = [&](const Scene& scene) {
    starts.push_back(scene);
    return std::make_unique<Frozen>(scene);
  };
  const double shift = 1e-9;
  const std::vector<SpreadMeasure> spread = runSuiteSceneShaken("stack of 10 cubes", frozen, 9, shift);
  REQUIRE(starts.size() == 9);
  const Scene original = contactSuite({"stack"})[0]->scene();
  std::vector<double> drifts;
  for (std::size_t run = 0; run < starts.size(); ++run) {
    double drift = 0.0;
    for (std::size_t i = 0; i < original.states.size(); ++i) {
      const Vec3 d = starts[run].states[i].x - original.states[i].x;
      CAPTURE(run, i, d.transpose());
      CHECK(d.z() == 0.0);                                      // only x and y move
      CHECK(d.cwiseAbs().maxCoeff() <= shift);                   // each by at most the shift
      if (original.bodies[i].fixed || run == 0) CHECK(d.isZero(0.0));  // the ground and run 0 stay
      drift = std::max(drift, starts[run].states[i].x.head<2>().norm());
    }
    drifts.push_back(drift);
  }
  CHECK(starts[1].states[1].x != starts[2].states[1].x);  // every run its own shift
  // A frozen stack's sway is its largest start offset: 0 in run 0, the shifts' in the others
  std::sort(drifts.begin(), drifts.end());
  REQUIRE(spread.size() == 2);
  CHECK(spread[1].median.name == "largest sideways drift [m]");
  CHECK(spread[1].median.value == drifts[4]);
  CHECK(spread[1].largest == drifts[8]);
  CHECK(drifts[4] > 0.0);
  // The sink is the same in every run (nothing moves up or down): median = largest
  CHECK(spread[0].median.value == spread[0].largest);
  CHECK(spread[0].median.tolerance == contactSuite({"stack"})[0]->measures()[0].tolerance);
  // Only the stack asks for several runs in reports
  for (const auto& scene : contactSuite()) CHECK(scene->runs() == (scene->name() == "stack of 10 cubes" ? 9 : 1));
  // One run without a shift is runSuiteScene itself
  const auto once = runSuiteSceneShaken("stack of 10 cubes", frozen, 1, 0.0);
  CHECK(once[1].median.value == 0.0);
  CHECK(once[1].largest == 0.0);
  // An even count takes the mean of the middle two
  starts.clear();
  const auto two = runSuiteSceneShaken("stack of 10 cubes", frozen, 2, shift);
  const double second = [&] {
    double d = 0.0;
    for (const BodyState& s : starts[1].states) d = std::max(d, s.x.head<2>().norm());
    return d;
  }();
  CHECK(two[1].median.value == 0.5 * second);
  CHECK(two[1].largest == second);
}

TEST_CASE("shaken scene: seed 0 is the scene, others shift each moving body by at most the shift in x and y", "[common]") {
  const Scene rain = boxRain(20, 3);
  const Scene same = shakenScene(rain, 0);
  const Scene one = shakenScene(rain, 1, 1e-6), again = shakenScene(rain, 1, 1e-6), two = shakenScene(rain, 2, 1e-6);
  REQUIRE(one.states.size() == rain.states.size());
  bool moved = false;
  for (std::size_t i = 0; i < rain.states.size(); ++i) {
    CAPTURE(i);
    CHECK(same.states[i].x == rain.states[i].x);
    const Vec3 d = one.states[i].x - rain.states[i].x;
    CHECK(d.z() == 0.0);
    CHECK(d.cwiseAbs().maxCoeff() <= 1e-6);
    if (rain.bodies[i].fixed) CHECK(d.isZero(0.0));  // the ground and the walls stay
    CHECK(one.states[i].x == again.states[i].x);      // seeded: the same seed, the same shifts
    CHECK(one.states[i].q.coeffs() == rain.states[i].q.coeffs());
    CHECK(one.states[i].P == rain.states[i].P);
    moved = moved || (!rain.bodies[i].fixed && one.states[i].x != two.states[i].x);
  }
  CHECK(moved);  // another seed, other shifts
  CHECK(shakenScene(rain, 5, 0.0).states[7].x == rain.states[7].x);
  CHECK_THROWS_WITH(shakenScene(rain, 1, -1e-9), Contains("shakenScene shift must be finite and >= 0"));
  CHECK_THROWS_WITH(shakenScene(rain, 1, INFINITY), Contains("shakenScene shift must be finite"));
}

TEST_CASE("contact suite: shaken runs refuse an unknown scene, no runs, a bad shift and a maker without engine", "[common]") {
  const SuiteEngineMaker world = [](const Scene& scene) { return std::make_unique<WorldEngine>(World(scene, Settings{})); };
  CHECK_THROWS_WITH(runSuiteSceneShaken("stack", world), Contains("no suite scene is called 'stack'"));
  CHECK_THROWS_WITH(runSuiteSceneShaken("stack of 10 cubes", world, 0), Contains("at least 1 run, got 0"));
  CHECK_THROWS_WITH(runSuiteSceneShaken("stack of 10 cubes", world, 9, -1e-9), Contains("shift must be finite and >= 0"));
  CHECK_THROWS_WITH(runSuiteSceneShaken("stack of 10 cubes", world, 9, std::nan("")), Contains("shift must be finite"));
  CHECK_THROWS_WITH(runSuiteSceneShaken("stack of 10 cubes", [](const Scene&) { return std::unique_ptr<SuiteEngine>(); }),
                    Contains("returned no engine"));
}

TEST_CASE("contact suite: a run that stops being finite makes the shaken median and largest fail", "[common]") {
  // An engine whose states are NaN after its first step
  class Broken : public SuiteEngine {
   public:
    explicit Broken(Scene scene) : scene_(std::move(scene)) {}
    void step(double) override {
      for (BodyState& s : scene_.states) s.x = Vec3::Constant(std::nan(""));
    }
    std::vector<BodyState> states() const override { return scene_.states; }

   private:
    Scene scene_;
  };
  int made = 0;
  const auto spread = runSuiteSceneShaken("stack of 10 cubes", [&](const Scene& scene) -> std::unique_ptr<SuiteEngine> {
    // Runs 0-4 break, 5-8 stand still
    if (made++ < 5) return std::make_unique<Broken>(scene);
    return std::make_unique<Frozen>(scene);
  });
  CHECK(std::isnan(spread[1].largest));
  CHECK(std::isnan(spread[1].median.value));  // five NaN of nine: the median is one of them
  CHECK_FALSE(spread[1].median.pass());
}

namespace {

// The largest difference of position, orientation or momentum of any body between two worlds
double largestDifference(const World& a, const World& b) {
  double largest = 0.0;
  for (std::size_t i = 0; i < a.states().size(); ++i) {
    const BodyState &s = a.states()[i], &t = b.states()[i];
    largest = std::max({largest, (s.x - t.x).cwiseAbs().maxCoeff(), (s.q.coeffs() - t.q.coeffs()).cwiseAbs().maxCoeff(),
                        (s.P - t.P).cwiseAbs().maxCoeff(), (s.L - t.L).cwiseAbs().maxCoeff()});
  }
  return largest;
}

}  // namespace

TEST_CASE("world islands: each island solved on its own gives the whole scene's states, to the bit with tolerance 0", "[common]") {
  // A rain of 60 bodies settling into piles on the container's floor: many islands at once
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    CAPTURE(responseMethodName(method));
    Settings settings;
    settings.method = method;
    // Tolerance 0: a solve stops only at a sweep that changes nothing, after which further
    // sweeps change nothing either, so the whole scene's extra sweeps leave a quiet island as it was
    settings.tolerance = 0.0;
    settings.iterations = 100;
    // and the response's sweeps not cut short where the shock propagation follows: it cuts them
    // on an island resting on a fixed body, and on one system when any body rests on one
    settings.shock_response_iterations = settings.iterations;
    Settings whole = settings;
    whole.islands = false;
    World by_island(boxRain(60, 7), settings), one_system(boxRain(60, 7), whole);
    int most_islands = 0;
    for (int n = 0; n < 300; ++n) {
      by_island.step(1.0 / 60.0);
      one_system.step(1.0 / 60.0);
      most_islands = std::max(most_islands, by_island.diagnostics().islands);
      REQUIRE(one_system.diagnostics().islands <= 1);
    }
    CHECK(most_islands > 5);
    CHECK(largestDifference(by_island, one_system) == 0.0);
    CHECK(by_island.diagnostics().largest_island <= by_island.diagnostics().contacts);
  }
}

TEST_CASE("world sleeping: the broad phase, sleepers looked up apart, steps the world as every pair does, to the bit", "[common]") {
  // A rain of 60 bodies in the container (fixed walls) settling, islands falling asleep and being
  // woken; then one body dropped from 1 m onto the piles. The broad phase gives the incremental
  // tree only the bodies not asleep and looks each awake one up among the sleepers' boxes: the
  // same candidates, in the same order, as every pair of bodies (the sleeping pairs skipped)
  Settings settings;
  settings.sleeping = true;
  Settings every_pair = settings;
  every_pair.use_broad_phase = false;
  World broad(boxRain(60, 7), settings), all(boxRain(60, 7), every_pair);
  const int dropped = static_cast<int>(broad.bodies().size()) - 1;
  int most_asleep = 0, wakes = 0;
  for (int n = 0; n < 420; ++n) {
    if (n == 300) {
      const BodyState above = BodyState::moving(broad.bodies()[dropped], Vec3(0.0, 0.0, 1.0), Quat::Identity(),
                                                Vec3::Zero(), Vec3::Zero());
      broad.setState(dropped, above);
      all.setState(dropped, above);
    }
    int asleep = 0;
    for (int i = 0; i <= dropped; ++i) asleep += broad.asleep(i) ? 1 : 0;
    broad.step(1.0 / 60.0);
    all.step(1.0 / 60.0);
    CAPTURE(n);
    REQUIRE(broad.diagnostics().asleep == all.diagnostics().asleep);
    REQUIRE(largestDifference(broad, all) == 0.0);
    most_asleep = std::max(most_asleep, broad.diagnostics().asleep);
    // Fewer asleep after the step than before it: an awake body woke an island
    if (broad.diagnostics().asleep < asleep) ++wakes;
  }
  CHECK(most_asleep > 20);
  CHECK(wakes > 0);
}

TEST_CASE("world islands and sleeping: bad sleep settings are refused by name, and asleep() checks its index", "[common]") {
  for (const double bad : {-1e-9, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    CAPTURE(bad);
    Settings s;
    s.sleep_linear = bad;
    CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), s), Contains("sleep_linear"));
    s = Settings{};
    s.sleep_angular = bad;
    CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), s), Contains("sleep_angular"));
    s = Settings{};
    s.sleep_time = bad;
    CHECK_THROWS_WITH(World(bouncingBall(1.0, 0.5), s), Contains("sleep_time"));
  }
  World world(bouncingBall(1.0, 0.5));
  CHECK_FALSE(world.asleep(0));
  CHECK_THROWS_AS(world.asleep(2), InvalidInput);
}
