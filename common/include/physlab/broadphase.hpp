/// \file broadphase.hpp
/// \brief Lab 4 broad phase: axis-aligned bounding boxes and the structures that find which of
/// them overlap.
///
/// Every broad phase answers the same question: given n boxes, which pairs (i, j) overlap? The
/// answer is exact (no pair missed, none extra), lists each pair once with i < j, and is sorted
/// lexicographically, so any two methods can be compared with `==`. Boxes that only touch (a
/// shared face, edge or corner) overlap. The brute-force test of all n(n-1)/2 pairs is the
/// oracle; the others find the same set faster by not testing pairs that cannot overlap:
///
/// | class | idea | cost per query |
/// |---|---|---|
/// | BruteForce | test every pair | O(n^2) |
/// | SweepAndPrune | sort the intervals on one axis, sweep | O(n log n + k_x), O(n + swaps) on update |
/// | UniformGrid | hash each box into the cells it covers | O(n + k) for similar sizes |
/// | Bvh | a tree of bounding boxes, one query per box | O(n log n + k) |
/// | KdTree | split space at median planes until few boxes remain | O(n log n + k) |
/// | IncrementalBroadPhase | a dynamic tree of enlarged boxes, pairs kept between steps | O(m log n + k_f) per step |
///
/// (k: pairs found; k_x: pairs whose intervals overlap on the sweep axis; m: boxes that left
/// their enlarged box since the last step; k_f: pairs whose enlarged boxes overlap.)
///
/// The objects are meant to be kept and reused: they hold their working memory between calls and
/// write into a caller's PairList, so that a world stepping many bodies allocates nothing per
/// step once the buffers have grown. Their public entry points (in common/) validate the boxes
/// and throw InvalidInput for a box with min > max or a non-finite coordinate.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "physlab/math.hpp"

namespace physlab {

namespace remote {
template <int>
struct Access;  // the grader's wire (tests/support/remote): what crosses to a grading worker
}  // namespace remote

/// An axis-aligned bounding box in the world frame [m]: the points p with min <= p <= max
/// component-wise. Boxes that only touch (a shared face, edge or corner) overlap.
struct Aabb {
  Vec3 min;  ///< lower corner, world frame [m]
  Vec3 max;  ///< upper corner, world frame [m]
};

/// A pair of box indices (i, j) with i < j.
using BoxPair = std::pair<int, int>;
/// The answer of a broad phase: overlapping pairs, i < j in each, sorted lexicographically.
using PairList = std::vector<BoxPair>;

/// True when the boxes share at least one point: their intervals overlap on all three axes,
/// touching included.
inline bool overlaps(const Aabb& a, const Aabb& b) {
  return a.min.x() <= b.max.x() && b.min.x() <= a.max.x() &&  //
         a.min.y() <= b.max.y() && b.min.y() <= a.max.y() &&  //
         a.min.z() <= b.max.z() && b.min.z() <= a.max.z();
}

/// The smallest box holding both a and b.
inline Aabb enclose(const Aabb& a, const Aabb& b) {
  return {a.min.cwiseMin(b.min), a.max.cwiseMax(b.max)};
}

/// Throws InvalidInput naming the first bad box: a non-finite coordinate, or min > max on an axis.
/// A box with min == max on every axis (a point) is valid.
void requireValidBoxes(const std::vector<Aabb>& boxes);

/// Common interface of the broad phases, so that a world can hold any of them.
class BroadPhase {
 public:
  virtual ~BroadPhase() = default;
  /// Writes the overlapping pairs of `boxes` to `pairs` (cleared first; i < j, sorted).
  /// Validates the boxes first (InvalidInput). Subclasses say what they reuse between calls.
  void findPairs(const std::vector<Aabb>& boxes, PairList& pairs);
  /// The method's name, for tables and charts.
  virtual std::string name() const = 0;
  /// How many box-box overlap tests the last query made (a measure of work, not of time).
  long overlapTests() const { return tests_; }

