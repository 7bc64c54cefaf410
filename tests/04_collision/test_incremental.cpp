// Lab 4 graded tests, incremental broad phase (section 10): over sequences of moves, insertions
// and removals the reported pairs are exactly the brute force's (i < j, sorted); touching boxes
// count; a box leaving its fat box is reinserted and one that stays is not; the dynamic tree
// keeps its invariants (boxes enclose children exactly, heights, fat holds tight, a logarithmic
// height) and its
// sibling choice follows the surface-area cost worked out by hand. Pair sets are integers and
// the hand cases use binary fractions, so the comparisons are exact: no tolerances.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>

#include "broad_phase_scenes.hpp"
#include "physlab/broadphase.hpp"
#include "physlab/error.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

namespace {

using Node = DynamicAabbTree::Node;

Aabb cuboid(double x0, double y0, double z0, double x1, double y1, double z1) {
  return {Vec3(x0, y0, z0), Vec3(x1, y1, z1)};
}

bool holds(const Aabb& inner, const Aabb& outer) {
  return (outer.min.array() <= inner.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
}

bool sameBox(const Aabb& a, const Aabb& b) { return a.min == b.min && a.max == b.max; }

// Everything the tree and the broad phase promise about their structure, checked by walking
// the tree from the root; returns "" when all holds, else the first problem found.
std::string structureProblem(const IncrementalBroadPhase& bp) {
  const DynamicAabbTree& tree = bp.tree();
  const std::vector<Node>& nodes = tree.nodes();
  std::ostringstream os;
  if (tree.root() == DynamicAabbTree::kNull) {
    if (bp.size() != 0 || tree.leafCount() != 0) os << "empty tree but " << bp.size() << " boxes";
    return os.str();
  }
  if (nodes[tree.root()].parent != DynamicAabbTree::kNull) return "the root has a parent";
  std::vector<int> stack = {tree.root()}, seen_ids;
  std::size_t visited = 0;
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    if (k < 0 || k >= static_cast<int>(nodes.size()) || ++visited > nodes.size()) return "a child index is out of the pool, or a cycle";
    const Node& n = nodes[k];
    if (n.isLeaf()) {
      if (n.height != 0) os << "leaf " << k << " has height " << n.height;
      else if (!bp.contains(n.id)) os << "leaf " << k << " holds id " << n.id << ", not a live box";
      else if (!sameBox(n.box, bp.fatBox(n.id))) os << "leaf " << k << " does not hold the fat box of id " << n.id;
      else if (!holds(bp.tightBox(n.id), bp.fatBox(n.id))) os << "the fat box of id " << n.id << " does not contain its tight box";
      if (!os.str().empty()) return os.str();
      seen_ids.push_back(n.id);
      continue;
    }
    const Node& c1 = nodes[n.child1];
    const Node& c2 = nodes[n.child2];
    if (c1.parent != k || c2.parent != k) os << "a child of node " << k << " does not point back to it";
    else if (!holds(c1.box, n.box) || !holds(c2.box, n.box)) os << "node " << k << "'s box does not contain a child's";
    else if (!sameBox(n.box, enclose(c1.box, c2.box))) os << "node " << k << "'s box is larger than its children's union (not refitted)";
    else if (n.height != 1 + std::max(c1.height, c2.height)) os << "node " << k << " has height " << n.height << ", not 1 + max of its children's";
    if (!os.str().empty()) return os.str();
    stack.push_back(n.child1);
    stack.push_back(n.child2);
  }
  std::sort(seen_ids.begin(), seen_ids.end());
  if (std::adjacent_find(seen_ids.begin(), seen_ids.end()) != seen_ids.end()) return "an id is in two leaves";
  if (static_cast<int>(seen_ids.size()) != bp.size() || tree.leafCount() != bp.size()) {
    os << seen_ids.size() << " leaves reached, leafCount() " << tree.leafCount() << ", " << bp.size() << " boxes";
  }
  return os.str();
}

#define CHECK_STRUCTURE(bp)                      \
  do {                                           \
    const std::string problem = structureProblem(bp); \
    INFO(problem);                               \
    CHECK(problem.empty());                      \
  } while (false)

// The brute force's pairs among the live ids of `live` (id -> box), as ids.
PairList bruteForceIds(const std::map<int, Aabb>& live) {
  PairList pairs;
  for (auto a = live.begin(); a != live.end(); ++a) {
    for (auto b = std::next(a); b != live.end(); ++b) {
      if (overlaps(a->second, b->second)) pairs.emplace_back(a->first, b->first);
    }
  }
  return pairs;
}

}  // namespace

