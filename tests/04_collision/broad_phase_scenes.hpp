// Scenes of random boxes for the Lab 4 broad-phase tests, and a comparison with the brute-force
// oracle that says which pairs differ. Random draws come from physlab::test::rng().
#pragma once

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "physlab/broadphase.hpp"
#include "support.hpp"

namespace physlab::test {

/// How the boxes of a random scene are sized and placed.
enum class BoxSizes {
  Uniform,     ///< edges uniform in [0.2, 1.2] m, centres uniform: a few overlaps per box
  WideRange,   ///< edges log-uniform in [0.01, 4] m on each axis: slivers, plates and big boxes
  Flat,        ///< zero thickness along z, all on a few planes: degenerate intervals
  Clustered,   ///< three tight clusters: dense, many pairs per box
};

inline const char* sizesName(BoxSizes sizes) {
  switch (sizes) {
    case BoxSizes::Uniform: return "uniform";
    case BoxSizes::WideRange: return "wide range";
    case BoxSizes::Flat: return "flat";
    case BoxSizes::Clustered: return "clustered";
  }
  return "?";
}

const BoxSizes kAllSizes[] = {BoxSizes::Uniform, BoxSizes::WideRange, BoxSizes::Flat, BoxSizes::Clustered};

/// A box with centre c and half-extents r.
inline Aabb boxAround(const Vec3& c, const Vec3& r) { return {c - r, c + r}; }

/// n random boxes in a cube of side cbrt(n) m (about one box centre per cubic metre).
inline std::vector<Aabb> randomScene(int n, BoxSizes sizes) {
  const double side = std::cbrt(static_cast<double>(n));
  const Vec3 clusters[3] = {randomVec3(side), randomVec3(side), randomVec3(side)};
  std::vector<Aabb> boxes;
  boxes.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    Vec3 c(uniform(0, side), uniform(0, side), uniform(0, side));
    Vec3 half = Vec3::Zero();
    switch (sizes) {
      case BoxSizes::Uniform:
        half = Vec3(uniform(0.1, 0.6), uniform(0.1, 0.6), uniform(0.1, 0.6));
        break;
      case BoxSizes::WideRange:
        for (int k = 0; k < 3; ++k) half[k] = 0.5 * std::exp(uniform(std::log(0.01), std::log(4.0)));
        break;
      case BoxSizes::Flat:
        c.z() = std::floor(uniform(0, 3));  // three planes z = 0, 1, 2
        half = Vec3(uniform(0.1, 0.6), uniform(0.1, 0.6), 0.0);
        break;
      case BoxSizes::Clustered:
        c = clusters[i % 3] + randomVec3(0.15 * side);
        half = Vec3(uniform(0.05, 0.3), uniform(0.05, 0.3), uniform(0.05, 0.3));
        break;
    }
    boxes.push_back(boxAround(c, half));
  }
  return boxes;
}

/// n boxes with corners on a lattice of spacing s (random), edges 0, 1 or 2 spacings: many
/// boxes share faces, edges or corners exactly, some are identical, some are points. Each corner
/// coordinate is computed by the same expression offset + s k for the same integer k, so two
/// boxes that meet share the exact same double.
inline std::vector<Aabb> touchingScene(int n) {
  const double s = uniform(0.05, 3.0);
  const Vec3 offset = randomVec3(10.0);
  const int m = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n)))) + 1;
  std::vector<Aabb> boxes;
  for (int i = 0; i < n; ++i) {
    Aabb b;
    for (int k = 0; k < 3; ++k) {
      const int lo = static_cast<int>(uniform(0, m));
      const int edge = static_cast<int>(uniform(0, 3));
      b.min[k] = offset[k] + s * lo;
      b.max[k] = offset[k] + s * (lo + edge);
    }
    boxes.push_back(b);
  }
  return boxes;
}