 protected:
  /// The method itself: `boxes` are valid (unless validate() is overridden), `pairs` is empty.
  virtual void computePairs(const std::vector<Aabb>& boxes, PairList& pairs) = 0;
  /// Checks the boxes before computePairs(): requireValidBoxes(). A method that checks them in a
  /// pass of its own overrides it with nothing, and must throw before it changes any state.
  virtual void validate(const std::vector<Aabb>& boxes) { requireValidBoxes(boxes); }
  /// The one box-box test every method uses: counts the test, then calls overlaps().
  bool test(const Aabb& a, const Aabb& b) {
    ++tests_;
    return overlaps(a, b);
  }
  /// Sets the test counter to zero (the public entry points call it before each query).
  void resetTests() { tests_ = 0; }
  /// Adds `count` box-box tests made without test() (a loop that tests without branching).
  void countTests(long count) { tests_ += count; }

 private:
  template <int>
  friend struct remote::Access;  // the grader sends the test count with a broad phase's state
  long tests_ = 0;
};

/// The oracle: tests all n(n-1)/2 pairs, in order, so its output is sorted as it is produced.
class BruteForce final : public BroadPhase {
 public:
  std::string name() const override { return "brute force"; }

 protected:
  void computePairs(const std::vector<Aabb>& boxes, PairList& pairs) override;
};

/// Sort and sweep (sweep and prune) along one axis, with an incremental update.
///
/// build() picks the axis along which the box centres spread most, sorts the boxes by the lower
/// endpoint of their interval on it, and sweeps: box a, then every later box b whose lower
/// endpoint is at most a's upper endpoint, is a candidate, tested on all three axes. update()
/// keeps the axis and the sorted order of the last call, copies the moved boxes in and restores
/// the order with insertion sort: when the boxes move little between calls (temporal coherence)
/// the list is nearly sorted and this costs O(n + swaps) instead of O(n log n).
/// findPairs() builds on the first call and whenever the number of boxes changes, and updates
/// otherwise.
class SweepAndPrune final : public BroadPhase {
 public:
  /// One box in the sweep list: its bounds (copied, so that the sweep reads memory in order)
  /// and its index. The list is sorted by `bounds.min[axis]`, the interval's lower endpoint.
  struct Entry {
    Aabb bounds;  ///< the box, world frame [m]
    int box;      ///< its index in the caller's vector
  };

  std::string name() const override { return "sort and sweep"; }
  /// Chooses the axis, sorts from scratch and sweeps. Throws InvalidInput on bad boxes.
  void build(const std::vector<Aabb>& boxes, PairList& pairs);
  /// Re-sorts the previous order by insertion sort and sweeps. Throws InvalidInput on bad boxes
  /// or when the number of boxes differs from the last build's.
  void update(const std::vector<Aabb>& boxes, PairList& pairs);
  /// The sweep axis (0 = x, 1 = y, 2 = z) chosen by the last build.
  int axis() const { return axis_; }
  /// How many adjacent swaps the last update's insertion sort made (0 after a build).
  long swaps() const { return swaps_; }
  /// The sorted list, for tests and drawing.
  const std::vector<Entry>& entries() const { return entries_; }

 protected:
  void computePairs(const std::vector<Aabb>& boxes, PairList& pairs) override;

 private:
  /// Student: choose axis_, fill entries_ and sort it by lower endpoint.
  void sortEntries(const std::vector<Aabb>& boxes);
  /// Student: copy the new bounds into entries_ in their current order, restore the order by
  /// insertion sort and return the number of swaps.
  long insertionSortEntries(const std::vector<Aabb>& boxes);
  /// Student: sweep the sorted entries_ and write the sorted pairs.
  void sweep(PairList& pairs);
  template <int>
  friend struct remote::Access;  // the grader sends the state and calls the student's functions remotely

  std::vector<Entry> entries_;
  int axis_ = 0;
  long swaps_ = 0;
};

/// A uniform grid of cubic cells of edge h, stored in a hash table (the cells of an unbounded
/// space, only those a box covers are ever touched).
///
/// Cell size: h = 2 x the median over the boxes of their longest edge, so that a typical box
/// covers at most 2 cells per axis (8 in all); the median ignores a few huge boxes. The median of
/// n edges is the one at index n / 2 (integer division) in increasing order, the upper of the two
/// middle ones when n is even. If that is 0 (more than half the boxes are points), h = 1 m. A box that would cover more than kMaxCellsPerAxis cells
/// along some axis is "oversized": it skips the grid and is tested against every other box.
/// Each pair is reported once, by the cell that holds the lower corner of the pair's
/// intersection max(min_a, min_b), which lies in a cell both boxes cover.
class UniformGrid final : public BroadPhase {
 public:
  /// A box that spans more cells than this along some axis is tested against all boxes instead.
  static constexpr long kMaxCellsPerAxis = 4;