TEST_CASE("incremental: same pairs as brute force over a seeded sequence of moves", "[lab04][pts=3][sec=10]") {
  // Margins: none (fat = tight, every move reinserts), the default, and one wider than a box.
  for (const double margin : {0.0, IncrementalBroadPhase::kDefaultMargin, 0.75}) {
    for (BoxSizes sizes : {BoxSizes::Uniform, BoxSizes::WideRange, BoxSizes::Clustered}) {
      const int n = randomCount(10, 1500);
      std::vector<Aabb> boxes = randomScene(n, sizes);
      IncrementalBroadPhase bp(margin);
      PairList pairs;
      for (int step = 0; step <= 10; ++step) {
        if (step > 0) moveBoxes(boxes, 0.03);  // small steps and a few teleports
        bp.findPairs(boxes, pairs);
        INFO("margin " << margin << ", " << sizesName(sizes) << " scene of " << n << " boxes, step " << step);
        CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
      }
      CHECK_STRUCTURE(bp);
    }
  }
}

TEST_CASE("incremental: a hand-built sequence, pair by pair, with the reinsertions counted", "[lab04][pts=2][sec=10]") {
  IncrementalBroadPhase bp(0.125);
  PairList pairs;
  CHECK(bp.add(cuboid(0, 0, 0, 1, 1, 1)) == 0);
  CHECK(bp.add(cuboid(2, 0, 0, 3, 1, 1)) == 1);
  CHECK(bp.add(cuboid(0, 2, 0, 1, 3, 1)) == 2);
  bp.update(pairs);
  CHECK(pairs.empty());
  CHECK(bp.fatPairs() == 0);  // fat boxes [-1/8, 9/8] and [15/8, 25/8] on x: apart
  // Box 1 moves 3/4 towards 0: out of its fat box; the new one reaches back by the displacement
  bp.move(1, cuboid(1.25, 0, 0, 2.25, 1, 1));
  bp.update(pairs);
  CHECK(bp.reinsertions() == 1);
  CHECK(sameBox(bp.fatBox(1), cuboid(1.25 - 0.125 - 0.75, -0.125, -0.125, 2.375, 1.125, 1.125)));
  CHECK(pairs.empty());       // tight boxes 1/4 apart
  CHECK(bp.fatPairs() == 1);  // fat boxes of 0 and 1 overlap
  // Box 1 reaches box 0's face x = 1 inside its fat box: no reinsertion, the touching pair found
  bp.move(1, cuboid(1, 0, 0, 2, 1, 1));
  bp.update(pairs);
  CHECK(bp.reinsertions() == 0);
  CHECK(pairs == PairList{{0, 1}});
  // Box 2 drops onto y = 1: it touches 0 on a face and 1 along an edge
  bp.move(2, cuboid(0, 1, 0, 1, 2, 1));
  bp.update(pairs);
  CHECK(bp.reinsertions() == 1);
  CHECK(pairs == PairList{{0, 1}, {0, 2}, {1, 2}});
  // Box 0 goes; a new box takes its id, far away
  bp.remove(0);
  bp.update(pairs);
  CHECK(pairs == PairList{{1, 2}});
  CHECK(bp.add(cuboid(10, 10, 10, 11, 11, 11)) == 0);
  bp.update(pairs);
  CHECK(pairs == PairList{{1, 2}});
  CHECK(bp.size() == 3);
  CHECK_STRUCTURE(bp);
}

TEST_CASE("incremental: boxes exactly touching, boxes at one point and huge boxes", "[lab04][pts=1][sec=10]") {
  const int n = randomCount(10, 1500);
  const std::vector<std::pair<const char*, std::vector<Aabb>>> scenes = {
      {"touching lattice boxes", touchingScene(n)},
      {"boxes at one point", pointScene(n)},
      {"huge boxes among uniform boxes", hugeBoxScene(n, BoxSizes::Uniform)},
      {"huge boxes among wide-range boxes", hugeBoxScene(n, BoxSizes::WideRange)},
  };
  for (const double margin : {0.0, IncrementalBroadPhase::kDefaultMargin}) {
    for (const auto& [what, boxes] : scenes) {
      INFO(what << ", " << n << " boxes, margin " << margin);
      IncrementalBroadPhase bp(margin);
      PairList pairs;
      bp.findPairs(boxes, pairs);
      CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
      // The same boxes again: nothing moves, the answer stays
      bp.findPairs(boxes, pairs);
      CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
    }
  }
}

