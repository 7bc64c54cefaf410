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
///
/// (k: pairs found; k_x: pairs whose intervals overlap on the sweep axis.)
///
/// The objects are meant to be kept and reused: they hold their working memory between calls and
/// write into a caller's PairList, so that a world stepping many bodies allocates nothing per
/// step once the buffers have grown. Their public entry points (in common/) validate the boxes
/// and throw InvalidInput for a box with min > max or a non-finite coordinate.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "physlab/math.hpp"

namespace physlab {

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
  /// The method itself: `boxes` are valid, `pairs` is empty.
  virtual void computePairs(const std::vector<Aabb>& boxes, PairList& pairs) = 0;
  /// The one box-box test every method uses: counts the test, then calls overlaps().
  bool test(const Aabb& a, const Aabb& b) {
    ++tests_;
    return overlaps(a, b);
  }
  /// Sets the test counter to zero (the public entry points call it before each query).
  void resetTests() { tests_ = 0; }

 private:
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

  std::vector<int> lists_;     ///< box lists of the nodes on the current path, back to back
  std::vector<double> keys_;   ///< scratch for the median
  long leaves_ = 0;
};

/// One object of every broad phase, brute force first, in the order the charts and tables use.
std::vector<std::unique_ptr<BroadPhase>> allBroadPhases();

}  // namespace physlab