  std::string name() const override { return "uniform grid"; }
  /// The cell edge h [m] used by the last query.
  double cellSize() const { return cell_size_; }

 protected:
  /// Fills the hash table and walks each bucket; reuses its tables between calls.
  void computePairs(const std::vector<Aabb>& boxes, PairList& pairs) override;

 private:
  /// Student: set cell_size_ by the rule above (edges_ is scratch for the median).
  void chooseCellSize(const std::vector<Aabb>& boxes);
  template <int>
  friend struct remote::Access;  // the grader sends the state and calls the student's functions remotely

  /// One box's presence in one cell: the cell's integer coordinates and the box index.
  struct CellEntry {
    int ix, iy, iz;  ///< integer cell coordinates floor(p / h), clamped to +-10^9
    int box;         ///< index in the caller's vector
  };
  std::vector<int> bucket_start_;      ///< prefix sums: bucket b holds cell_entries_[start[b], start[b+1])
  std::vector<CellEntry> cell_entries_;  ///< every (cell, box), grouped by bucket
  std::vector<int> oversized_;           ///< boxes tested against all others
  std::vector<char> is_oversized_;       ///< per box, 1 when oversized
  std::vector<double> edges_;            ///< scratch for the median edge
  double cell_size_ = 1.0;
};

/// A bounding volume hierarchy: a binary tree whose leaves hold up to kLeafSize boxes and whose
/// nodes hold the box enclosing their subtree.
///
/// Build (top down): a node's boxes are split at the median of their centres along the longest
/// axis of the centres' bounds (an object-median split: balanced, no
/// cost estimate; the surface area heuristic gives tighter trees at a higher build cost). The
/// depth is 1 + the number of halvings from n to kLeafSize, about log2(n / kLeafSize) + 1.
/// Query: each box i descends from the root into every child whose bounds it overlaps and
/// reports the boxes j > i of the leaves it reaches. Refit: after the boxes move, leaf bounds
/// and then every parent's are recomputed bottom-up without changing the tree; the answer stays
/// exact, only the pruning gets worse as the tree stops matching the boxes.
/// findPairs() rebuilds on every call; a caller whose boxes move little calls refit().
class Bvh final : public BroadPhase {
 public:
  /// Largest number of boxes in a leaf.
  static constexpr int kLeafSize = 4;
  /// A node: bounds, and either two children (internal) or a range of order() (leaf).
  /// Nodes are stored in pre-order, so a child's index is always larger than its parent's.
  struct Node {
    Aabb bounds;     ///< box enclosing every box below, world frame [m]
    int left = -1;   ///< index of the left child, -1 in a leaf
    int right = -1;  ///< index of the right child, -1 in a leaf
    int first = 0;   ///< leaf: first position in order()
    int count = 0;   ///< leaf: number of boxes (0 in an internal node)
  };

  std::string name() const override { return "BVH"; }
  /// Builds the tree from scratch and queries it. Throws InvalidInput on bad boxes.
  void build(const std::vector<Aabb>& boxes, PairList& pairs);
  /// Refits the last tree to moved boxes and queries it. Throws InvalidInput on bad boxes or
  /// when the number of boxes differs from the last build's.
  void refit(const std::vector<Aabb>& boxes, PairList& pairs);
  /// The nodes, root first (empty before the first build or for no boxes).
  const std::vector<Node>& nodes() const { return nodes_; }
  /// Box indices in leaf order.
  const std::vector<int>& order() const { return order_; }
  /// Number of nodes on the longest root-to-leaf path (1 for a single leaf, 0 for no boxes).
  int depth() const;

 protected:
  void computePairs(const std::vector<Aabb>& boxes, PairList& pairs) override;