TEST_CASE("incremental: a box moving out of its fat box and back", "[lab04][pts=1][sec=10]") {
  IncrementalBroadPhase bp(0.25);
  PairList pairs;
  bp.add(cuboid(0, 0, 0, 1, 1, 1));
  bp.add(cuboid(1.5, 0, 0, 2.5, 1, 1));
  bp.update(pairs);
  const Aabb fat = cuboid(-0.25, -0.25, -0.25, 1.25, 1.25, 1.25);
  CHECK(sameBox(bp.fatBox(0), fat));
  // Up to the fat box's face (inside, touching included): the tree is not touched
  bp.move(0, cuboid(0.25, 0, 0, 1.25, 1, 1));
  bp.update(pairs);
  CHECK(bp.reinsertions() == 0);
  CHECK(sameBox(bp.fatBox(0), fat));
  CHECK(pairs.empty());
  // Past it: reinserted, the fat box grown by the margin and by the displacement 1/2 on +x
  bp.move(0, cuboid(0.75, 0, 0, 1.75, 1, 1));
  bp.update(pairs);
  CHECK(bp.reinsertions() == 1);
  CHECK(sameBox(bp.fatBox(0), cuboid(0.5, -0.25, -0.25, 2.5, 1.25, 1.25)));
  CHECK(pairs == PairList{{0, 1}});
  // Back where it started: out again (below 0.5), grown by the displacement 3/4 on -x
  bp.move(0, cuboid(0, 0, 0, 1, 1, 1));
  bp.update(pairs);
  CHECK(bp.reinsertions() == 1);
  CHECK(sameBox(bp.fatBox(0), cuboid(-1, -0.25, -0.25, 1.25, 1.25, 1.25)));
  CHECK(pairs.empty());
  CHECK(bp.fatPairs() == 1);  // fat boxes [-1, 1.25] and [1.25, 2.75] on x touch: the pair is kept
  CHECK_STRUCTURE(bp);
}

TEST_CASE("incremental: insertions and removals mid-sequence match brute force", "[lab04][pts=2][sec=10]") {
  // The id interface: random adds, removals and moves, checked after every update
  IncrementalBroadPhase bp(randomCount(0, 1) ? 0.0 : IncrementalBroadPhase::kDefaultMargin);
  std::map<int, Aabb> live;
  std::vector<Aabb> scene = randomScene(400, BoxSizes::Uniform);
  PairList pairs;
  for (int step = 0; step < 30; ++step) {
    for (int op = 0; op < 40; ++op) {
      const double pick = uniform(0, 1);
      if (pick < 0.3 || live.empty()) {
        const Aabb b = scene[static_cast<std::size_t>(uniform(0, 400))];
        const int id = bp.add(b);
        REQUIRE(live.count(id) == 0);
        live[id] = b;
      } else {
        auto it = live.begin();
        std::advance(it, static_cast<long>(uniform(0, static_cast<double>(live.size()))));
        if (pick < 0.5) {
          bp.remove(it->first);
          live.erase(it);
        } else {
          const Vec3 d = uniform(0, 1) < 0.1 ? randomVec3(3.0) : randomVec3(0.1);
          it->second.min += d;
          it->second.max += d;
          bp.move(it->first, it->second);
        }
      }
    }
    bp.update(pairs);
    INFO("step " << step << ", " << live.size() << " boxes");
    CHECK_SAME_PAIRS(pairs, bruteForceIds(live));
    CHECK(bp.size() == static_cast<int>(live.size()));
  }
  CHECK_STRUCTURE(bp);
  // findPairs on scenes whose size changes: ids past the end go, new ones come
  IncrementalBroadPhase same;
  for (const int n : {50, 200, 120, 0, 7, 300}) {
    const std::vector<Aabb> boxes = randomScene(n, BoxSizes::Clustered);
    same.findPairs(boxes, pairs);
    INFO(n << " boxes");
    CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
    CHECK(same.size() == n);
    CHECK_STRUCTURE(same);
  }
}

