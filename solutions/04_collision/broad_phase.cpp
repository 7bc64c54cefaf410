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
  Vec3 mean = Vec3::Zero();
  for (const Aabb& b : boxes) mean += 0.5 * (b.min + b.max);
  mean /= std::max<double>(1.0, static_cast<double>(boxes.size()));
  Vec3 spread = Vec3::Zero();
  for (const Aabb& b : boxes) spread += (0.5 * (b.min + b.max) - mean).cwiseAbs2();
  Index axis = 0;
  spread.maxCoeff(&axis);
  axis_ = static_cast<int>(axis);
  // Copy the boxes into the list and sort it by lower endpoint
  entries_.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) entries_[i] = {boxes[i], static_cast<int>(i)};
  const int a = axis_;
  std::sort(entries_.begin(), entries_.end(),
            [a](const Entry& p, const Entry& q) { return p.bounds.min[a] < q.bounds.min[a]; });
}

long SweepAndPrune::insertionSortEntries(const std::vector<Aabb>& boxes) {
  // Copy the moved boxes in, keeping the previous order
  for (Entry& e : entries_) e.bounds = boxes[e.box];
  // Sink each entry past the larger lower endpoints before it; a nearly sorted list costs O(n)
  const int a = axis_;
  long swaps = 0;
  for (std::size_t k = 1; k < entries_.size(); ++k) {
    const Entry moving = entries_[k];
    const double key = moving.bounds.min[a];
    std::size_t j = k;
    while (j > 0 && entries_[j - 1].bounds.min[a] > key) {
      entries_[j] = entries_[j - 1];
      --j;
      ++swaps;
    }
    entries_[j] = moving;
  }
  return swaps;
}

void SweepAndPrune::sweep(PairList& pairs) {
  const int a = axis_;
  const std::size_t n = entries_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Entry& e = entries_[k];
    const double upper = e.bounds.max[a];
    // Test every later box whose interval starts before this one's ends (touching included)
    for (std::size_t m = k + 1; m < n && entries_[m].bounds.min[a] <= upper; ++m) {
      if (test(e.bounds, entries_[m].bounds)) {
        const int i = e.box, j = entries_[m].box;
        pairs.emplace_back(std::min(i, j), std::max(i, j));
      }
    }
  }
  // Sort the pairs: the sweep finds them in axis order, not index order
  std::sort(pairs.begin(), pairs.end());
}

// ---------------------------------------------------------------------------------------------
// Hashed uniform grid (section 1.2)

namespace {

// Cell coordinates past this are clamped: the conversion to an integer stays defined, and the
// clamp is monotone, so a box still covers the cell of every point inside it.
constexpr double kFarthestCell = 1.0e9;

int cellIndex(double x, double inverse_cell) {
  return static_cast<int>(std::clamp(std::floor(x * inverse_cell), -kFarthestCell, kFarthestCell));
}

std::size_t cellHash(int ix, int iy, int iz) {
  // Three large odd multipliers (Teschner et al. 2003) spread neighbouring cells over the table.
  const std::uint64_t h = static_cast<std::uint64_t>(static_cast<std::int64_t>(ix)) * 73856093ULL ^
                          static_cast<std::uint64_t>(static_cast<std::int64_t>(iy)) * 19349663ULL ^
                          static_cast<std::uint64_t>(static_cast<std::int64_t>(iz)) * 83492791ULL;
  return static_cast<std::size_t>(h ^ (h >> 29));
}

}  // namespace

void UniformGrid::chooseCellSize(const std::vector<Aabb>& boxes) {
  // Take the median over the boxes of their longest edge
  edges_.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) edges_[i] = (boxes[i].max - boxes[i].min).maxCoeff();
  double median = 0.0;
  if (!edges_.empty()) {
    const auto middle = edges_.begin() + static_cast<std::ptrdiff_t>(edges_.size() / 2);
    std::nth_element(edges_.begin(), middle, edges_.end());
    median = *middle;
  }
  // Make a cell twice that, or 1 m when the typical box is a point
  cell_size_ = median > 0.0 ? 2.0 * median : 1.0;
}

