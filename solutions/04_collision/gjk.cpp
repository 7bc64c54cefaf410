// Lab 4, section 8: the distance between convex shapes by GJK (Gilbert-Johnson-Keerthi).
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {
namespace {

// A vertex of the Minkowski difference, w = a - b, with the support points it came from.
struct SimplexVertex {
  Vec3 w, a, b;
};

// The simplex (1 to 4 vertices) and the barycentric weights of its point closest to the origin.
struct Simplex {
  std::array<SimplexVertex, 4> v;
  std::array<double, 4> lambda{};
  int count = 0;

  // Keeps only the listed vertices with the given weights.
  void keep(std::initializer_list<int> indices, std::initializer_list<double> weights) {
    std::array<SimplexVertex, 4> kept = v;
    int k = 0;
    auto w = weights.begin();
    for (int i : indices) {
      kept[k] = v[i];
      lambda[k++] = *w++;
    }
    v = kept;
    count = k;
  }
  Vec3 closest() const {
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < count; ++i) p += lambda[i] * v[i].w;
    return p;
  }
};

// Reduces the segment {0, 1} to the sub-simplex nearest the origin.
void closestOnSegment(Simplex& s, int i, int j) {
  const Vec3 d = s.v[j].w - s.v[i].w;
  const double t = -s.v[i].w.dot(d) / d.squaredNorm();
  if (!(t > 0.0)) s.keep({i}, {1.0});
  else if (t >= 1.0) s.keep({j}, {1.0});
  else s.keep({i, j}, {1.0 - t, t});
}

// Reduces the triangle {i, j, k} to the sub-simplex nearest the origin (Voronoi regions).
void closestOnTriangle(Simplex& s, int i, int j, int k) {
  const Vec3 &a = s.v[i].w, &b = s.v[j].w, &c = s.v[k].w;
  const Vec3 ab = b - a, ac = c - a, ap = -a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return s.keep({i}, {1.0});
  const Vec3 bp = -b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return s.keep({j}, {1.0});
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double t = d1 / (d1 - d3);
    return s.keep({i, j}, {1.0 - t, t});
  }
  const Vec3 cp = -c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return s.keep({k}, {1.0});
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    return s.keep({i, k}, {1.0 - t, t});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return s.keep({j, k}, {1.0 - t, t});
  }
  const double denom = 1.0 / (va + vb + vc);
  s.keep({i, j, k}, {va * denom, vb * denom, vc * denom});
}

// Reduces the tetrahedron to the face nearest the origin; returns false when it encloses it.
bool closestOnTetrahedron(Simplex& s) {
  static constexpr int faces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
  Simplex best;
  double best_d2 = std::numeric_limits<double>::infinity();
  bool outside_any = false;
  // A flat tetrahedron (the new vertex in the triangle's plane, to round-off) encloses nothing:
  // its side tests are noise, so every face is a candidate
  double extent = 0.0;
  for (int i = 1; i < 4; ++i) extent = std::max(extent, (s.v[i].w - s.v[0].w).norm());
  const double volume = (s.v[1].w - s.v[0].w).dot((s.v[2].w - s.v[0].w).cross(s.v[3].w - s.v[0].w));
  const bool flat = std::abs(volume) <= 1e-10 * extent * extent * extent;
  for (const auto& f : faces) {
    const Vec3 &a = s.v[f[0]].w, &b = s.v[f[1]].w, &c = s.v[f[2]].w, &d = s.v[f[3]].w;
    const Vec3 n = (b - a).cross(c - a);
    // The origin is beyond this face when it and the fourth vertex are on opposite sides
    const double side_origin = -n.dot(a), side_d = n.dot(d - a);
    if (!flat && side_origin * side_d > 0.0) continue;
    outside_any = true;
    Simplex face = s;
    closestOnTriangle(face, f[0], f[1], f[2]);
    const double d2 = face.closest().squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = face;
  }
  if (!outside_any) return false;
  s = best;
  return true;
}

}  // namespace

DistanceResult gjkDistance(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b) {
  if (std::holds_alternative<Plane>(a) || std::holds_alternative<Plane>(b)) {
    throw InvalidInput("gjkDistance: a plane is unbounded; use distance()");
  }
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  validatePose(pose_b, "pose_b");
  DistanceResult r;
  // Start from the support point along the line of centres
  auto vertex = [&](const Vec3& d) {
    ++r.iterations;
    const Vec3 pa = coreSupport(a, pose_a, -d), pb = coreSupport(b, pose_b, d);
    return SimplexVertex{pa - pb, pa, pb};
  };
  Simplex s;
  const Vec3 centres = pose_a.x - pose_b.x;
  s.v[0] = vertex(centres.squaredNorm() > 0.0 ? Vec3(-centres) : Vec3(-Vec3::UnitX()));
  s.lambda[0] = 1.0;
  s.count = 1;
  Vec3 v = s.v[0].w;
  double scale2 = v.squaredNorm();
  bool overlap = false;
  for (int iteration = 0; iteration < 100; ++iteration) {
    // Stop when the origin is (within round-off) in the simplex
    if (v.squaredNorm() <= 1e-24 * scale2) {
      overlap = true;
      break;
    }
    // Ask for the support point against v; stop when it brings the bound no closer
    const SimplexVertex w = vertex(v);
    scale2 = std::max(scale2, w.w.squaredNorm());
    if (v.squaredNorm() - v.dot(w.w) <= 1e-10 * v.squaredNorm()) break;
    bool repeated = false;
    for (int i = 0; i < s.count; ++i) repeated = repeated || (s.v[i].w - w.w).squaredNorm() <= 1e-24 * scale2;
    if (repeated) break;
    // Add it and keep the sub-simplex nearest the origin
    Simplex next = s;
    next.v[next.count++] = w;
    if (next.count == 2) closestOnSegment(next, 0, 1);
    else if (next.count == 3) closestOnTriangle(next, 0, 1, 2);
    else if (!closestOnTetrahedron(next)) {
      overlap = true;
      break;
    }
    const Vec3 closer = next.closest();
    if (closer.squaredNorm() >= v.squaredNorm()) break;  // no progress: round-off has the last word
    s = next;
    v = closer;
  }
  // Read the closest points from the barycentric weights, then grow the cores by the margins
  Vec3 pa = Vec3::Zero(), pb = Vec3::Zero();
  for (int i = 0; i < s.count; ++i) pa += s.lambda[i] * s.v[i].a, pb += s.lambda[i] * s.v[i].b;
  const double ra = margin(a), rb = margin(b), core = overlap ? 0.0 : v.norm();
  r.point_a = pa;
  r.point_b = pb;
  if (overlap || core <= ra + rb) {
    r.overlap = true;
    return r;
  }
  const Vec3 n = v / core;  // from B to A
  r.distance = core - ra - rb;
  r.point_a = pa - ra * n;
  r.point_b = pb + rb * n;
  return r;
}

}  // namespace physlab