TEST_CASE("incremental: an empty scene and a single box, then a second", "[lab04][pts=1][sec=10]") {
  IncrementalBroadPhase bp;
  PairList pairs = {{0, 1}};
  bp.findPairs({}, pairs);
  CHECK(pairs.empty());
  CHECK(bp.tree().height() == 0);
  bp.findPairs({cuboid(0, 0, 0, 1, 1, 1)}, pairs);
  CHECK(pairs.empty());
  CHECK(bp.tree().height() == 1);
  // A second box touching the first: one internal node above two leaves
  bp.findPairs({cuboid(0, 0, 0, 1, 1, 1), cuboid(1, 1, 1, 2, 2, 2)}, pairs);
  CHECK(pairs == PairList{{0, 1}});
  CHECK(bp.tree().height() == 2);
  CHECK_STRUCTURE(bp);
  bp.findPairs({}, pairs);
  CHECK(pairs.empty());
  CHECK(bp.size() == 0);
  CHECK_STRUCTURE(bp);
}

TEST_CASE("incremental: tree invariants, and a logarithmic height for sorted insertions", "[lab04][pts=2][sec=10]") {
  // A random sequence: every node encloses its children, heights are exact, the height stays
  // logarithmic (the reference's is about log2 n + 3; a tree without rotations drifts far deeper)
  std::vector<Aabb> boxes = randomScene(randomCount(100, 1500), BoxSizes::WideRange);
  IncrementalBroadPhase bp;
  PairList pairs;
  for (int step = 0; step < 5; ++step) {
    moveBoxes(boxes, 0.2);
    bp.findPairs(boxes, pairs);
    CHECK_STRUCTURE(bp);
  }
  const int levels = static_cast<int>(std::ceil(std::log2(static_cast<double>(boxes.size()))));
  CHECK(bp.tree().height() <= 2 * levels + 2);
  // 1024 disjoint boxes inserted in order along x: the cost-driven insertion alone pairs each new
  // box with the last one's subtree and makes a chain of 1024 levels; the rotations keep it within
  // about the AVL bound 1.44 log2(n) + 2 = 16 (the reference's is 11, the least possible).
  IncrementalBroadPhase line(0.0);
  for (int k = 0; k < 1024; ++k) line.add(cuboid(2 * k, 0, 0, 2 * k + 1, 1, 1));
  line.update(pairs);
  CHECK(pairs.empty());
  CHECK(line.tree().height() <= 16);
  CHECK_STRUCTURE(line);
}

TEST_CASE("incremental: the tree rotates where its subtrees' heights differ by more than one, not at one (hand-built, both sides)", "[lab04][pts=1][sec=10]") {
  // Unit cubes along x, inserted one by one into a bare DynamicAabbTree; each pairs with its
  // nearest box (the surface-area costs, worked out below, are far apart: no tie). The ids under
  // each child of the root give the shape.
  const auto idsUnder = [](const DynamicAabbTree& tree, int node) {
    std::vector<int> ids, stack = {node};
    while (!stack.empty()) {
      const Node& k = tree.nodes()[stack.back()];
      stack.pop_back();
      if (k.isLeaf()) {
        ids.push_back(k.id);
      } else {
        stack.push_back(k.child1);
        stack.push_back(k.child2);
      }
    }
    std::sort(ids.begin(), ids.end());
    return ids;
  };
  const auto rootSplit = [&](const DynamicAabbTree& tree) {
    const Node& root = tree.nodes()[tree.root()];
    std::vector<std::vector<int>> halves = {idsUnder(tree, root.child1), idsUnder(tree, root.child2)};
    std::sort(halves.begin(), halves.end());
    return halves;
  };
  using Split = std::vector<std::vector<int>>;
  // Growing to the right (the new leaf is always a second child): A = [0,1] (id 0), B = [2,3]
  // (id 1), C = [4,5] (id 2), D = [6,7] (id 3), all x [0,1]^2.
  {
    DynamicAabbTree tree;
    tree.insertLeaf(cuboid(0, 0, 0, 1, 1, 1), 0);
    tree.insertLeaf(cuboid(2, 0, 0, 3, 1, 1), 1);
    // C: the root costs 2 A([0,5]) = 44, A 16 + 22 = 38, B 16 + 14 = 30: C pairs with B. The root's
    // subtrees are then A (height 0) and (B, C) (height 1): differing by one, no rotation.
    tree.insertLeaf(cuboid(4, 0, 0, 5, 1, 1), 2);
    CHECK(rootSplit(tree) == Split{{0}, {1, 2}});
    CHECK(tree.height() == 3);
    // D pairs with C (the root 60, A 46, (B, C) 24; then (B, C) 44, B 38, C 30): the root's subtrees
    // are A (0) and (B, (C, D)) (2), differing by two: (B, (C, D)) rotates up, keeping (C, D), and
    // the old root takes B: ((A, B), (C, D)).
    tree.insertLeaf(cuboid(6, 0, 0, 7, 1, 1), 3);
    CHECK(rootSplit(tree) == Split{{0, 1}, {2, 3}});
    CHECK(tree.height() == 3);
  }
  // Growing to the left (the taller subtree is the root's first child): A = [0,1] (id 0),
  // B = [10,11] (id 1), C = [-2,-1] (id 2), D = [-4,-3] (id 3).
  {
    DynamicAabbTree tree;
    tree.insertLeaf(cuboid(0, 0, 0, 1, 1, 1), 0);
    tree.insertLeaf(cuboid(10, 0, 0, 11, 1, 1), 1);
    // C: the root 108, A 16 + 14 = 30, B 16 + 54 = 70: C pairs with A. Subtrees (A, C) (1) and B (0).
    tree.insertLeaf(cuboid(-2, 0, 0, -1, 1, 1), 2);
    CHECK(rootSplit(tree) == Split{{0, 2}, {1}});
    CHECK(tree.height() == 3);
    // D pairs with C (the root 124, (A, C) 24, B 78; then (A, C) 44, A 38, C 30): subtrees
    // (A, (C, D)) (2) and B (0): the first rotates up, and the old root takes A: ((A, B), (C, D)).
    tree.insertLeaf(cuboid(-4, 0, 0, -3, 1, 1), 3);
    CHECK(rootSplit(tree) == Split{{0, 1}, {2, 3}});
    CHECK(tree.height() == 3);
  }
}

