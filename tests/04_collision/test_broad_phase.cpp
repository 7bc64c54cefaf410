// Lab 4 graded tests, broad phase: each method must return exactly the brute-force pair set
// (i < j, sorted) on random scenes of 10-2000 boxes, on touching and degenerate boxes, and after
// the boxes move (sort-and-sweep update, BVH refit); and it must do far less work than testing
// every pair. The answers are sets of integers, so the comparisons are exact: no tolerances.
#include <algorithm>
#include <cmath>
#include <memory>

#include "broad_phase_scenes.hpp"
#include "physlab/broadphase.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// Every random scene kind at a small and a random size in [10, 2000].
template <class Method>
void checkRandomScenes(Method& method) {
  for (BoxSizes sizes : kAllSizes) {
    for (int n : {10, randomCount(10, 2000)}) {
      INFO(sizesName(sizes) << " scene of " << n << " boxes");
      const std::vector<Aabb> boxes = randomScene(n, sizes);
      PairList pairs;
      method.findPairs(boxes, pairs);
      CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
    }
  }
}

// Shared faces, coincident points and boxes spanning (most of) everything.
template <class Method>
void checkDegenerateScenes(Method& method) {
  const int n = randomCount(10, 2000);
  const std::vector<std::pair<const char*, std::vector<Aabb>>> scenes = {
      {"touching lattice boxes", touchingScene(n)},
      {"boxes at one point", pointScene(n)},
      {"huge boxes among uniform boxes", hugeBoxScene(n, BoxSizes::Uniform)},
      {"huge boxes among wide-range boxes", hugeBoxScene(n, BoxSizes::WideRange)},
  };
  for (const auto& [what, boxes] : scenes) {
    INFO(what << ", " << n << " boxes");
    PairList pairs;
    method.findPairs(boxes, pairs);
    CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  }
}

// Number of inversions of the sequence: pairs k < m with keys[k] > keys[m].
long inversions(const std::vector<double>& keys) {
  long count = 0;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    for (std::size_t m = k + 1; m < keys.size(); ++m) count += keys[k] > keys[m];
  }
  return count;
}

// Number of pairs whose intervals overlap on `axis` (touching included).
long intervalOverlaps(const std::vector<Aabb>& boxes, int axis) {
  long count = 0;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      count += boxes[i].min[axis] <= boxes[j].max[axis] && boxes[j].min[axis] <= boxes[i].max[axis];
    }
  }
  return count;
}

}  // namespace

TEST_CASE("sort and sweep: same pairs as brute force on random scenes", "[lab04][pts=2][sec=1]") {
  SweepAndPrune sap;
  checkRandomScenes(sap);
}

TEST_CASE("sort and sweep: touching boxes, boxes at one point and huge boxes", "[lab04][pts=1][sec=1]") {
  SweepAndPrune sap;
  checkDegenerateScenes(sap);
}

TEST_CASE("sort and sweep: update after moves matches brute force", "[lab04][pts=2][sec=1]") {
  for (BoxSizes sizes : {BoxSizes::Uniform, BoxSizes::WideRange, BoxSizes::Clustered}) {
    const int n = randomCount(10, 2000);
    std::vector<Aabb> boxes = randomScene(n, sizes);
    SweepAndPrune sap;
    PairList pairs;
    sap.build(boxes, pairs);
    for (int step = 1; step <= 5; ++step) {
      moveBoxes(boxes, 0.05);
      sap.update(boxes, pairs);
      INFO(sizesName(sizes) << " scene of " << n << " boxes, update " << step);
      CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
    }
  }
}

