// Lab 4 hidden tests, broad phase (instructor only, shown after grades are published): scenes
// far from the origin, boxes flat on one plane, teleported boxes, and empty input.
#include <memory>

#include "../../04_collision/broad_phase_scenes.hpp"
#include "physlab/broadphase.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

std::vector<std::unique_ptr<BroadPhase>> studentMethods() {
  std::vector<std::unique_ptr<BroadPhase>> methods;
  methods.push_back(std::make_unique<SweepAndPrune>());
  methods.push_back(std::make_unique<UniformGrid>());
  methods.push_back(std::make_unique<Bvh>());
  methods.push_back(std::make_unique<KdTree>());
  return methods;
}

}  // namespace

TEST_CASE("hidden: broad phases are exact far from the origin", "[lab04][pts=1][hidden][sec=1]") {
  // At 10^6 m the spacing of doubles is ~1e-10 m: coordinates are still exact multiples of it,
  // and cell and split computations must not lose touching pairs to rounding.
  const int n = randomCount(10, 2000);
  std::vector<Aabb> boxes = touchingScene(n);
  const Vec3 far = Vec3(1e6, -2e6, 3e6) + randomVec3(1e5);
  for (Aabb& b : boxes) {
    b.min += far;
    b.max += far;
  }
  for (const auto& method : studentMethods()) {
    PairList pairs;
    method->findPairs(boxes, pairs);
    INFO(method->name() << ", " << n << " boxes");
    CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  }
}

TEST_CASE("hidden: broad phases handle boxes flat on one plane", "[lab04][pts=1][hidden][sec=1]") {
  const int n = randomCount(10, 2000);
  std::vector<Aabb> boxes = randomScene(n, BoxSizes::Flat);
  const double z = uniform(-5, 5);
  for (Aabb& b : boxes) b.min.z() = b.max.z() = z;  // every box has zero thickness at one height
  for (const auto& method : studentMethods()) {
    PairList pairs;
    method->findPairs(boxes, pairs);
    INFO(method->name() << ", " << n << " boxes");
    CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  }
}

TEST_CASE("hidden: sort-and-sweep update and BVH refit survive teleported boxes", "[lab04][pts=1][hidden][sec=1]") {
  const int n = randomCount(10, 2000);
  std::vector<Aabb> boxes = randomScene(n, BoxSizes::Uniform);
  SweepAndPrune sap;
  Bvh bvh;
  PairList sap_pairs, bvh_pairs;
  sap.build(boxes, sap_pairs);
  bvh.build(boxes, bvh_pairs);
  // Every box jumps to a fresh random place: the old order and tree are no help, yet the
  // answer must stay exact.
  boxes = randomScene(n, BoxSizes::WideRange);
  sap.update(boxes, sap_pairs);
  bvh.refit(boxes, bvh_pairs);
  const PairList expected = bruteForcePairs(boxes);
  CHECK_SAME_PAIRS(sap_pairs, expected);
  CHECK_SAME_PAIRS(bvh_pairs, expected);
}

TEST_CASE("hidden: no boxes and one box give no pairs", "[lab04][pts=1][hidden][sec=1]") {
  for (const auto& method : studentMethods()) {
    INFO(method->name());
    PairList pairs = {{0, 1}};  // stale content must be cleared
    method->findPairs({}, pairs);
    CHECK(pairs.empty());
    pairs = {{0, 1}};
    method->findPairs({Aabb{randomVec3(1.0), randomVec3(1.0) + Vec3::Constant(2.0)}}, pairs);
    CHECK(pairs.empty());
    // And the object still works afterwards.
    const std::vector<Aabb> boxes = randomScene(randomCount(10, 300), BoxSizes::Uniform);
    method->findPairs(boxes, pairs);
    CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  }
}
