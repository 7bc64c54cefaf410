// Lab 4 hidden tests, incremental broad phase (instructor only, shown after grades are
// published): a scene far from the origin moving in lockstep, and a scene that empties and
// refills while everything teleports every step.
#include "../../04_collision/broad_phase_scenes.hpp"
#include "physlab/broadphase.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

TEST_CASE("hidden: incremental broad phase exact far from the origin, touching boxes drifting together", "[lab04][pts=1][hidden][sec=10]") {
  // Lattice boxes 10^6 m out, all shifted by the same multiple of a power of two each step:
  // the touching pairs stay touching exactly, and must stay reported.
  const int n = randomCount(10, 1500);
  std::vector<Aabb> boxes = touchingScene(n);
  const Vec3 far(1e6, -2e6, 3e6);
  for (Aabb& b : boxes) {
    b.min += far;
    b.max += far;
  }
  IncrementalBroadPhase bp;
  PairList pairs;
  for (int step = 0; step < 8; ++step) {
    const Vec3 d = Vec3(0.0078125, -0.015625, 0.03125) * step;  // binary fractions: exact sums
    std::vector<Aabb> moved = boxes;
    for (Aabb& b : moved) {
      b.min += d;
      b.max += d;
    }
    bp.findPairs(moved, pairs);
    INFO(n << " boxes, step " << step);
    CHECK_SAME_PAIRS(pairs, bruteForcePairs(moved));
  }
}

TEST_CASE("hidden: incremental broad phase survives teleports, emptying and refilling", "[lab04][pts=1][hidden][sec=10]") {
  IncrementalBroadPhase bp(0.0);
  PairList pairs;
  for (const int n : {300, 300, 0, 300, 1, 2, 300}) {
    const std::vector<Aabb> boxes = randomScene(n, BoxSizes::WideRange);  // a new scene: all teleport
    bp.findPairs(boxes, pairs);
    INFO(n << " boxes");
    CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
    CHECK(bp.tree().leafCount() == n);
  }
}