TEST_CASE("sort and sweep: insertion sort makes one swap per inversion", "[lab04][pts=1][sec=1]") {
  // Boxes spread far along x (centres 0, 1, 2, ...) and little along y and z: x is the sweep
  // axis, and the sorted order after build is the index order.
  const int n = randomCount(50, 400);  // the inversions are counted below by brute force: O(n^2)
  std::vector<Aabb> boxes;
  for (int i = 0; i < n; ++i) boxes.push_back(boxAround(Vec3(i, uniform(-1, 1), uniform(-1, 1)), Vec3::Constant(0.2)));
  SweepAndPrune sap;
  PairList pairs;
  sap.build(boxes, pairs);
  REQUIRE(sap.axis() == 0);
  // Unmoved boxes are already sorted: nothing to swap.
  sap.update(boxes, pairs);
  CHECK(sap.swaps() == 0);
  // Give box i the x position perm[i]: the list, in index order, has exactly inversions(perm)
  // out-of-order pairs, and insertion sort removes one per swap.
  std::vector<double> perm(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) perm[static_cast<std::size_t>(i)] = i;
  std::shuffle(perm.begin(), perm.end(), rng());
  for (int i = 0; i < n; ++i) {
    const double shift = perm[static_cast<std::size_t>(i)] - i;
    boxes[static_cast<std::size_t>(i)].min.x() += shift;
    boxes[static_cast<std::size_t>(i)].max.x() += shift;
  }
  sap.update(boxes, pairs);
  CHECK(sap.swaps() == inversions(perm));
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  // Mirroring x reverses the order: n (n - 1) / 2 swaps.
  for (Aabb& b : boxes) {
    const double lo = b.min.x();
    b.min.x() = -b.max.x();
    b.max.x() = -lo;
  }
  sap.update(boxes, pairs);
  CHECK(sap.swaps() == static_cast<long>(n) * (n - 1) / 2);
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  // Equal lower endpoints are not out of order: moving every box to the same x needs no swap.
  for (Aabb& b : boxes) {
    b.min.x() = 0.0;
    b.max.x() = 0.4;
  }
  sap.update(boxes, pairs);
  CHECK(sap.swaps() == 0);
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
}

TEST_CASE("sort and sweep: sweeps the axis of widest spread, testing exactly the pairs overlapping on it", "[lab04][pts=1][sec=1]") {
  // Stretching the scene threefold along one axis makes the centres spread most along it,
  // far beyond the sampling noise of the other two: build must pick it.
  std::vector<Aabb> boxes = randomScene(randomCount(200, 2000), BoxSizes::Uniform);
  const int stretched = static_cast<int>(uniform(0, 3));
  for (Aabb& b : boxes) {
    b.min[stretched] *= 3.0;
    b.max[stretched] *= 3.0;
  }
  SweepAndPrune sap;
  PairList pairs;
  sap.build(boxes, pairs);
  CHECK(sap.axis() == stretched);
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  // The sweep meets each pair whose intervals overlap on its axis once, and no other pair.
  CHECK(sap.overlapTests() == intervalOverlaps(boxes, sap.axis()));
}

TEST_CASE("uniform grid: same pairs as brute force on random scenes", "[lab04][pts=2][sec=1]") {
  UniformGrid grid;
  checkRandomScenes(grid);
  // Dense scenes in which most boxes are specks, so that the cell (twice the median edge) is far
  // smaller than the rest, which cover 3 or 4 cells per axis: tens of thousands of (cell, box)
  // entries and thousands of overlapping pairs, so that in a table sized to the entries some cells
  // of a pair share a bucket, whatever the hash. A grid that pairs boxes by bucket instead of by
  // cell then reports a pair twice, or a box with itself.
  for (int scene = 0; scene < 4; ++scene) {
    INFO("dense scene " << scene << " of specks and boxes over many cells");
    std::vector<Aabb> boxes;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 c(uniform(0.0, 0.3), uniform(0.0, 0.3), uniform(0.0, 0.3));
      // Two in three are specks 0.01 m wide, so the cell is 0.02 m; the others, 0.05-0.06 m
      // wide, cover 3 or 4 cells per axis, never more (which would set them aside as oversized).
      const double half = i % 3 != 0 ? 0.005 : uniform(0.025, 0.03);
      boxes.push_back(boxAround(c, Vec3::Constant(half)));
    }
    PairList pairs;
    grid.findPairs(boxes, pairs);
    CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  }
}

TEST_CASE("uniform grid: touching boxes, boxes at one point and huge boxes", "[lab04][pts=1][sec=1]") {
  UniformGrid grid;
  checkDegenerateScenes(grid);
}

