// Lab 4, section 1: broad phase - sort and sweep, a hashed uniform grid, a bounding volume
// hierarchy and a k-d tree. Each finds exactly the pairs the brute-force oracle finds.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "physlab/broadphase.hpp"
#include "physlab/error.hpp"

namespace physlab {

// ---------------------------------------------------------------------------------------------
// Sort and sweep (section 1.1)

void SweepAndPrune::sortEntries(const std::vector<Aabb>& boxes) {
  // Choose the axis along which the box centres spread most
  // TODO(student): centre c = (min + max) / 2; sum (c - mean)^2 per axis; axis_ = index of the largest (Vec3::maxCoeff(&i)).
  // Copy the boxes into the list and sort it by lower endpoint
  // TODO(student): entries_[i] = {boxes[i], i}; std::sort by bounds.min[axis_].
  notImplemented("SweepAndPrune::sortEntries", "Lab 4 handout, section 1.1", boxes);
}

long SweepAndPrune::insertionSortEntries(const std::vector<Aabb>& boxes) {
  // Copy the moved boxes in, keeping the previous order
  // TODO(student): for each entry e, e.bounds = boxes[e.box].
  // Sink each entry past the larger lower endpoints before it; a nearly sorted list costs O(n)
  // TODO(student): insertion sort on bounds.min[axis_] with a strict > (equal keys stay put); count and return the moves.
  notImplemented("SweepAndPrune::insertionSortEntries", "Lab 4 handout, section 1.1", boxes);
}

void SweepAndPrune::sweep(PairList& pairs) {
  // Test every later box whose interval starts before this one's ends (touching included)
  // TODO(student): for entry k, scan m = k+1, ... while entries_[m].bounds.min[axis_] <= entries_[k].bounds.max[axis_]; if test(...) add (min, max) of the two indices.
  // Sort the pairs: the sweep finds them in axis order, not index order
  // TODO(student): std::sort(pairs.begin(), pairs.end()).
  notImplemented("SweepAndPrune::sweep", "Lab 4 handout, section 1.1", pairs);
}

// ---------------------------------------------------------------------------------------------
// Hashed uniform grid (section 1.2)

void UniformGrid::chooseCellSize(const std::vector<Aabb>& boxes) {
  // Take the median over the boxes of their longest edge
  // TODO(student): edges_[i] = (max - min).maxCoeff(); std::nth_element at edges_.size() / 2 (no boxes: median 0).
  // Make a cell twice that, or 1 m when the typical box is a point
  // TODO(student): cell_size_ = median > 0 ? 2 * median : 1.0.
  notImplemented("UniformGrid::chooseCellSize", "Lab 4 handout, section 1.2", boxes);
}

void UniformGrid::computePairs(const std::vector<Aabb>& boxes, PairList& pairs) {
  // Find each box's cell range; set aside the boxes that cover too many cells
  // TODO(student): call chooseCellSize first; cell of x is floor(x / h) (clamp it to +-1e9 before converting to int); more than kMaxCellsPerAxis cells on an axis -> oversized_.
  // Size the hash table to twice the number of (cell, box) entries, a power of two
  // TODO(student): count the entries of the other boxes; buckets = smallest power of two >= 2 * count; hash (ix, iy, iz) with three large odd multipliers, XOR, & (buckets - 1).
  // Count the entries per bucket, then place them (a counting sort by bucket)
  // TODO(student): bucket_start_ holds prefix sums of the counts; cell_entries_[...] = {ix, iy, iz, box}.
  // Placing advanced each start to the next bucket's: shift back by one bucket
  // TODO(student): or keep a separate cursor per bucket - but reuse members, do not allocate per call.
  // Test the boxes sharing a cell; keep a pair only in the cell of its intersection's lower corner
  // TODO(student): two entries of a bucket with equal (ix, iy, iz): if test(A, B) and the cell of A.min.cwiseMax(B.min) is this cell, add the pair.
  // Test each oversized box against every other box (two oversized boxes once)
  // TODO(student): skip j == o, and oversized j < o (that pair is found from j).
  // Sort the pairs
  // TODO(student): std::sort(pairs.begin(), pairs.end()).
  notImplemented("UniformGrid::computePairs", "Lab 4 handout, section 1.2", boxes, pairs);
}

// ---------------------------------------------------------------------------------------------
// Bounding volume hierarchy (section 1.3)

void Bvh::buildTree(const std::vector<Aabb>& boxes) {
  // Start from all boxes in input order and an empty tree
  // TODO(student): nodes_.clear(); order_ = 0, 1, ..., n-1 (std::iota).
  // Build the root and, recursively, everything below it
  // TODO(student): if there are boxes, buildNode(boxes, 0, n).
  notImplemented("Bvh::buildTree", "Lab 4 handout, section 1.3", boxes);
}

int Bvh::buildNode(const std::vector<Aabb>& boxes, int first, int last) {
  // Enclose the node's boxes, and find the bounds of their centres
  // TODO(student): index = nodes_.size(); nodes_.emplace_back(); bounds = enclose(...) over boxes[order_[first..last)].
  // Make a leaf when few boxes remain
  // TODO(student): last - first <= kLeafSize: set first and count, return index.
  // Split at the median centre along the longest axis of the centres' bounds
  // TODO(student): mid = (first + last) / 2; std::nth_element on order_ comparing min[axis] + max[axis].
  // Build the two halves; pre-order puts the left child right after its parent
  // TODO(student): left = buildNode(first, mid), right = buildNode(mid, last); store them through nodes_[index] only after both calls (nodes_ grows).
  notImplemented("Bvh::buildNode", "Lab 4 handout, section 1.3", boxes, first, last);
}

void Bvh::refitTree(const std::vector<Aabb>& boxes) {
  // Visit the nodes backwards: in pre-order every child comes after its parent
  // TODO(student): for k = nodes_.size() - 1 down to 0.
  // Re-enclose a leaf's boxes
  // TODO(student): bounds = enclose of boxes[order_[first .. first + count)].
  // Enclose an internal node's two refitted children
  // TODO(student): bounds = enclose(nodes_[left].bounds, nodes_[right].bounds).
  notImplemented("Bvh::refitTree", "Lab 4 handout, section 1.3", boxes);
}

void Bvh::queryAll(const std::vector<Aabb>& boxes, PairList& pairs) {
  // Descend from the root into every node whose bounds the box overlaps
  // TODO(student): for each box i: stack_ = {0}; pop a node; skip it unless test(box, node.bounds); push both children.
  // Report the leaf's later boxes that overlap (j > i: each pair once)
  // TODO(student): j = order_[p] for p in the leaf's range; if j > i && test(box, boxes[j]) add (i, j).
  // Sort box i's partners: boxes in increasing i then give the whole list sorted
  // TODO(student): std::sort over the pairs added for this i only.
  notImplemented("Bvh::queryAll", "Lab 4 handout, section 1.3", boxes, pairs);
}

// ---------------------------------------------------------------------------------------------
// k-d tree (section 1.4)

void KdTree::computePairs(const std::vector<Aabb>& boxes, PairList& pairs) {
  // Start at the root: every box, and all of space as the region
  // TODO(student): leaves_ = 0; lists_ = 0, 1, ..., n-1; visit(boxes, 0, n, -infinity, +infinity, 0, pairs).
  // Sort the pairs: leaves find them in space order, not index order
  // TODO(student): std::sort(pairs.begin(), pairs.end()).
  notImplemented("KdTree::computePairs", "Lab 4 handout, section 1.4", boxes, pairs);
}

void KdTree::visit(const std::vector<Aabb>& boxes, std::size_t begin, std::size_t end, const Vec3& lo,
                   const Vec3& hi, int depth, PairList& pairs) {
  // Choose the axis where the centres spread most and split at their median
  // TODO(student): only when end - begin > kLeafSize and depth < kMaxDepth; axis of the largest centre range; median of the centres with std::nth_element on keys_.
  // Count the boxes each side would get: left if min < split, right if max >= split
  // TODO(student): a box reaching across the plane counts on both sides.
  // Split only if both children shrink and few boxes are copied into both
  // TODO(student): left < n, right < n and left + right <= 1.5 n; otherwise fall through to the leaf.
  // Append the left child's list, visit it, drop it; then the same for the right child
  // TODO(student): push the box indices onto lists_ (copy the index first), visit(end, lists_.size(), region with hi[axis] = split, depth + 1), lists_.resize(end); then the right with lo[axis] = split.
  // Test the leaf's boxes pairwise; keep a pair only if its intersection's lower corner is here
  // TODO(student): ++leaves_; corner = min_i.cwiseMax(min_j); keep if lo <= corner < hi on every axis.
  notImplemented("KdTree::visit", "Lab 4 handout, section 1.4", boxes, begin, end, lo, hi, depth, pairs);
}

}  // namespace physlab