 private:
  /// Student: build nodes_ and order_ top down from scratch.
  void buildTree(const std::vector<Aabb>& boxes);
  /// Student: recompute every node's bounds from the moved boxes, children before parents.
  void refitTree(const std::vector<Aabb>& boxes);
  /// Student: query the tree with every box and write the sorted pairs.
  void queryAll(const std::vector<Aabb>& boxes, PairList& pairs);
  /// Student helper: makes the node for order_[first, last) and its subtree; returns its index.
  int buildNode(const std::vector<Aabb>& boxes, int first, int last);
  template <int>
  friend struct remote::Access;  // the grader sends the state and calls the student's functions remotely

  std::vector<Node> nodes_;
  std::vector<int> order_;
  std::vector<int> stack_;  ///< traversal stack, kept between queries
};

/// A k-d tree over space: each node splits its region in two at a plane x_axis = s, along the
/// axis where its boxes' centres spread most, at their median. A box goes to every child its
/// interval reaches (left if min < s, right if max >= s), so a box crossing a plane is in both.
/// Leaves test their boxes pairwise and report a pair only if the lower corner of its
/// intersection, max(min_a, min_b), lies in the leaf's half-open region: exactly one leaf does.
///
/// A node becomes a leaf when it holds at most kLeafSize boxes, when it is kMaxDepth deep, or
/// when splitting would not pay: one child would get every box, or the children together would
/// hold more than 1.5 times as many (most boxes cross the plane). The tree is built and walked
/// in one depth-first pass; only its working lists are kept between calls.
class KdTree final : public BroadPhase {
 public:
  /// A node with at most this many boxes is a leaf.
  static constexpr int kLeafSize = 8;
  /// Nodes this deep are leaves.
  static constexpr int kMaxDepth = 32;

  std::string name() const override { return "k-d tree"; }
  /// Number of leaves the last query visited.
  long leafCount() const { return leaves_; }

 protected:
  void computePairs(const std::vector<Aabb>& boxes, PairList& pairs) override;

 private:
  /// Student: the node whose boxes are lists_[begin, end) and whose region is [lo, hi): split it
  /// or test it as a leaf. The children's lists are appended to lists_ and dropped after use.
  void visit(const std::vector<Aabb>& boxes, std::size_t begin, std::size_t end, const Vec3& lo,
             const Vec3& hi, int depth, PairList& pairs);
  template <int>
  friend struct remote::Access;  // the grader sends the state and calls the student's functions remotely

  std::vector<int> lists_;     ///< box lists of the nodes on the current path, back to back
  std::vector<double> keys_;   ///< scratch for the median
  long leaves_ = 0;
};

/// The surface area 2 (dx dy + dy dz + dz dx) of a box [m^2]: the cost measure of the dynamic
/// tree (the chance that a random ray or box hits it grows with its area).
inline double surfaceArea(const Aabb& b) {
  const Vec3 d = b.max - b.min;
  return 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
}

/// A dynamic AABB tree (Lab 4, section 10): a binary tree whose leaves hold one box each and
/// whose internal nodes hold the box enclosing their two children, kept balanced while leaves
/// come and go one at a time (no rebuild).
///
/// Insertion: pickSibling() walks down from the root to the node whose pairing with the new
/// leaf adds least surface area to the tree (greedy descent, below); a new internal node takes
/// that sibling's place with the sibling and the leaf as children; refitUpward() then walks from
/// the new node to the root, rotating where the two subtrees' heights differ by more than one
/// and refitting boxes and heights. Removal: the leaf's parent is replaced by the leaf's
/// sibling, and refitUpward() runs from the grandparent.
///
/// Greedy descent at an internal node N with children C1, C2, for a new box L: pairing L with N
/// itself costs 2 A(N u L) (a new parent of that area) and every step deeper adds the
/// "inheritance" 2 (A(N u L) - A(N)) paid by N's enlargement. Descending into a child C costs the
/// inheritance plus A(C u L) if C is a leaf, or A(C u L) - A(C) if not (a lower bound on what a
/// pairing below C would add). Stop at N when it is strictly cheaper than both children, else go
/// to the cheaper child (C1 on a tie).
///
/// Nodes live in one pool (a vector) and are addressed by index; freed nodes are chained in a
/// free list and reused, so a tree of steady size allocates nothing.
class DynamicAabbTree {
 public:
  /// The index that means "no node".
  static constexpr int kNull = -1;
  /// A node of the pool.
  struct Node {
    Aabb box{Vec3::Zero(), Vec3::Zero()};  ///< leaf: the stored box; internal: encloses both children [m]
    int parent = kNull;   ///< kNull at the root (in a free node: the next free node)
    int child1 = kNull;   ///< first child, kNull in a leaf
    int child2 = kNull;   ///< second child, kNull in a leaf
    int height = -1;      ///< 0 for a leaf, 1 + the larger child's height inside, -1 when free
    int id = kNull;       ///< leaf: the caller's id for the box
    /// True for a leaf (and for a free node).
    bool isLeaf() const { return child1 == kNull; }
  };