TEST_CASE("incremental: the sibling is the one of least surface-area cost (hand-computed)", "[lab04][pts=1][sec=10]") {
  // Margin 0: fat = tight. Leaves A = [0,1]^3 (id 0) and B = [4,5]x[0,1]^2 (id 1) under a root
  // of area 2 (5 + 1 + 5) = 22.
  IncrementalBroadPhase bp(0.0);
  PairList pairs;
  bp.add(cuboid(0, 0, 0, 1, 1, 1));
  bp.add(cuboid(4, 0, 0, 5, 1, 1));
  bp.update(pairs);
  const DynamicAabbTree& tree = bp.tree();
  const auto leafOf = [&](int id) {
    for (int k = 0; k < static_cast<int>(tree.nodes().size()); ++k) {
      if (tree.nodes()[k].height == 0 && tree.nodes()[k].id == id) return k;
    }
    return DynamicAabbTree::kNull;
  };
  // L = [1,2]x[0,1]^2 is inside the root: pairing at the root costs 44, with A 10, with B 18
  CHECK(tree.pickSibling(cuboid(1, 0, 0, 2, 1, 1)) == leafOf(0));
  // L = [3.5,4.5]x[0,1]^2: with A 2 (4.5 + 1 + 4.5) = 20, with B 2 (1.5 + 1 + 1.5) = 8
  CHECK(tree.pickSibling(cuboid(3.5, 0, 0, 4.5, 1, 1)) == leafOf(1));
  // L = [-3,8]x[0,1]^2 spans both: the root costs 2 A(L) = 92, each leaf 2 (46 - 22) + 46 = 94
  CHECK(tree.pickSibling(cuboid(-3, 0, 0, 8, 1, 1)) == tree.root());
  // L = [0,1]^2 x [1,5], on top of A: the root costs 2 x 70 = 140, A 2 (70 - 22) + 22 = 118 and
  // B 96 + 70 = 166; the root is cheaper than one child only, so the search goes down to A
  CHECK(tree.pickSibling(cuboid(0, 0, 1, 1, 1, 5)) == leafOf(0));
  // Inserting [1,2]x[0,1]^2 makes it A's sibling: their parent has exactly these two children
  const int c = bp.add(cuboid(1, 0, 0, 2, 1, 1));
  bp.update(pairs);
  CHECK(pairs == PairList{{0, 2}});
  const Node& parent = tree.nodes()[tree.nodes()[leafOf(c)].parent];
  CHECK(((parent.child1 == leafOf(0) && parent.child2 == leafOf(c)) ||
         (parent.child1 == leafOf(c) && parent.child2 == leafOf(0))));
  CHECK(sameBox(parent.box, cuboid(0, 0, 0, 2, 1, 1)));
}

