// Lab 4, sections 5-6: the separating-axis test for boxes and convex polyhedra, clipping of the
// incident face (Sutherland-Hodgman), and reduction of the manifold to 4 points.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {
namespace {

// The best axis found so far: its overlap, unit direction from B to A, and what it came from.
struct Axis {
  double overlap = std::numeric_limits<double>::infinity();
  Vec3 normal = Vec3::Zero();
  int feature = -1;  // face: 0..(faces of A)-1, then B's; edge pair: its index
};

// Whether an axis with this overlap replaces the best so far: only when smaller by more than
// round-off, so that exact ties (a box resting on a box) keep the axis tested first and the
// reference face cannot flip from step to step.
bool clearlyBelow(double overlap, double best) {
  return !std::isfinite(best) || overlap < best - 1e-9 * std::abs(best) - 1e-12;
}

// Clips `incident` by the side planes of a reference face and returns the points below the
// face (depth = offset - n.p >= 0), each moved half its depth up to the midpoint.
ContactPolygon keepBelow(const ContactPolygon& clipped, const Vec3& n_ref, double offset, std::uint32_t face_id) {
  ContactPolygon below;
  for (int i = 0; i < clipped.count; ++i) {
    const Vec3& p = clipped.points[i].position;
    const double depth = offset - n_ref.dot(p);
    if (depth >= 0.0) below.add(p + 0.5 * depth * n_ref, depth, combineFeatures(face_id, clipped.points[i].id));
  }
  return below;
}

// The incident face of a box while it is clipped, on the stack: 4 corners, and each side plane
// adds at most one corner to a convex polygon, so 8 points (16 leave room for round-off; a point
// past the capacity is dropped, as ContactPolygon::add does).
struct FacePolygon {
  static constexpr int kCapacity = 16;
  std::array<Vec3, kCapacity> points;         // world frame
  std::array<std::uint32_t, kCapacity> ids;  // corner numbers, then combined with the planes
  int count = 0;
  void add(const Vec3& p, std::uint32_t id) {
    if (count < kCapacity) points[count] = p, ids[count++] = id;
  }
};

// One Sutherland-Hodgman step, as clipPolygon() (the same points, ids and order), on the stack,
// with each point's distance to the plane computed once.
void clipFace(const FacePolygon& polygon, const Vec3& plane_normal, double plane_offset, std::uint32_t plane_id,
              FacePolygon& out) {
  std::array<double, FacePolygon::kCapacity> d;
  for (int i = 0; i < polygon.count; ++i) d[i] = plane_normal.dot(polygon.points[i]) - plane_offset;
  out.count = 0;
  for (int i = 0; i < polygon.count; ++i) {
    const int next = i + 1 < polygon.count ? i + 1 : 0;
    const double dp = d[i], dq = d[next];
    if (dp <= 0.0) out.add(polygon.points[i], polygon.ids[i]);
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
      const Vec3 &p = polygon.points[i], &q = polygon.points[next];
      out.add(p + dp / (dp - dq) * (q - p), combineFeatures(polygon.ids[i], plane_id));
    }
  }
}

// Squared distance of q from p in the plane normal to n.
double planarDistance2(const Vec3& p, const Vec3& q, const Vec3& n) {
  const Vec3 d = q - p;
  return (d - d.dot(n) * n).squaredNorm();
}

}  // namespace

ContactPolygon clipPolygon(const ContactPolygon& polygon, const Vec3& plane_normal, double plane_offset,
                           std::uint32_t plane_id) {
  // Refuse a count that would read past the points, and a point or plane that is not finite
  validatePolygon(polygon, "clipPolygon polygon");
  requireFinite(plane_normal, "clipPolygon plane_normal");
  if (!std::isfinite(plane_offset)) throw InvalidInput("clipPolygon plane_offset must be finite");
  ContactPolygon out;
  for (int i = 0; i < polygon.count; ++i) {
    const ContactPoint& p = polygon.points[i];
    const ContactPoint& q = polygon.points[(i + 1) % polygon.count];
    const double dp = plane_normal.dot(p.position) - plane_offset, dq = plane_normal.dot(q.position) - plane_offset;
    // Keep the edge's start when it is inside
    if (dp <= 0.0) out.add(p.position, p.depth, p.id);
    // Add the crossing when the edge passes through the plane
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
      out.add(p.position + dp / (dp - dq) * (q.position - p.position), 0.0, combineFeatures(p.id, plane_id));
    }
  }
  return out;
}

