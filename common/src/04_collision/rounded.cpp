// Framework half of Lab 4: spheres and capsules against boxes and polyhedra. These pairs need
// no idea beyond the lab's (closest points, then separating axes when the cores meet), so the
// framework provides them for Labs 5 and 6; they call no student code.
#include <algorithm>
#include <cmath>
#include <limits>

#include "physlab/collision.hpp"
#include "physlab/error.hpp"
#include "rounded.hpp"

namespace physlab {
namespace {

// The polytope in the world frame.
struct WorldPolytope {
  const ConvexPolyhedron& shape;
  std::vector<Vec3> v;   // vertices
  std::vector<Vec3> n;   // face normals
  std::vector<double> o; // face offsets: n_f . p <= o_f inside
};

WorldPolytope toWorld(const ConvexPolyhedron& p, const Pose& pose) {
  WorldPolytope w{p, {}, {}, {}};
  for (const Vec3& v : p.vertices) w.v.push_back(pose.toWorld(v));
  for (std::size_t f = 0; f < p.normals.size(); ++f) {
    w.n.push_back(pose.q * p.normals[f]);
    w.o.push_back(w.n.back().dot(w.v[p.faces[f][0]]));
  }
  return w;
}

Vec3 closestOnSegment(const Vec3& p, const Vec3& q, const Vec3& c) {
  const Vec3 d = q - p;
  const double len2 = d.squaredNorm();
  if (len2 == 0.0) return p;
  return p + std::clamp((c - p).dot(d) / len2, 0.0, 1.0) * d;
}

// The point of the polytope closest to c (c itself when inside): the best of the face
// projections that land inside their face, the closest points of the edges, and the vertices.
Vec3 closestOnPolytope(const WorldPolytope& w, const Vec3& c) {
  bool inside = true;
  for (std::size_t f = 0; f < w.n.size(); ++f) inside = inside && w.n[f].dot(c) <= w.o[f];
  if (inside) return c;
  Vec3 best = w.v[0];
  double best_d2 = (c - best).squaredNorm();
  auto consider = [&](const Vec3& p) {
    const double d2 = (c - p).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = p;
  };
  for (std::size_t f = 0; f < w.n.size(); ++f) {
    const Vec3 p = c - (w.n[f].dot(c) - w.o[f]) * w.n[f];
    const std::vector<int>& face = w.shape.faces[f];
    bool within = true;
    for (std::size_t k = 0; k < face.size() && within; ++k) {
      const Vec3& a = w.v[face[k]];
      const Vec3& b = w.v[face[(k + 1) % face.size()]];
      within = (b - a).cross(p - a).dot(w.n[f]) >= 0.0;
    }
    if (within) consider(p);
  }
  for (const auto& e : w.shape.edges) consider(closestOnSegment(w.v[e[0]], w.v[e[1]], c));
  return best;
}

// Distance of the segment point at s from the polytope, and the two points.
double segmentGap(const WorldPolytope& w, const Vec3& p0, const Vec3& p1, double s, Vec3& on_core, Vec3& on_poly) {
  on_core = p0 + s * (p1 - p0);
  on_poly = closestOnPolytope(w, on_core);
  return (on_core - on_poly).norm();
}

}  // namespace

Manifold collideRoundedPolytope(const Vec3& p0, const Vec3& p1, double radius, const ConvexPolyhedron& b,
                                const Pose& pose_b) {
  const WorldPolytope w = toWorld(b, pose_b);
  // The distance from the polytope is convex along the core: golden-section search for its minimum
  double lo = 0.0, hi = 1.0;
  Vec3 core, poly;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  if ((p1 - p0).squaredNorm() > 0.0) {
    for (int k = 0; k < 80; ++k) {
      const double m1 = hi - golden * (hi - lo), m2 = lo + golden * (hi - lo);
      Vec3 c1, q1, c2, q2;
      if (segmentGap(w, p0, p1, m1, c1, q1) <= segmentGap(w, p0, p1, m2, c2, q2)) hi = m2;
      else lo = m1;
    }
  }
  const double gap = segmentGap(w, p0, p1, 0.5 * (lo + hi), core, poly);
  Manifold m;
  if (gap > radius) return m;
  if (gap > 1e-12 * (1.0 + radius)) {
    // Shallow: the cores are apart, the normal runs between their closest points
    m.normal = (core - poly) / gap;
    // A capsule lying along a face rests on both ends
    int ends = 0;
    for (const Vec3& e : {p0, p1}) {
      const Vec3 q = closestOnPolytope(w, e);
      const double d = (e - q).norm();
      if ((p1 - p0).squaredNorm() > 0.0 && d <= radius && d > 0.0 && (e - q).dot(m.normal) > (1.0 - 1e-6) * d) ++ends;
    }
    if (ends == 2) {
      std::uint32_t id = 1;
      for (const Vec3& e : {p0, p1}) {
        const Vec3 q = closestOnPolytope(w, e);
        const double d = (e - q).norm();
        m.add(0.5 * (e - radius * m.normal + q), radius - d, id++);
      }
    } else {
      m.add(0.5 * (core - radius * m.normal + poly), radius - gap, 0);
    }
    return m;
  }
  // Deep: the core reaches inside; leave through the face of least overlap (one-sided)
  double best = std::numeric_limits<double>::infinity();
  int best_face = 0;
  for (std::size_t f = 0; f < w.n.size(); ++f) {
    const double overlap = w.o[f] - std::min(w.n[f].dot(p0), w.n[f].dot(p1)) + radius;
    if (overlap < best) best = overlap, best_face = static_cast<int>(f);
  }
  const Vec3& n = w.n[best_face];
  m.normal = n;
  // The part of the core over that face (clipped by its side planes), or the core's point
  // nearest the polytope when none of it is
  Vec3 ends[2] = {p0, p1};
  bool over = true;
  const std::vector<int>& face = b.faces[best_face];
  for (std::size_t k = 0; k < face.size() && over; ++k) {
    const Vec3& a = w.v[face[k]];
    const Vec3 side = (w.v[face[(k + 1) % face.size()]] - a).cross(n).normalized();
    const double d0 = side.dot(ends[0] - a), d1 = side.dot(ends[1] - a);
    if (d0 > 0.0 && d1 > 0.0) over = false;
    else if (d0 > 0.0) ends[0] += d0 / (d0 - d1) * (ends[1] - ends[0]);
    else if (d1 > 0.0) ends[1] += d1 / (d1 - d0) * (ends[0] - ends[1]);
  }
  if (!over) ends[0] = ends[1] = core;
  const int count = (ends[1] - ends[0]).squaredNorm() > 1e-24 ? 2 : 1;
  for (int k = 0; k < count; ++k) {
    const double height = n.dot(ends[k]) - w.o[best_face];
    if (radius - height < 0.0) continue;
    m.add(ends[k] - 0.5 * (radius + height) * n, radius - height, combineFeatures(300 + best_face, k));
  }
  if (m.empty()) m.normal = Vec3::Zero();
  return m;
}

}  // namespace physlab