TEST_CASE("incremental: an unmoved scene reinserts nothing, small moves inside the margin neither", "[lab04][pts=1][sec=10]") {
  std::vector<Aabb> boxes = randomScene(randomCount(100, 1500), BoxSizes::Uniform);
  IncrementalBroadPhase bp(0.1);
  PairList pairs;
  bp.findPairs(boxes, pairs);
  const PairList first = pairs;
  bp.findPairs(boxes, pairs);
  CHECK(bp.reinsertions() == 0);
  CHECK(pairs == first);
  // Every box moves by at most 0.05 per axis: inside the 0.1 margin, nothing reinserted
  for (Aabb& b : boxes) {
    const Vec3 d = randomVec3(0.05);
    b.min += d;
    b.max += d;
  }
  bp.findPairs(boxes, pairs);
  CHECK(bp.reinsertions() == 0);
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
  // Every third box moves 0.25 on x: exactly those are reinserted
  long moved = 0;
  for (std::size_t i = 0; i < boxes.size(); i += 3, ++moved) {
    boxes[i].min.x() += 0.25;
    boxes[i].max.x() += 0.25;
  }
  bp.findPairs(boxes, pairs);
  CHECK(bp.reinsertions() == moved);
  CHECK_SAME_PAIRS(pairs, bruteForcePairs(boxes));
}

TEST_CASE("incremental: bad input is refused by name and leaves the scene as it was", "[lab04][pts=1][sec=10]") {
  IncrementalBroadPhase bp;
  PairList pairs;
  bp.add(cuboid(0, 0, 0, 1, 1, 1));
  bp.add(cuboid(1, 0, 0, 2, 1, 1));
  bp.add(cuboid(5, 5, 5, 6, 6, 6));
  bp.update(pairs);
  REQUIRE(pairs == PairList{{0, 1}});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(bp.add(cuboid(0, nan, 0, 1, 1, 1)), Contains("non-finite") && Contains("y axis"));
  CHECK_THROWS_WITH(bp.move(1, cuboid(2, 0, 0, 1, 1, 1)), Contains("id 1") && Contains("min > max") && Contains("x axis"));
  CHECK_THROWS_WITH(bp.move(7, cuboid(0, 0, 0, 1, 1, 1)), Contains("unknown box id 7"));
  CHECK_THROWS_WITH(bp.remove(-1), Contains("unknown box id -1"));
  bp.remove(2);
  CHECK_THROWS_WITH(bp.remove(2), Contains("unknown box id 2"));
  CHECK_THROWS_WITH(bp.fatBox(2), Contains("unknown box id 2"));
  CHECK_THROWS_WITH(IncrementalBroadPhase(-0.1), Contains("margin"));
  CHECK_THROWS_WITH(bp.findPairs({cuboid(0, 0, 0, 1, 1, std::numeric_limits<double>::infinity())}, pairs),
                    Contains("box 0") && Contains("non-finite"));
  // Nothing refused changed the scene
  bp.update(pairs);
  CHECK(pairs == PairList{{0, 1}});
  CHECK(bp.size() == 2);
  CHECK_STRUCTURE(bp);
  // findPairs checks the boxes in its own pass: a box turned inside out within its fat box and a
  // NaN are refused by index and axis, and the boxes of the last call stay
  const std::vector<Aabb> scene = {cuboid(0, 0, 0, 1, 1, 1), cuboid(1, 0, 0, 2, 1, 1), cuboid(3, 0, 0, 4, 1, 1)};
  IncrementalBroadPhase again;
  again.findPairs(scene, pairs);
  std::vector<Aabb> bad = scene;
  std::swap(bad[1].min.y(), bad[1].max.y());
  CHECK_THROWS_WITH(again.findPairs(bad, pairs), Contains("box 1") && Contains("min > max") && Contains("y axis"));
  bad = scene;
  bad[2].max.z() = nan;
  CHECK_THROWS_WITH(again.findPairs(bad, pairs), Contains("box 2") && Contains("non-finite") && Contains("z axis"));
  CHECK(sameBox(again.tightBox(1), scene[1]));
  again.update(pairs);
  CHECK(pairs == PairList{{0, 1}});
}