void UniformGrid::computePairs(const std::vector<Aabb>& boxes, PairList& pairs) {
  chooseCellSize(boxes);
  const double inverse_cell = 1.0 / cell_size_;
  const std::size_t n = boxes.size();
  // Find each box's cell range; set aside the boxes that cover too many cells
  oversized_.clear();
  is_oversized_.assign(n, 0);
  std::size_t total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    long long cells = 1;
    for (int k = 0; k < 3; ++k) {
      const long long span = static_cast<long long>(cellIndex(boxes[i].max[k], inverse_cell)) -
                             cellIndex(boxes[i].min[k], inverse_cell) + 1;
      if (span > kMaxCellsPerAxis) {
        is_oversized_[i] = 1;
        break;
      }
      cells *= span;
    }
    if (is_oversized_[i]) {
      oversized_.push_back(static_cast<int>(i));
    } else {
      total += static_cast<std::size_t>(cells);
    }
  }
  // Size the hash table to twice the number of (cell, box) entries, a power of two
  std::size_t buckets = 1;
  while (buckets < 2 * total) buckets *= 2;
  const std::size_t mask = buckets - 1;
  bucket_start_.assign(buckets + 1, 0);
  cell_entries_.resize(total);
  // Count the entries per bucket, then place them (a counting sort by bucket)
  const auto forEachCell = [&](auto&& visitCell) {
    for (std::size_t i = 0; i < n; ++i) {
      if (is_oversized_[i]) continue;
      const Aabb& b = boxes[i];
      const int x0 = cellIndex(b.min.x(), inverse_cell), x1 = cellIndex(b.max.x(), inverse_cell);
      const int y0 = cellIndex(b.min.y(), inverse_cell), y1 = cellIndex(b.max.y(), inverse_cell);
      const int z0 = cellIndex(b.min.z(), inverse_cell), z1 = cellIndex(b.max.z(), inverse_cell);
      for (int ix = x0; ix <= x1; ++ix) {
        for (int iy = y0; iy <= y1; ++iy) {
          for (int iz = z0; iz <= z1; ++iz) visitCell(CellEntry{ix, iy, iz, static_cast<int>(i)});
        }
      }
    }
  };
  forEachCell([&](const CellEntry& c) { ++bucket_start_[(cellHash(c.ix, c.iy, c.iz) & mask) + 1]; });
  std::partial_sum(bucket_start_.begin(), bucket_start_.end(), bucket_start_.begin());
  forEachCell([&](const CellEntry& c) { cell_entries_[bucket_start_[cellHash(c.ix, c.iy, c.iz) & mask]++] = c; });
  // Placing advanced each start to the next bucket's: shift back by one bucket
  for (std::size_t b = buckets; b > 0; --b) bucket_start_[b] = bucket_start_[b - 1];
  bucket_start_[0] = 0;
  // Test the boxes sharing a cell; keep a pair only in the cell of its intersection's lower corner
  for (std::size_t b = 0; b < buckets; ++b) {
    for (int p = bucket_start_[b]; p < bucket_start_[b + 1]; ++p) {
      const CellEntry& cp = cell_entries_[p];
      for (int q = p + 1; q < bucket_start_[b + 1]; ++q) {
        const CellEntry& cq = cell_entries_[q];
        if (cp.ix != cq.ix || cp.iy != cq.iy || cp.iz != cq.iz) continue;  // another cell, same bucket
        const Aabb& A = boxes[cp.box];
        const Aabb& B = boxes[cq.box];
        if (!test(A, B)) continue;
        const Vec3 corner = A.min.cwiseMax(B.min);
        if (cellIndex(corner.x(), inverse_cell) == cp.ix && cellIndex(corner.y(), inverse_cell) == cp.iy &&
            cellIndex(corner.z(), inverse_cell) == cp.iz) {
          pairs.emplace_back(std::min(cp.box, cq.box), std::max(cp.box, cq.box));
        }
      }
    }
  }
  // Test each oversized box against every other box (two oversized boxes once)
  for (const int o : oversized_) {
    for (std::size_t j = 0; j < n; ++j) {
      const int other = static_cast<int>(j);
      if (other == o || (is_oversized_[j] && other < o)) continue;
      if (test(boxes[o], boxes[j])) pairs.emplace_back(std::min(o, other), std::max(o, other));
    }
  }
  // Sort the pairs
  std::sort(pairs.begin(), pairs.end());
}

