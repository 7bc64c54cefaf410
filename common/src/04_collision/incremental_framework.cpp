// Framework half of the Lab 4 incremental broad phase (section 10): the dynamic tree's node pool,
// insertion and removal around the student's pickSibling/refitUpward, and the broad phase that
// keeps fat boxes and the pair set between steps; a step over a list of boxes (computePairs) is
// incremental_pairs.cpp.
#include <algorithm>
#include <cmath>
#include <string>

#include "physlab/broadphase.hpp"
#include "physlab/error.hpp"

namespace physlab {
namespace {

const char* const kAxisNames[3] = {"x", "y", "z"};

// Throws InvalidInput naming `what` for a non-finite coordinate or min > max.
void requireValidBox(const Aabb& b, const std::string& what) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(b.min[k]) || !std::isfinite(b.max[k])) {
      throw InvalidInput(what + " has a non-finite coordinate on the " + kAxisNames[k] + " axis");
    }
    if (b.min[k] > b.max[k]) {
      throw InvalidInput(what + " has min > max on the " + kAxisNames[k] + " axis (" + std::to_string(b.min[k]) +
                         " > " + std::to_string(b.max[k]) + ")");
    }
  }
}

bool inside(const Aabb& inner, const Aabb& outer) {
  return (outer.min.array() <= inner.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
}

static_assert(sizeof(Aabb) == 6 * sizeof(double), "an Aabb is its 6 coordinates, min then max");

std::uint64_t pairKey(int i, int j) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Dynamic AABB tree: the pool and the two edits

int DynamicAabbTree::allocateNode() {
  if (free_ == kNull) {
    nodes_.emplace_back();
    return static_cast<int>(nodes_.size()) - 1;
  }
  const int node = free_;
  free_ = nodes_[static_cast<std::size_t>(node)].parent;
  nodes_[static_cast<std::size_t>(node)] = Node{};
  return node;
}

void DynamicAabbTree::freeNode(int node) {
  Node& n = nodes_[static_cast<std::size_t>(node)];
  n = Node{};
  n.parent = free_;
  free_ = node;
}

int DynamicAabbTree::insertLeaf(const Aabb& box, int id) {
  const int leaf = allocateNode();
  Node& l = nodes_[static_cast<std::size_t>(leaf)];
  l.box = box;
  l.id = id;
  l.height = 0;
  ++leaves_;
  if (root_ == kNull) {
    root_ = leaf;
    return leaf;
  }
  // A new internal node takes the sibling's place, with the sibling and the leaf as children
  const int sibling = pickSibling(box);
  const int parent = allocateNode();  // may grow the pool: no references held across it
  const int grand = nodes_[static_cast<std::size_t>(sibling)].parent;
  Node& p = nodes_[static_cast<std::size_t>(parent)];
  p.parent = grand;
  p.child1 = sibling;
  p.child2 = leaf;
  p.box = enclose(nodes_[static_cast<std::size_t>(sibling)].box, box);
  p.height = nodes_[static_cast<std::size_t>(sibling)].height + 1;
  if (grand == kNull) {
    root_ = parent;
  } else {
    Node& g = nodes_[static_cast<std::size_t>(grand)];
    (g.child1 == sibling ? g.child1 : g.child2) = parent;
  }
  nodes_[static_cast<std::size_t>(sibling)].parent = parent;
  nodes_[static_cast<std::size_t>(leaf)].parent = parent;
  refitUpward(parent);
  return leaf;
}

void DynamicAabbTree::removeLeaf(int leaf) {
  --leaves_;
  if (leaf == root_) {
    root_ = kNull;
    freeNode(leaf);
    return;
  }
  // The sibling takes the parent's place
  const int parent = nodes_[static_cast<std::size_t>(leaf)].parent;
  const Node& p = nodes_[static_cast<std::size_t>(parent)];
  const int grand = p.parent;
  const int sibling = p.child1 == leaf ? p.child2 : p.child1;
  nodes_[static_cast<std::size_t>(sibling)].parent = grand;
  freeNode(parent);
  freeNode(leaf);
  if (grand == kNull) {
    root_ = sibling;
    return;
  }
  Node& g = nodes_[static_cast<std::size_t>(grand)];
  (g.child1 == parent ? g.child1 : g.child2) = sibling;
  refitUpward(grand);
}

void DynamicAabbTree::clear() {
  nodes_.clear();
  root_ = free_ = kNull;
  leaves_ = 0;
}

// ---------------------------------------------------------------------------------------------
// Incremental broad phase

IncrementalBroadPhase::IncrementalBroadPhase(double margin) : margin_(margin) {
  requireNonNegative(margin, "incremental broad phase: the margin");
}

bool IncrementalBroadPhase::contains(int id) const {
  return id >= 0 && id < static_cast<int>(leaf_.size()) && leaf_[static_cast<std::size_t>(id)] != DynamicAabbTree::kNull;
}

void IncrementalBroadPhase::requireLive(int id, const char* what) const {
  if (!contains(id)) {
    throw InvalidInput(std::string("incremental broad phase ") + what + ": unknown box id " + std::to_string(id) +
                       " (never added, or removed)");
  }
}

const Aabb& IncrementalBroadPhase::tightBox(int id) const {
  requireLive(id, "tightBox");
  return tight_[static_cast<std::size_t>(id)];
}

const Aabb& IncrementalBroadPhase::fatBox(int id) const {
  requireLive(id, "fatBox");
  return fat_[static_cast<std::size_t>(id)];
}

Aabb IncrementalBroadPhase::fatten(const Aabb& box, const Vec3& displacement) const {
  const Vec3 m = Vec3::Constant(margin_);
  return {box.min - m + displacement.cwiseMin(0.0), box.max + m + displacement.cwiseMax(0.0)};
}

void IncrementalBroadPhase::markDirty(int id) {
  char& flag = dirty_[static_cast<std::size_t>(id)];
  if (!flag) {
    flag = 1;
    dirty_list_.push_back(id);
  }
}

int IncrementalBroadPhase::insertProxy(int id, const Aabb& box) {
  if (id >= static_cast<int>(leaf_.size())) {
    const std::size_t n = static_cast<std::size_t>(id) + 1;
    tight_.resize(n);
    fat_.resize(n);
    leaf_.resize(n, DynamicAabbTree::kNull);
    dirty_.resize(n, 0);
  }
  const std::size_t k = static_cast<std::size_t>(id);
  tight_[k] = box;
  fat_[k] = fatten(box, Vec3::Zero());
  leaf_[k] = tree_.insertLeaf(fat_[k], id);
  markDirty(id);
  return id;
}

int IncrementalBroadPhase::add(const Aabb& box) {
  requireValidBox(box, "incremental broad phase add: the box");
  int id = static_cast<int>(leaf_.size());
  if (!free_ids_.empty()) {
    id = free_ids_.back();
    free_ids_.pop_back();
  }
  return insertProxy(id, box);
}

void IncrementalBroadPhase::remove(int id) {
  requireLive(id, "remove");
  tree_.removeLeaf(leaf_[static_cast<std::size_t>(id)]);
  leaf_[static_cast<std::size_t>(id)] = DynamicAabbTree::kNull;
  free_ids_.push_back(id);
  markDirty(id);
}

void IncrementalBroadPhase::move(int id, const Aabb& box) {
  requireLive(id, "move");
  requireValidBox(box, "incremental broad phase move: the box of id " + std::to_string(id));
  moveValid(id, box);
}

void IncrementalBroadPhase::moveValid(int id, const Aabb& box) {
  const std::size_t k = static_cast<std::size_t>(id);
  if (inside(box, fat_[k])) {
    tight_[k] = box;
    return;
  }
  // Left its fat box: reinsert with a new one, and redo its pairs at the next update
  const Vec3 displacement = (box.min + box.max - tight_[k].min - tight_[k].max) / 2;
  tight_[k] = box;
  tree_.removeLeaf(leaf_[k]);
  fat_[k] = fatten(box, displacement);
  leaf_[k] = tree_.insertLeaf(fat_[k], id);
  ++reinsertions_;
  markDirty(id);
}

void IncrementalBroadPhase::update(PairList& pairs) {
  pairs.clear();
  resetTests();
  last_reinsertions_ = reinsertions_;
  reinsertions_ = 0;
  if (!dirty_list_.empty()) {
    // Drop the pairs of dirty ids; the others' fat boxes did not change, nor did their overlap
    kept_.clear();
    for (const std::uint64_t key : pair_set_) {
      if (!dirty_[key >> 32] && !dirty_[key & 0xffffffffu]) kept_.push_back(key);
    }
    // Query the tree with each live dirty id's fat box; two dirty ids: found from the smaller
    found_.clear();
    for (const int id : dirty_list_) {
      if (!contains(id)) continue;
      tree_.query(fat_[static_cast<std::size_t>(id)], [&](int other) {
        if (other == id || (dirty_[static_cast<std::size_t>(other)] && other < id)) return;
        found_.push_back(pairKey(std::min(id, other), std::max(id, other)));
      });
    }
    std::sort(found_.begin(), found_.end());
    pair_set_.resize(kept_.size() + found_.size());
    std::merge(kept_.begin(), kept_.end(), found_.begin(), found_.end(), pair_set_.begin());
    for (const int id : dirty_list_) dirty_[static_cast<std::size_t>(id)] = 0;
    dirty_list_.clear();
  }
  // Report the kept pairs whose tight boxes overlap: sorted, since the set is. Each pair is
  // written, and the count advanced only when it overlaps: no branch to mispredict
  pairs.resize(pair_set_.size());
  const Aabb* tight = tight_.data();
  BoxPair* out = pairs.data();
  std::size_t count = 0;
  for (const std::uint64_t key : pair_set_) {
    const std::uint32_t i = static_cast<std::uint32_t>(key >> 32), j = static_cast<std::uint32_t>(key);
    const double* a = tight[i].min.data();  // min x, y, z then max x, y, z: 6 doubles in a row
    const double* b = tight[j].min.data();
    out[count] = {static_cast<int>(i), static_cast<int>(j)};
    count += static_cast<std::size_t>((a[0] <= b[3]) & (b[0] <= a[3]) & (a[1] <= b[4]) & (b[1] <= a[4]) &
                                      (a[2] <= b[5]) & (b[2] <= a[5]));
  }
  pairs.resize(count);
  countTests(static_cast<long>(pair_set_.size()));
}

void IncrementalBroadPhase::clear() {
  tree_.clear();
  tight_.clear();
  fat_.clear();
  leaf_.clear();
  dirty_.clear();
  dirty_list_.clear();
  free_ids_.clear();
  pair_set_.clear();
  reinsertions_ = last_reinsertions_ = 0;
}

}  // namespace physlab