TEST_CASE("uniform grid: the cell is twice the median longest edge", "[lab04][pts=1][sec=1]") {
  std::vector<Aabb> boxes = randomScene(randomCount(11, 501) | 1, BoxSizes::WideRange);  // odd n: one median
  std::vector<double> edges;
  for (const Aabb& b : boxes) edges.push_back((b.max - b.min).maxCoeff());
  std::sort(edges.begin(), edges.end());
  UniformGrid grid;
  PairList pairs;
  grid.findPairs(boxes, pairs);
  CHECK(grid.cellSize() == 2.0 * edges[edges.size() / 2]);  // the same double, chosen and doubled
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  // Points only: the median edge is 0 and the rule falls back to 1 m.
  boxes = pointScene(20);
  for (Aabb& b : boxes) b.max = b.min;
  grid.findPairs(boxes, pairs);
  CHECK(grid.cellSize() == 1.0);
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  // An even count: the median is the upper middle edge, so exactly half the boxes being points
  // does not yet give the fallback (it takes more than half).
  const int half = randomCount(5, 100);
  boxes.clear();
  edges.clear();
  for (int i = 0; i < 2 * half; ++i) {
    const Vec3 c = randomVec3(3.0);
    const double e = i % 2 == 0 ? 0.0 : uniform(0.1, 0.5);
    boxes.push_back(boxAround(c, Vec3::Constant(0.5 * e)));
    edges.push_back((boxes.back().max - boxes.back().min).maxCoeff());
  }
  std::sort(edges.begin(), edges.end());
  grid.findPairs(boxes, pairs);
  INFO(half << " points and " << half << " boxes");
  CHECK(edges[edges.size() / 2] > 0.0);
  CHECK(grid.cellSize() == 2.0 * edges[edges.size() / 2]);  // the same double, chosen and doubled
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
}

TEST_CASE("BVH: same pairs as brute force on random scenes", "[lab04][pts=2][sec=1]") {
  Bvh bvh;
  checkRandomScenes(bvh);
}

TEST_CASE("BVH: touching boxes, boxes at one point and huge boxes", "[lab04][pts=1][sec=1]") {
  Bvh bvh;
  checkDegenerateScenes(bvh);
}

TEST_CASE("BVH: refit after moves matches brute force", "[lab04][pts=2][sec=1]") {
  for (BoxSizes sizes : {BoxSizes::Uniform, BoxSizes::WideRange, BoxSizes::Clustered}) {
    const int n = randomCount(10, 2000);
    std::vector<Aabb> boxes = randomScene(n, sizes);
    Bvh bvh;
    PairList pairs;
    bvh.build(boxes, pairs);
    for (int step = 1; step <= 5; ++step) {
      moveBoxes(boxes, 0.05);
      bvh.refit(boxes, pairs);
      INFO(sizesName(sizes) << " scene of " << n << " boxes, refit " << step);
      CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
      // Refitting changes bounds, never the tree: every node still encloses its children.
      for (const Bvh::Node& node : bvh.nodes()) {
        if (node.left < 0) continue;
        const Aabb& l = bvh.nodes()[static_cast<std::size_t>(node.left)].bounds;
        const Aabb& r = bvh.nodes()[static_cast<std::size_t>(node.right)].bounds;
        REQUIRE((node.bounds.min.array() <= l.min.cwiseMin(r.min).array()).all());
        REQUIRE((node.bounds.max.array() >= l.max.cwiseMax(r.max).array()).all());
      }
    }
  }
}

TEST_CASE("BVH: the median split builds a balanced pre-order tree", "[lab04][pts=1][sec=1]") {
  // A random count, and on every run counts whose halvings end exactly at kLeafSize boxes (a
  // full leaf), at kLeafSize itself (one leaf) and one more (the first split).
  for (const int n : {randomCount(10, 2000), 8 * Bvh::kLeafSize, Bvh::kLeafSize, Bvh::kLeafSize + 1}) {
    INFO(n << " boxes");
    const std::vector<Aabb> boxes = randomScene(n, BoxSizes::WideRange);
    Bvh bvh;
    PairList pairs;
    bvh.build(boxes, pairs);
    CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
    // Halving from n until a leaf holds at most kLeafSize boxes: the depth of a median split.
    int expected_depth = 1;
    for (int size = n; size > Bvh::kLeafSize; size = (size + 1) / 2) ++expected_depth;
    CHECK(bvh.depth() == expected_depth);
    // Every box sits in exactly one leaf, and the leaves' boxes lie inside their bounds.
    std::vector<int> seen(static_cast<std::size_t>(n), 0);
    for (std::size_t k = 0; k < bvh.nodes().size(); ++k) {
      const Bvh::Node& node = bvh.nodes()[k];
      if (node.left >= 0) {
        CHECK(node.left == static_cast<int>(k) + 1);  // pre-order: the left child follows its parent
        continue;
      }
      CHECK(node.count >= 1);
      CHECK(node.count <= Bvh::kLeafSize);
      for (int p = node.first; p < node.first + node.count; ++p) {
        const int box = bvh.order()[static_cast<std::size_t>(p)];
        ++seen[static_cast<std::size_t>(box)];
        const Aabb& b = boxes[static_cast<std::size_t>(box)];
        CHECK((node.bounds.min.array() <= b.min.array()).all());
        CHECK((node.bounds.max.array() >= b.max.array()).all());
      }
    }
    CHECK(std::count(seen.begin(), seen.end(), 1) == n);
  }
}

