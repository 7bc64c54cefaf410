// Framework tests for the Lab 4 broad phase: the brute-force oracle on a scene worked out by
// hand, and bad boxes refused with a message naming them (before any student code runs).
#include <cmath>
#include <limits>
#include <memory>

#include "physlab/broadphase.hpp"
#include "physlab/error.hpp"
#include "support.hpp"

using namespace physlab;
using Catch::Matchers::Contains;

namespace {

Aabb box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return {Vec3(x0, y0, z0), Vec3(x1, y1, z1)};
}

}  // namespace

TEST_CASE("broad phase validation: brute force finds the hand-made pairs", "[common]") {
  const std::vector<Aabb> boxes = {
      box(0, 0, 0, 1, 1, 1),          // 0
      box(1, 0, 0, 2, 1, 1),          // 1: shares a face with 0
      box(2, 1, 1, 3, 2, 2),          // 2: shares one corner with 1
      box(3.5, 0, 0, 4, 1, 1),        // 3: apart from all
      box(0.5, 0.5, 0.5, 0.5, 0.5, 0.5),  // 4: a point inside 0
      box(std::nextafter(2.0, 3.0), 0, 0, 3, 1, 1),  // 5: one ulp from 1's face: apart
  };
  BruteForce brute;
  PairList pairs;
  brute.findPairs(boxes, pairs);
  CHECK(pairs == PairList{{0, 1}, {0, 4}, {1, 2}, {2, 5}});
  CHECK(brute.overlapTests() == 15);  // all 6 * 5 / 2 pairs
}

TEST_CASE("broad phase validation: min > max is refused, naming the box and axis", "[common]") {
  std::vector<Aabb> boxes = {box(0, 0, 0, 1, 1, 1), box(0, 0, 0, 1, 1, 1), box(0, 0, 0, 1, 1, 1)};
  boxes[2].min.y() = 2.0;
  PairList pairs;
  for (const auto& method : allBroadPhases()) {
    INFO(method->name());
    CHECK_THROWS_AS(method->findPairs(boxes, pairs), InvalidInput);
    CHECK_THROWS_WITH(method->findPairs(boxes, pairs), Contains("box 2 has min > max on the y axis"));
  }
  SweepAndPrune sap;
  CHECK_THROWS_WITH(sap.build(boxes, pairs), Contains("box 2 has min > max"));
  Bvh bvh;
  CHECK_THROWS_WITH(bvh.build(boxes, pairs), Contains("box 2 has min > max"));
}

TEST_CASE("broad phase validation: NaN and infinite coordinates are refused", "[common]") {
  std::vector<Aabb> boxes = {box(0, 0, 0, 1, 1, 1), box(0, 0, 0, 1, 1, 1)};
  boxes[1].max.z() = std::nan("");
  PairList pairs;
  for (const auto& method : allBroadPhases()) {
    INFO(method->name());
    CHECK_THROWS_WITH(method->findPairs(boxes, pairs), Contains("box 1 has a non-finite coordinate on the z axis"));
  }
  boxes[1].max.z() = 1.0;
  boxes[0].min.x() = -std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(requireValidBoxes(boxes), Contains("box 0 has a non-finite coordinate on the x axis"));
  // A point (min == max) is a valid box.
  boxes[0].min = boxes[0].max;
  CHECK_NOTHROW(requireValidBoxes(boxes));
}

TEST_CASE("broad phase validation: update and refit need the boxes of the last build", "[common]") {
  const std::vector<Aabb> boxes = {box(0, 0, 0, 1, 1, 1), box(2, 0, 0, 3, 1, 1)};
  PairList pairs;
  SweepAndPrune sap;  // never built: it holds 0 boxes
  CHECK_THROWS_WITH(sap.update(boxes, pairs), Contains("sort and sweep update got 2 boxes, but the last build had 0"));
  Bvh bvh;
  CHECK_THROWS_WITH(bvh.refit(boxes, pairs), Contains("BVH refit got 2 boxes, but the last build had 0"));
  std::vector<Aabb> bad = boxes;
  bad[0].max.x() = -1.0;
  CHECK_THROWS_WITH(sap.update(bad, pairs), Contains("box 0 has min > max on the x axis"));
}