  /// Inserts a leaf holding `box` (valid, not checked here) and `id`; returns the leaf's node.
  int insertLeaf(const Aabb& box, int id);
  /// Removes a leaf made by insertLeaf() and frees it and its parent.
  void removeLeaf(int leaf);
  /// Removes everything (the pool's memory is kept).
  void clear();
  /// The root's node, kNull when empty.
  int root() const { return root_; }
  /// The pool: every node ever allocated, free ones with height -1.
  const std::vector<Node>& nodes() const { return nodes_; }
  /// Number of leaves.
  int leafCount() const { return leaves_; }
  /// Number of nodes on the longest root-to-leaf path: 0 when empty, 1 for a single leaf.
  int height() const { return root_ == kNull ? 0 : nodes_[static_cast<std::size_t>(root_)].height + 1; }
  /// Student: the node the greedy descent by surface-area cost (above) pairs `box` with. The
  /// tree must not be empty.
  int pickSibling(const Aabb& box) const;
  /// Calls visit(id) for every leaf whose box overlaps `box` (touching included).
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) {
    if (root_ == kNull) return;
    stack_.clear();
    stack_.push_back(root_);
    while (!stack_.empty()) {
      const Node& node = nodes_[static_cast<std::size_t>(stack_.back())];
      stack_.pop_back();
      if (!overlaps(box, node.box)) continue;
      if (node.isLeaf()) {
        visit(node.id);
      } else {
        stack_.push_back(node.child1);
        stack_.push_back(node.child2);
      }
    }
  }

 private:
  /// Student: walks from `node` to the root; at each node first balance() it, then recompute
  /// its box (enclosing its children) and its height, then go on from its parent.
  void refitUpward(int node);
  /// Student: if the heights of a's children differ by more than 1, rotates the taller child C
  /// up into a's place: C keeps its taller child, a takes C's shorter child instead of C, and
  /// the boxes and heights of a and C are recomputed. Returns the node now at a's place
  /// (a itself when nothing rotated, or when a is a leaf).
  int balance(int a);
  int allocateNode();
  void freeNode(int node);
  template <int>
  friend struct remote::Access;  // the grader sends the state and calls the student's functions remotely

  std::vector<Node> nodes_;
  std::vector<int> stack_;  ///< query stack, kept between queries
  int root_ = kNull;
  int free_ = kNull;  ///< first free node, chained through Node::parent
  int leaves_ = 0;
};

/// An incremental broad phase for moving scenes (Lab 4, section 10): each box is stored in a
/// DynamicAabbTree enlarged to a "fat" box, and the pairs whose fat boxes overlap are kept
/// between steps, so a step only redoes the work for boxes that left their fat box.
///
/// Fat box: when a box is added, or moved outside its fat box, its fat box is set to the tight
/// box grown by `margin` on every side and, along each axis, further by the box's displacement
/// d since its last move on the side it moves to (min + min(d, 0), max + max(d, 0)): a box moving
/// steadily by less than the margin per step leaves its fat box rarely. A box whose new tight
/// box is still inside its fat box (touching the fat box's faces included) changes nothing in
/// the tree.
///
/// The pair set: sorted, every pair (i < j) of live boxes whose fat boxes overlap. update()
/// drops the pairs of boxes moved out of their fat boxes (or added, or removed) since the last
/// update, queries the tree with the new fat box of each such box, merges the new pairs in, and
/// reports the pairs of the set whose TIGHT boxes overlap, sorted: the brute force's answer.
/// A tight overlap implies a fat one (tight is inside fat), so no pair is missed.
///
/// The id interface (add/remove/move/update) is the engine's; findPairs(boxes) treats box i as
/// id i, adding and removing ids when the number of boxes changes. Buffers are kept, so a step
/// of a scene of steady size allocates nothing. overlapTests() counts the tight-box tests of the
/// last update (the tree's queries are not counted).
class IncrementalBroadPhase final : public BroadPhase {
 public:
  /// The default margin [m]: 5 cm, for boxes of decimetres to metres moving centimetres per step.
  static constexpr double kDefaultMargin = 0.05;

