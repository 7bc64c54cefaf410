// Framework half of the Lab 4 broad phase: validation, the brute-force oracle, and the public
// entry points that validate before calling the student's methods in labs/04_collision.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "physlab/broadphase.hpp"
#include "physlab/error.hpp"

namespace physlab {
namespace {

const char* const kAxisNames[3] = {"x", "y", "z"};

void requireSameCount(std::size_t actual, std::size_t expected, const std::string& what) {
  if (actual != expected) {
    throw InvalidInput(what + " got " + std::to_string(actual) + " boxes, but the last build had " +
                       std::to_string(expected) + " (call build for a new set of boxes)");
  }
}

}  // namespace

void requireValidBoxes(const std::vector<Aabb>& boxes) {
  // Fast pass: -DBL_MAX <= min <= max <= DBL_MAX on every axis is false for NaN and infinities
  // too; combined without branches, so a world's every step pays a few instructions per box
  constexpr double kLargest = std::numeric_limits<double>::max();
  int valid = 1;
  for (const Aabb& b : boxes) {
    const double* lo = b.min.data();
    const double* hi = b.max.data();
    valid &= (-kLargest <= lo[0]) & (lo[0] <= hi[0]) & (hi[0] <= kLargest) &  //
             (-kLargest <= lo[1]) & (lo[1] <= hi[1]) & (hi[1] <= kLargest) &  //
             (-kLargest <= lo[2]) & (lo[2] <= hi[2]) & (hi[2] <= kLargest);
  }
  if (valid) return;
  // Slow pass: find the first bad box and say what is wrong with it
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Aabb& b = boxes[i];
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(b.min[k]) || !std::isfinite(b.max[k])) {
        throw InvalidInput("box " + std::to_string(i) + " has a non-finite coordinate on the " +
                           kAxisNames[k] + " axis");
      }
      if (b.min[k] > b.max[k]) {
        throw InvalidInput("box " + std::to_string(i) + " has min > max on the " + kAxisNames[k] +
                           " axis (" + std::to_string(b.min[k]) + " > " + std::to_string(b.max[k]) + ")");
      }
    }
  }
}

void BroadPhase::findPairs(const std::vector<Aabb>& boxes, PairList& pairs) {
  validate(boxes);
  pairs.clear();
  resetTests();
  computePairs(boxes, pairs);
}

void BruteForce::computePairs(const std::vector<Aabb>& boxes, PairList& pairs) {
  const int n = static_cast<int>(boxes.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (test(boxes[i], boxes[j])) pairs.emplace_back(i, j);
    }
  }
}

void SweepAndPrune::build(const std::vector<Aabb>& boxes, PairList& pairs) {
  requireValidBoxes(boxes);
  pairs.clear();
  resetTests();
  swaps_ = 0;
  sortEntries(boxes);
  sweep(pairs);
}

void SweepAndPrune::update(const std::vector<Aabb>& boxes, PairList& pairs) {
  requireValidBoxes(boxes);
  requireSameCount(boxes.size(), entries_.size(), "sort and sweep update");
  pairs.clear();
  resetTests();
  swaps_ = insertionSortEntries(boxes);
  sweep(pairs);
}

void SweepAndPrune::computePairs(const std::vector<Aabb>& boxes, PairList& pairs) {
  // Reuse the last order when the boxes are (presumably) the same ones, moved.
  if (!entries_.empty() && entries_.size() == boxes.size()) {
    swaps_ = insertionSortEntries(boxes);
  } else {
    swaps_ = 0;
    sortEntries(boxes);
  }
  sweep(pairs);
}

void Bvh::build(const std::vector<Aabb>& boxes, PairList& pairs) {
  requireValidBoxes(boxes);
  pairs.clear();
  resetTests();
  buildTree(boxes);
  queryAll(boxes, pairs);
}

void Bvh::refit(const std::vector<Aabb>& boxes, PairList& pairs) {
  requireValidBoxes(boxes);
  requireSameCount(boxes.size(), order_.size(), "BVH refit");
  pairs.clear();
  resetTests();
  refitTree(boxes);
  queryAll(boxes, pairs);
}

void Bvh::computePairs(const std::vector<Aabb>& boxes, PairList& pairs) {
  buildTree(boxes);
  queryAll(boxes, pairs);
}

int Bvh::depth() const {
  if (nodes_.empty()) return 0;
  // Pre-order storage: a child's index is larger than its parent's, so one forward pass
  // propagates each node's level to its children.
  std::vector<int> level(nodes_.size(), 0);
  level[0] = 1;
  int deepest = 1;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    deepest = std::max(deepest, level[k]);
    const int left = nodes_[k].left, right = nodes_[k].right;
    if (left < 0) continue;
    const int size = static_cast<int>(nodes_.size());
    if (left <= static_cast<int>(k) || right <= static_cast<int>(k) || left >= size || right >= size) {
      return -1;  // not a pre-order tree: the tests report it rather than crash
    }
    level[left] = level[right] = level[k] + 1;
  }
  return deepest;
}

std::vector<std::unique_ptr<BroadPhase>> allBroadPhases() {
  std::vector<std::unique_ptr<BroadPhase>> methods;
  methods.push_back(std::make_unique<BruteForce>());
  methods.push_back(std::make_unique<SweepAndPrune>());
  methods.push_back(std::make_unique<UniformGrid>());
  methods.push_back(std::make_unique<Bvh>());
  methods.push_back(std::make_unique<KdTree>());
  return methods;
}

}  // namespace physlab