Manifold reduceContacts(const Vec3& normal, const ContactPolygon& candidates) {
  // Refuse a count that would read past the points, and a point or normal that is not finite
  requireFinite(normal, "reduceContacts normal");
  validatePolygon(candidates, "reduceContacts candidates");
  Manifold m;
  m.normal = normal;
  if (candidates.count <= Manifold::kMaxPoints) {
    for (int i = 0; i < candidates.count; ++i) m.points[m.count++] = candidates.points[i];
    return m;
  }
  const auto& c = candidates.points;
  // Start from the deepest point
  int first = 0;
  for (int i = 1; i < candidates.count; ++i) {
    if (c[i].depth > c[first].depth) first = i;
  }
  // Add the point farthest from it
  int second = first;
  double best = -1.0;
  for (int i = 0; i < candidates.count; ++i) {
    const double d2 = planarDistance2(c[first].position, c[i].position, normal);
    if (d2 > best) best = d2, second = i;
  }
  // Add the point farthest from the line through both (the largest triangle)
  const Vec3 line = c[second].position - c[first].position;
  int third = -1;
  double most = 0.0;
  for (int i = 0; i < candidates.count; ++i) {
    const double area = std::abs(line.cross(c[i].position - c[first].position).dot(normal));
    if (area > most) most = area, third = i;
  }
  m.points[m.count++] = c[first];
  if (second != first) m.points[m.count++] = c[second];
  if (third < 0) return m;
  m.points[m.count++] = c[third];
  // Add the point outside that triangle that adds the most area to it
  const int corner[3] = {first, second, third};
  const double orientation = line.cross(c[third].position - c[first].position).dot(normal) > 0.0 ? 1.0 : -1.0;
  int fourth = -1;
  double added = 0.0;
  for (int i = 0; i < candidates.count; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = c[corner[k]].position;
      const Vec3& q = c[corner[(k + 1) % 3]].position;
      const double outside = -orientation * (q - p).cross(c[i].position - p).dot(normal);
      if (outside > added) added = outside, fourth = i;
    }
  }
  if (fourth >= 0) m.points[m.count++] = c[fourth];
  return m;
}