  /// Throws InvalidInput unless `margin` is finite and >= 0.
  explicit IncrementalBroadPhase(double margin = kDefaultMargin);
  std::string name() const override { return "incremental AABB tree"; }

  /// Adds a box and returns its id: the most recently removed id if any, else the next unused.
  /// Throws InvalidInput on a box with min > max or a non-finite coordinate.
  int add(const Aabb& box);
  /// Removes the box `id`. Throws InvalidInput if `id` is not a live box.
  void remove(int id);
  /// Sets the tight box of `id`; reinserts it with a new fat box if it left its fat box.
  /// Throws InvalidInput on an unknown id or a bad box.
  void move(int id, const Aabb& box);
  /// Brings the pair set up to date and writes the pairs of ids whose tight boxes overlap
  /// (i < j, sorted) to `pairs`.
  void update(PairList& pairs);
  /// Removes every box (memory kept).
  void clear();

  /// The margin [m].
  double margin() const { return margin_; }
  /// Number of live boxes.
  int size() const { return static_cast<int>(tight_.size() - free_ids_.size()); }
  /// True when `id` is a live box.
  bool contains(int id) const;
  /// The tight box of a live id, as last given [m].
  const Aabb& tightBox(int id) const;
  /// The fat box of a live id, as stored in the tree [m].
  const Aabb& fatBox(int id) const;
  /// How many reinsertions (boxes that left their fat box) the moves before the last update made.
  long reinsertions() const { return last_reinsertions_; }
  /// Number of pairs whose fat boxes overlap (the kept pair set) after the last update.
  long fatPairs() const { return static_cast<long>(pair_set_.size()); }
  /// The tree, for tests and drawing.
  const DynamicAabbTree& tree() const { return tree_; }
  /// Calls visit(id) for every live id whose fat box overlaps `box` (touching included): the
  /// World's continuous collision finds what a fast body's sweep may reach this way.
  template <class Visit>
  void query(const Aabb& box, Visit&& visit) {
    tree_.query(box, visit);
  }

 protected:
  /// Box i is id i: removes ids >= boxes.size(), adds missing ones, moves the rest, updates.
  /// Checks the boxes itself, in the read-only pass that finds the boxes leaving their fat box.
  void computePairs(const std::vector<Aabb>& boxes, PairList& pairs) override;
  /// Nothing: computePairs() checks the boxes before it changes anything.
  void validate(const std::vector<Aabb>& /*boxes*/) override {}

 private:
  void requireLive(int id, const char* what) const;
  int insertProxy(int id, const Aabb& box);
  void moveValid(int id, const Aabb& box);
  void markDirty(int id);
  Aabb fatten(const Aabb& box, const Vec3& displacement) const;
  template <int>
  friend struct remote::Access;  // in a grade, computePairs() runs in the worker: the state crosses

  double margin_;
  DynamicAabbTree tree_;
  std::vector<Aabb> tight_, fat_;  ///< per id
  std::vector<int> leaf_;          ///< per id: its leaf node, kNull when the id is free
  std::vector<char> dirty_;        ///< per id: 1 when its pairs must be redone at the next update
  std::vector<int> dirty_list_;    ///< the ids with dirty_ set
  std::vector<int> free_ids_;      ///< removed ids, reused last first
  std::vector<int> leaving_;       ///< computePairs: ids whose box left its fat box, or new ones
  std::vector<std::uint64_t> pair_set_, kept_, found_;  ///< pairs as (i << 32) | j, sorted
  long reinsertions_ = 0, last_reinsertions_ = 0;
};

/// One object of every broad phase, brute force first, in the order the charts and tables use.
std::vector<std::unique_ptr<BroadPhase>> allBroadPhases();

}  // namespace physlab