/// n boxes that are all the same point, except some that contain it or just reach it.
inline std::vector<Aabb> pointScene(int n) {
  const Vec3 p = randomVec3(5.0);
  std::vector<Aabb> boxes(static_cast<std::size_t>(n), Aabb{p, p});
  for (int i = 0; i < n; i += 7) {
    const Vec3 r(uniform(0.0, 1.0), uniform(0.0, 1.0), uniform(0.0, 1.0));
    boxes[static_cast<std::size_t>(i)] = (i % 2 == 0) ? Aabb{p - r, p + r} : Aabb{p, p + r};
  }
  return boxes;
}

/// A random scene in which one box, at a random index, spans the whole scene, and (for n >= 3)
/// two more at random indices span most of it: huge boxes overlap everything and each other.
inline std::vector<Aabb> hugeBoxScene(int n, BoxSizes sizes) {
  std::vector<Aabb> boxes = randomScene(n, sizes);
  Aabb all = boxes[0];
  for (const Aabb& b : boxes) all = enclose(all, b);
  const Vec3 size = all.max - all.min;
  boxes[static_cast<std::size_t>(uniform(0, n))] = {all.min - Vec3::Constant(1.0), all.max + Vec3::Constant(1.0)};
  for (int k = 0; k < 2 && n >= 3; ++k) {
    const Vec3 lo = all.min + 0.2 * Vec3(uniform(0, 1), uniform(0, 1), uniform(0, 1)).cwiseProduct(size);
    boxes[static_cast<std::size_t>(uniform(0, n))] = {lo, lo + 0.7 * size};
  }
  return boxes;
}

/// Moves every box by a random displacement of at most `step` per axis, and teleports a few.
inline void moveBoxes(std::vector<Aabb>& boxes, double step) {
  const double side = std::cbrt(static_cast<double>(boxes.size()));
  for (Aabb& b : boxes) {
    Vec3 d = randomVec3(step);
    if (uniform(0, 1) < 0.02) d = randomVec3(side);  // a few large jumps: insertion sort must cope
    b.min += d;
    b.max += d;
  }
}

/// A random number of boxes in [lo, hi].
inline int randomCount(int lo, int hi) { return static_cast<int>(uniform(lo, hi + 1)); }

/// The oracle's answer.
inline PairList bruteForcePairs(const std::vector<Aabb>& boxes) {
  BruteForce brute;
  PairList pairs;
  brute.findPairs(boxes, pairs);
  return pairs;
}

/// Which pairs differ between `got` and `expected` (sorted, unique), in a few lines.
inline std::string describeDifference(const PairList& got, const PairList& expected) {
  std::ostringstream os;
  os << got.size() << " pairs found, " << expected.size() << " expected";
  if (!std::is_sorted(got.begin(), got.end())) os << "; the list is not sorted";
  for (const BoxPair& p : got) {
    if (p.first >= p.second) {
      os << "; pair (" << p.first << ", " << p.second << ") does not have i < j";
      break;
    }
  }
  PairList sorted = got, missing, extra;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) os << "; a pair is listed twice";
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  std::set_difference(expected.begin(), expected.end(), sorted.begin(), sorted.end(), std::back_inserter(missing));
  std::set_difference(sorted.begin(), sorted.end(), expected.begin(), expected.end(), std::back_inserter(extra));
  const auto list = [&os](const char* what, const PairList& pairs) {
    if (pairs.empty()) return;
    os << "; " << pairs.size() << " " << what << ":";
    for (std::size_t k = 0; k < std::min<std::size_t>(pairs.size(), 5); ++k) {
      os << " (" << pairs[k].first << ", " << pairs[k].second << ")";
    }
  };
  list("missing", missing);
  list("extra", extra);
  return os.str();
}

}  // namespace physlab::test

/// Checks that `got` is exactly the oracle's `expected` list, printing a summary of the
/// difference if not. (A plain CHECK(got == expected) would print both lists in full: up to
/// millions of pairs, which Catch's reporter takes minutes to format.)
#define CHECK_SAME_PAIRS(got, expected)                                                       \
  do {                                                                                        \
    const bool same_pairs = (got) == (expected);                                              \
    INFO((same_pairs ? std::string() : ::physlab::test::describeDifference((got), (expected)))); \
    CHECK(same_pairs);                                                                        \
  } while (false)