Manifold collideBoxBox(const Box& a, const Pose& pose_a, const Box& b, const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  validatePose(pose_b, "pose_b");
  // Express B in A's frame once: every axis test below reads these numbers and multiplies no matrix
  // (column j of R = R_A^T R_B is b_j in A's axes; t_A, t_B are x_A - x_B in A's and B's axes)
  const Mat3 Ra = pose_a.q.toRotationMatrix(), Rb = pose_b.q.toRotationMatrix();
  const Mat3 R = Ra.transpose() * Rb, absR = R.cwiseAbs();
  const Vec3 &ha = a.half_extents, &hb = b.half_extents;
  const Vec3 t = pose_a.x - pose_b.x;
  const Vec3 ta = Ra.transpose() * t, tb = Rb.transpose() * t;
  // Test the 6 face axes; any positive gap is a separating plane
  // (along a_k: r_A = h_A,k, r_B = sum_j |R_kj| h_B,j; along b_k the same with R's column)
  Axis face;
  for (int k = 0; k < 3; ++k) {
    const double overlap = ha[k] + absR.row(k).dot(hb) - std::abs(ta[k]);
    if (overlap < 0.0) return Manifold{};
    if (clearlyBelow(overlap, face.overlap)) face = {overlap, ta[k] >= 0.0 ? Vec3(Ra.col(k)) : Vec3(-Ra.col(k)), k};
  }
  for (int k = 0; k < 3; ++k) {
    const double overlap = absR.col(k).dot(ha) + hb[k] - std::abs(tb[k]);
    if (overlap < 0.0) return Manifold{};
    if (clearlyBelow(overlap, face.overlap)) face = {overlap, tb[k] >= 0.0 ? Vec3(Rb.col(k)) : Vec3(-Rb.col(k)), 3 + k};
  }
  // Test the 9 edge-pair axes, skipping (near-)parallel edges whose faces were already tested
  // (in A's frame L = e_i x (column j of R), so radii and distance are two products each; neither
  // the test nor the ranking needs |L|: g / |L| < g* / |L*| for overlaps g, g* >= 0 along the
  // unnormalised axes is g^2 |L*|^2 < g*^2 |L|^2, so only the winner is divided by |L|)
  double best_g = 0.0, best_length2 = 0.0;
  int best_edge = -1;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double length2 = R(i1, j) * R(i1, j) + R(i2, j) * R(i2, j);
      if (length2 < 1e-12) continue;
      const double ra = ha[i1] * absR(i2, j) + ha[i2] * absR(i1, j);
      const double rb = hb[j1] * absR(i, j2) + hb[j2] * absR(i, j1);
      const double g = ra + rb - std::abs(ta[i2] * R(i1, j) - ta[i1] * R(i2, j));
      if (g < 0.0) return Manifold{};
      if (best_edge < 0 || g * g * best_length2 < best_g * best_g * length2) best_g = g, best_length2 = length2, best_edge = 3 * i + j;
    }
  }
  // Prefer a face axis unless an edge axis is clearly shallower
  if (best_edge >= 0 && best_g / std::sqrt(best_length2) < (1.0 - kEdgeAxisBias) * face.overlap) {
    // Edge-edge: one point between the two edges that reach furthest towards each other
    // (on the winner's unit world axis, its depth measured along that axis: the ranking above
    // divided by a length made of R's entries, exact only for an exactly orthonormal R)
    const int i = best_edge / 3, j = best_edge % 3;
    const Vec3 L = Ra.col(i).cross(Rb.col(j)).normalized();
    const Vec3 n = t.dot(L) >= 0.0 ? L : Vec3(-L);
    const double depth = (Ra.transpose() * L).cwiseAbs().dot(ha) + (Rb.transpose() * L).cwiseAbs().dot(hb) - std::abs(t.dot(L));
    Vec3 ca = pose_a.x, cb = pose_b.x;
    std::uint32_t code_a = 0, code_b = 0;
    for (int k = 0; k < 3; ++k) {
      const double sa = Ra.col(k).dot(n) > 0.0 ? -1.0 : 1.0, sb = Rb.col(k).dot(n) > 0.0 ? 1.0 : -1.0;
      if (k != i) ca += sa * ha[k] * Ra.col(k), code_a |= (sa > 0) << k;
      if (k != j) cb += sb * hb[k] * Rb.col(k), code_b |= (sb > 0) << k;
    }
    const Vec3 pa = ca - ha[i] * Ra.col(i), qa = ca + ha[i] * Ra.col(i);
    const Vec3 pb = cb - hb[j] * Rb.col(j), qb = cb + hb[j] * Rb.col(j);
    const std::array<double, 2> st = closestSegmentParameters(pa, qa, pb, qb);
    Manifold m;
    m.normal = n;
    m.add(0.5 * (pa + st[0] * (qa - pa) + pb + st[1] * (qb - pb)), depth,
          combineFeatures(100 + best_edge, 8 * code_a + code_b));
    return m;
  }
  // Face: the reference face is the winner's face towards the other box
  const bool ref_is_a = face.feature < 3;
  const int axis = face.feature % 3;
  const Mat3& Rr = ref_is_a ? Ra : Rb;
  const Mat3& Ri = ref_is_a ? Rb : Ra;
  const Vec3& hr = ref_is_a ? ha : hb;
  const Vec3& hi = ref_is_a ? hb : ha;
  const Vec3& xr = ref_is_a ? pose_a.x : pose_b.x;
  const Vec3& xi = ref_is_a ? pose_b.x : pose_a.x;
  const Vec3 n_ref = ref_is_a ? Vec3(-face.normal) : face.normal;  // out of the reference box
  // Find the incident face: the other box's face most anti-parallel to the reference normal
  const Vec3 along = Ri.transpose() * n_ref;
  Index m_axis;
  along.cwiseAbs().maxCoeff(&m_axis);
  const int u = (m_axis + 1) % 3, v = (m_axis + 2) % 3;
  Vec3 corner_signs = Vec3::Zero();
  corner_signs[m_axis] = along[m_axis] > 0.0 ? -1.0 : 1.0;
  FacePolygon polygon, clipped;
  const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
  for (int k = 0; k < 4; ++k) {
    corner_signs[u] = su[k];
    corner_signs[v] = sv[k];
    const std::uint32_t corner = (corner_signs.x() > 0) + 2 * (corner_signs.y() > 0) + 4 * (corner_signs.z() > 0);
    polygon.add(xi + Ri * corner_signs.cwiseProduct(hi), corner);
  }
  // Clip it by the four side planes of the reference face
  std::uint32_t plane_id = 0;
  for (int k = 1; k <= 2; ++k) {
    const Vec3 side = Rr.col((axis + k) % 3);
    const double extent = hr[(axis + k) % 3], centre = side.dot(xr);
    clipFace(polygon, side, centre + extent, plane_id++, clipped);
    clipFace(clipped, -side, -centre + extent, plane_id++, polygon);
  }
  // Keep the points below the reference face, at most 4
  // (moved half their depth up to the midpoint, compacted in place; reduceContacts returns 4 or
  // fewer as they are, so only a larger set pays for its 64-point candidate buffer)
  const std::uint32_t face_id = 2 * face.feature + (n_ref.dot(Rr.col(axis)) > 0.0);
  const double offset = n_ref.dot(xr) + hr[axis];
  std::array<double, FacePolygon::kCapacity> depth;
  int kept = 0;
  for (int k = 0; k < polygon.count; ++k) {
    const Vec3 p = polygon.points[k];
    depth[kept] = offset - n_ref.dot(p);
    if (depth[kept] < 0.0) continue;
    polygon.points[kept] = p + 0.5 * depth[kept] * n_ref;
    polygon.ids[kept++] = combineFeatures(face_id, polygon.ids[k]);
  }
  if (kept == 0) return Manifold{};
  if (kept <= Manifold::kMaxPoints) {
    Manifold m;
    m.normal = face.normal;
    for (int k = 0; k < kept; ++k) m.add(polygon.points[k], depth[k], polygon.ids[k]);
    return m;
  }
  ContactPolygon below;
  for (int k = 0; k < kept; ++k) below.add(polygon.points[k], depth[k], polygon.ids[k]);
  return reduceContacts(face.normal, below);
}