// ---------------------------------------------------------------------------------------------
// Bounding volume hierarchy (section 1.3)

void Bvh::buildTree(const std::vector<Aabb>& boxes) {
  // Start from all boxes in input order and an empty tree
  nodes_.clear();
  order_.resize(boxes.size());
  std::iota(order_.begin(), order_.end(), 0);
  // Build the root and, recursively, everything below it
  if (!boxes.empty()) buildNode(boxes, 0, static_cast<int>(boxes.size()));
}

int Bvh::buildNode(const std::vector<Aabb>& boxes, int first, int last) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  // Enclose the node's boxes, and find the bounds of their centres
  Aabb bounds = boxes[order_[first]];
  Vec3 centre_min = bounds.min + bounds.max, centre_max = centre_min;  // twice the centres
  for (int k = first + 1; k < last; ++k) {
    const Aabb& b = boxes[order_[k]];
    bounds = enclose(bounds, b);
    centre_min = centre_min.cwiseMin(b.min + b.max);
    centre_max = centre_max.cwiseMax(b.min + b.max);
  }
  nodes_[index].bounds = bounds;
  // Make a leaf when few boxes remain
  if (last - first <= kLeafSize) {
    nodes_[index].first = first;
    nodes_[index].count = last - first;
    return index;
  }
  // Split at the median centre along the longest axis of the centres' bounds
  Index axis = 0;
  (centre_max - centre_min).maxCoeff(&axis);
  const int mid = first + (last - first) / 2;
  std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + last, [&](int i, int j) {
    return boxes[i].min[axis] + boxes[i].max[axis] < boxes[j].min[axis] + boxes[j].max[axis];
  });
  // Build the two halves; pre-order puts the left child right after its parent
  const int left = buildNode(boxes, first, mid);
  const int right = buildNode(boxes, mid, last);
  nodes_[index].left = left;  // no reference into nodes_ is held across the recursion: it grows
  nodes_[index].right = right;
  return index;
}

void Bvh::refitTree(const std::vector<Aabb>& boxes) {
  // Visit the nodes backwards: in pre-order every child comes after its parent
  for (std::size_t k = nodes_.size(); k-- > 0;) {
    Node& node = nodes_[k];
    if (node.left < 0) {
      // Re-enclose a leaf's boxes
      node.bounds = boxes[order_[node.first]];
      for (int p = node.first + 1; p < node.first + node.count; ++p) node.bounds = enclose(node.bounds, boxes[order_[p]]);
    } else {
      // Enclose an internal node's two refitted children
      node.bounds = enclose(nodes_[node.left].bounds, nodes_[node.right].bounds);
    }
  }
}

void Bvh::queryAll(const std::vector<Aabb>& boxes, PairList& pairs) {
  if (nodes_.empty()) return;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
    const std::size_t first_new = pairs.size();
    const Aabb& box = boxes[i];
    // Descend from the root into every node whose bounds the box overlaps
    stack_.clear();
    stack_.push_back(0);
    while (!stack_.empty()) {
      const Node& node = nodes_[stack_.back()];
      stack_.pop_back();
      if (!test(box, node.bounds)) continue;
      if (node.left >= 0) {
        stack_.push_back(node.right);
        stack_.push_back(node.left);
        continue;
      }
      // Report the leaf's later boxes that overlap (j > i: each pair once)
      for (int p = node.first; p < node.first + node.count; ++p) {
        const int j = order_[p];
        if (j > i && test(box, boxes[j])) pairs.emplace_back(i, j);
      }
    }
    // Sort box i's partners: boxes in increasing i then give the whole list sorted
    std::sort(pairs.begin() + static_cast<std::ptrdiff_t>(first_new), pairs.end());
  }
}

