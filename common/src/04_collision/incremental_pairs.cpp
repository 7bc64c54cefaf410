// Lab 4 framework: a step of the incremental broad phase over a list of boxes (section 10).
//
// In a grade this file runs in the worker, beside the submitted functions it calls (IN_WORKER in
// CMakeLists.txt; docs/grading.md, "Where submitted code runs"): a step reinserts every box that
// left its fat box, and each reinsertion calls pickSibling() and refitUpward(), thousands of
// calls a step that would each cost a pipe round trip across the wire.
#include <limits>
#include <vector>

#include "physlab/broadphase.hpp"

namespace physlab {

void IncrementalBroadPhase::computePairs(const std::vector<Aabb>& boxes, PairList& pairs) {
  const int n = static_cast<int>(boxes.size());
  const int known = std::min(n, static_cast<int>(leaf_.size()));
  // Read-only pass: which boxes left their fat box (or are new), and is every box valid:
  // -DBL_MAX <= min <= max <= DBL_MAX per axis, false for NaN and infinities too?
  constexpr double kLargest = std::numeric_limits<double>::max();
  leaving_.clear();
  bool valid = true;
  for (int id = 0; id < known; ++id) {
    const double* b = boxes[static_cast<std::size_t>(id)].min.data();  // min x, y, z, max x, y, z
    const double* f = fat_[static_cast<std::size_t>(id)].min.data();
    const bool stays = (f[0] <= b[0]) & (f[1] <= b[1]) & (f[2] <= b[2]) & (b[3] <= f[3]) & (b[4] <= f[4]) & (b[5] <= f[5]);
    valid &= (-kLargest <= b[0]) & (b[0] <= b[3]) & (b[3] <= kLargest) & (-kLargest <= b[1]) & (b[1] <= b[4]) &
             (b[4] <= kLargest) & (-kLargest <= b[2]) & (b[2] <= b[5]) & (b[5] <= kLargest);
    if (!stays || leaf_[static_cast<std::size_t>(id)] == DynamicAabbTree::kNull) leaving_.push_back(id);
  }
  for (int id = known; id < n; ++id) leaving_.push_back(id);
  // A bad box, or boxes not yet checked: the full check, naming the bad box, before any change
  if (!valid || known < n) requireValidBoxes(boxes);
  // Ids past the last box go; the leaving ones are reinserted (or added); every tight box copied
  for (int id = static_cast<int>(leaf_.size()) - 1; id >= n; --id) {
    if (contains(id)) {
      tree_.removeLeaf(leaf_[static_cast<std::size_t>(id)]);
      leaf_[static_cast<std::size_t>(id)] = DynamicAabbTree::kNull;
      markDirty(id);
    }
  }
  for (const int id : leaving_) {
    if (contains(id)) {
      moveValid(id, boxes[static_cast<std::size_t>(id)]);
    } else {
      insertProxy(id, boxes[static_cast<std::size_t>(id)]);
    }
  }
  std::copy(boxes.begin(), boxes.end(), tight_.begin());
  // Every id below n is live now; the free ones are those past it, smallest reused first
  free_ids_.clear();
  for (int id = static_cast<int>(leaf_.size()) - 1; id >= n; --id) free_ids_.push_back(id);
  update(pairs);
}

}  // namespace physlab