Manifold collideConvexConvex(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                             const Pose& pose_b) {
  // Refuse a shape changed after construction and a pose that is not finite or not unit
  validateShape(a, "shape a");
  validatePose(pose_a, "pose_a");
  validateShape(b, "shape b");
  validatePose(pose_b, "pose_b");
  // Move both into the world
  std::vector<Vec3> va(a.vertices.size()), vb(b.vertices.size());
  for (std::size_t i = 0; i < va.size(); ++i) va[i] = pose_a.toWorld(a.vertices[i]);
  for (std::size_t i = 0; i < vb.size(); ++i) vb[i] = pose_b.toWorld(b.vertices[i]);
  auto extent = [](const std::vector<Vec3>& v, const Vec3& L, double& lo, double& hi) {
    lo = hi = L.dot(v[0]);
    for (const Vec3& p : v) lo = std::min(lo, L.dot(p)), hi = std::max(hi, L.dot(p));
  };
  // Overlap along L, oriented from B to A: the smaller of the two ways the projections overlap
  auto overlapAlong = [&](const Vec3& L, Vec3& n) {
    double loa, hia, lob, hib;
    extent(va, L, loa, hia);
    extent(vb, L, lob, hib);
    const double a_above = hib - loa, a_below = hia - lob;
    n = a_above <= a_below ? L : Vec3(-L);
    return std::min(a_above, a_below);
  };
  const int fa = static_cast<int>(a.faces.size()), fb = static_cast<int>(b.faces.size());
  Axis face, edge;
  // Test every face normal of both; a positive gap is a separating plane
  // (one-sided: the face's own body lies below it, the other body must reach down past it)
  for (int f = 0; f < fa + fb; ++f) {
    const bool of_a = f < fa;
    const Vec3 L = of_a ? Vec3(pose_a.q * a.normals[f]) : Vec3(pose_b.q * b.normals[f - fa]);
    double loa, hia, lob, hib;
    extent(va, L, loa, hia);
    extent(vb, L, lob, hib);
    const double overlap = of_a ? hia - lob : hib - loa;
    if (overlap < 0.0) return Manifold{};
    if (clearlyBelow(overlap, face.overlap)) face = {overlap, of_a ? Vec3(-L) : L, f};
  }
  // Test the cross product of every pair of edge directions
  const int ea = static_cast<int>(a.edges.size()), eb = static_cast<int>(b.edges.size());
  for (int i = 0; i < ea; ++i) {
    const Vec3 da = va[a.edges[i][1]] - va[a.edges[i][0]];
    for (int j = 0; j < eb; ++j) {
      const Vec3 db = vb[b.edges[j][1]] - vb[b.edges[j][0]];
      Vec3 L = da.cross(db);
      const double length = L.norm();
      if (length < 1e-6 * da.norm() * db.norm()) continue;
      L /= length;
      Vec3 n;
      const double overlap = overlapAlong(L, n);
      if (overlap < 0.0) return Manifold{};
      if (overlap < edge.overlap) edge = {overlap, n, i * eb + j};
    }
  }
  // Prefer a face axis unless an edge axis is clearly shallower
  if (edge.feature >= 0 && edge.overlap < (1.0 - kEdgeAxisBias) * face.overlap) {
    // Edge-edge: among the edges parallel to the winners, those reaching furthest across
    const Vec3& n = edge.normal;
    const int i0 = edge.feature / eb, j0 = edge.feature % eb;
    const Vec3 da = (va[a.edges[i0][1]] - va[a.edges[i0][0]]).normalized();
    const Vec3 db = (vb[b.edges[j0][1]] - vb[b.edges[j0][0]]).normalized();
    int best_a = i0, best_b = j0;
    for (int i = 0; i < ea; ++i) {
      const Vec3 d = va[a.edges[i][1]] - va[a.edges[i][0]];
      const auto mid = [&](int k) { return n.dot(va[a.edges[k][0]] + va[a.edges[k][1]]); };
      if (d.normalized().cross(da).norm() < 1e-6 && mid(i) < mid(best_a)) best_a = i;
    }
    for (int j = 0; j < eb; ++j) {
      const Vec3 d = vb[b.edges[j][1]] - vb[b.edges[j][0]];
      const auto mid = [&](int k) { return n.dot(vb[b.edges[k][0]] + vb[b.edges[k][1]]); };
      if (d.normalized().cross(db).norm() < 1e-6 && mid(j) > mid(best_b)) best_b = j;
    }
    const Vec3 &pa = va[a.edges[best_a][0]], &qa = va[a.edges[best_a][1]];
    const Vec3 &pb = vb[b.edges[best_b][0]], &qb = vb[b.edges[best_b][1]];
    const std::array<double, 2> st = closestSegmentParameters(pa, qa, pb, qb);
    Manifold m;
    m.normal = n;
    m.add(0.5 * (pa + st[0] * (qa - pa) + pb + st[1] * (qb - pb)), edge.overlap,
          combineFeatures(1000 + best_a, static_cast<std::uint32_t>(best_b)));
    return m;
  }
  // Face: the reference face's outward normal points at the other body
  const bool ref_is_a = face.feature < fa;
  const ConvexPolyhedron& ref = ref_is_a ? a : b;
  const ConvexPolyhedron& inc = ref_is_a ? b : a;
  const std::vector<Vec3>& vr = ref_is_a ? va : vb;
  const std::vector<Vec3>& vi = ref_is_a ? vb : va;
  const Quat& qr = ref_is_a ? pose_a.q : pose_b.q;
  const Quat& qi = ref_is_a ? pose_b.q : pose_a.q;
  const int rf = ref_is_a ? face.feature : face.feature - fa;
  const Vec3 n_ref = qr * ref.normals[rf];
  // Find the incident face: the other body's face most anti-parallel to the reference normal
  int incident = 0;
  double most = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < inc.faces.size(); ++f) {
    const double c = n_ref.dot(qi * inc.normals[f]);
    if (c < most) most = c, incident = static_cast<int>(f);
  }
  ContactPolygon polygon;
  for (int i : inc.faces[incident]) polygon.add(vi[i], 0.0, static_cast<std::uint32_t>(i));
  // Clip it by the side planes through the reference face's edges
  const std::vector<int>& rface = ref.faces[rf];
  for (std::size_t k = 0; k < rface.size(); ++k) {
    const Vec3& p = vr[rface[k]];
    const Vec3 side = (vr[rface[(k + 1) % rface.size()]] - p).cross(n_ref).normalized();
    polygon = clipPolygon(polygon, side, side.dot(p), static_cast<std::uint32_t>(k));
  }
  // Keep the points below the reference face, at most 4
  const ContactPolygon below = keepBelow(polygon, n_ref, n_ref.dot(vr[rface[0]]), static_cast<std::uint32_t>(face.feature));
  if (below.count == 0) return Manifold{};
  return reduceContacts(face.normal, below);
}

}  // namespace physlab