// ---------------------------------------------------------------------------------------------
// k-d tree (section 1.4)

void KdTree::computePairs(const std::vector<Aabb>& boxes, PairList& pairs) {
  // Start at the root: every box, and all of space as the region
  leaves_ = 0;
  lists_.resize(boxes.size());
  std::iota(lists_.begin(), lists_.end(), 0);
  const double inf = std::numeric_limits<double>::infinity();
  visit(boxes, 0, boxes.size(), Vec3::Constant(-inf), Vec3::Constant(inf), 0, pairs);
  // Sort the pairs: leaves find them in space order, not index order
  std::sort(pairs.begin(), pairs.end());
}

void KdTree::visit(const std::vector<Aabb>& boxes, std::size_t begin, std::size_t end, const Vec3& lo,
                   const Vec3& hi, int depth, PairList& pairs) {
  const std::size_t count = end - begin;
  if (count > static_cast<std::size_t>(kLeafSize) && depth < kMaxDepth) {
    // Choose the axis where the centres spread most and split at their median
    Vec3 centre_min = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 centre_max = -centre_min;
    for (std::size_t k = begin; k < end; ++k) {
      const Vec3 c = 0.5 * (boxes[lists_[k]].min + boxes[lists_[k]].max);
      centre_min = centre_min.cwiseMin(c);
      centre_max = centre_max.cwiseMax(c);
    }
    Index axis = 0;
    (centre_max - centre_min).maxCoeff(&axis);
    keys_.resize(count);
    for (std::size_t k = begin; k < end; ++k) {
      keys_[k - begin] = 0.5 * (boxes[lists_[k]].min[axis] + boxes[lists_[k]].max[axis]);
    }
    const auto middle = keys_.begin() + static_cast<std::ptrdiff_t>(count / 2);
    std::nth_element(keys_.begin(), middle, keys_.end());
    const double split = *middle;
    // Count the boxes each side would get: left if min < split, right if max >= split
    std::size_t left_count = 0, right_count = 0;
    for (std::size_t k = begin; k < end; ++k) {
      left_count += boxes[lists_[k]].min[axis] < split;
      right_count += boxes[lists_[k]].max[axis] >= split;
    }
    // Split only if both children shrink and few boxes are copied into both
    if (left_count < count && right_count < count && 2 * (left_count + right_count) <= 3 * count) {
      // Append the left child's list, visit it, drop it; then the same for the right child
      Vec3 left_hi = hi, right_lo = lo;
      left_hi[axis] = split;
      right_lo[axis] = split;
      for (std::size_t k = begin; k < end; ++k) {
        const int b = lists_[k];
        if (boxes[b].min[axis] < split) lists_.push_back(b);
      }
      visit(boxes, end, lists_.size(), lo, left_hi, depth + 1, pairs);
      lists_.resize(end);
      for (std::size_t k = begin; k < end; ++k) {
        const int b = lists_[k];
        if (boxes[b].max[axis] >= split) lists_.push_back(b);
      }
      visit(boxes, end, lists_.size(), right_lo, hi, depth + 1, pairs);
      lists_.resize(end);
      return;
    }
  }
  // Test the leaf's boxes pairwise; keep a pair only if its intersection's lower corner is here
  ++leaves_;
  for (std::size_t p = begin; p < end; ++p) {
    const int i = lists_[p];
    for (std::size_t q = p + 1; q < end; ++q) {
      const int j = lists_[q];
      if (!test(boxes[i], boxes[j])) continue;
      const Vec3 corner = boxes[i].min.cwiseMax(boxes[j].min);
      if ((corner.array() >= lo.array()).all() && (corner.array() < hi.array()).all()) {
        pairs.emplace_back(std::min(i, j), std::max(i, j));
      }
    }
  }
}

}  // namespace physlab