TEST_CASE("k-d tree: same pairs as brute force on random scenes", "[lab04][pts=2][sec=1]") {
  KdTree tree;
  checkRandomScenes(tree);
}

TEST_CASE("k-d tree: touching boxes, boxes at one point and huge boxes", "[lab04][pts=1][sec=1]") {
  KdTree tree;
  checkDegenerateScenes(tree);
}

TEST_CASE("k-d tree: a node of at most kLeafSize boxes is one leaf, and leafCount() counts the leaves", "[lab04][pts=1][sec=1]") {
  // Boxes in a row along x, well apart: kLeafSize of them are one leaf (the root); one more and
  // the root splits at the median centre into two children that are both leaves (the median box
  // goes to both: kLeafSize / 2 + 1 boxes each).
  KdTree tree;
  for (const int n : {1, KdTree::kLeafSize, KdTree::kLeafSize + 1}) {
    std::vector<Aabb> boxes;
    for (int i = 0; i < n; ++i) boxes.push_back(boxAround(Vec3(3.0 * i, uniform(-1, 1), uniform(-1, 1)), Vec3::Constant(0.5)));
    PairList pairs;
    tree.findPairs(boxes, pairs);
    INFO(n << " boxes in a row");
    CHECK(pairs.empty());
    CHECK(tree.leafCount() == (n <= KdTree::kLeafSize ? 1 : 2));
  }
  // A dense random scene: every leaf the query visits is counted, and there are more than one.
  const std::vector<Aabb> boxes = randomScene(randomCount(200, 2000), BoxSizes::Uniform);
  PairList pairs;
  tree.findPairs(boxes, pairs);
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  CHECK(tree.leafCount() > 1);
}

TEST_CASE("broad phase: far fewer overlap tests than brute force on a sparse scene", "[lab04][pts=2][sec=1]") {
  const int n = 2000;
  const std::vector<Aabb> boxes = randomScene(n, BoxSizes::Uniform);
  const long all_pairs = static_cast<long>(n) * (n - 1) / 2;
  std::vector<std::unique_ptr<BroadPhase>> methods;
  methods.push_back(std::make_unique<UniformGrid>());
  methods.push_back(std::make_unique<Bvh>());
  methods.push_back(std::make_unique<KdTree>());
  // A scene with a few overlaps per box needs O(n) tests for the grid and the k-d tree and
  // O(n log n) for the BVH's per-box queries (about 80k here, 200k when n(n-1)/2 is 2M):
  // a tenth of brute force leaves a wide margin, yet rules out testing every pair.
  for (const auto& method : methods) {
    PairList pairs;
    method->findPairs(boxes, pairs);
    INFO(method->name() << ": " << method->overlapTests() << " overlap tests");
    CHECK(method->overlapTests() > 0);  // every test goes through BroadPhase::test
    CHECK(method->overlapTests() < all_pairs / 10);
  }
}

TEST_CASE("broad phase: one object reused on scenes of changing size", "[lab04][pts=1][sec=1]") {
  // A world keeps one broad phase and one pair buffer for its whole life, and the number of
  // bodies may change between steps.
  std::vector<std::unique_ptr<BroadPhase>> methods;
  methods.push_back(std::make_unique<SweepAndPrune>());
  methods.push_back(std::make_unique<UniformGrid>());
  methods.push_back(std::make_unique<Bvh>());
  methods.push_back(std::make_unique<KdTree>());
  for (const auto& method : methods) {
    PairList pairs;
    for (int n : {randomCount(100, 1000), randomCount(100, 1000), 3, randomCount(100, 1000)}) {
      std::vector<Aabb> boxes = randomScene(n, BoxSizes::WideRange);
      for (int step = 0; step < 3; ++step) {
        method->findPairs(boxes, pairs);
        INFO(method->name() << ", " << n << " boxes, call " << step);
        CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
        moveBoxes(boxes, 0.1);
      }
    }
  }
}
