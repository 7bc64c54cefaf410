// Framework half of Lab 4: shape descriptions and their validation, poses, support points,
// bounding boxes and radii. The collision routines themselves are the student's.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Newell's normal of a polygon: robust for any planar polygon, zero for a degenerate one.
Vec3 newellNormal(const std::vector<Vec3>& vertices, const std::vector<int>& face) {
  Vec3 n = Vec3::Zero();
  for (std::size_t k = 0; k < face.size(); ++k) {
    const Vec3& p = vertices[face[k]];
    const Vec3& q = vertices[face[(k + 1) % face.size()]];
    n += Vec3((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()),
              (p.x() - q.x()) * (p.y() + q.y()));
  }
  return n;
}

// Reverses a face whose winding points its normal towards the centroid (builders only).
void orientOutward(const std::vector<Vec3>& vertices, std::vector<int>& face, const Vec3& centroid) {
  if (newellNormal(vertices, face).dot(vertices[face[0]] - centroid) < 0.0) std::reverse(face.begin(), face.end());
}

// The message of a refused pose, motion or shape, built out of line and only on failure.
[[noreturn, gnu::cold, gnu::noinline]] void refuse(std::string_view what, const std::string& problem) {
  throw InvalidInput(std::string(what) + problem);
}

// Refuses `field` of the shape `what` unless `value` is positive and finite.
void requireLength(double value, std::string_view what, const char* field) {
  if (!(std::isfinite(value) && value > 0.0)) {
    refuse(what, std::string(": ") + field + " must be positive and finite, got " + std::to_string(value));
  }
}

}  // namespace

void refuseBadPose(const Pose& pose, std::string_view what) {
  if (const Index k = firstNonFinite(pose.x); k >= 0) {
    refuse(what, " position has a non-finite entry at (" + std::to_string(k) + ", 0)");
  }
  if (const Index k = firstNonFinite(pose.q.coeffs()); k >= 0) {
    refuse(what, " quaternion has a non-finite entry at (" + std::to_string(k) + ", 0)");
  }
  if (const double norm = pose.q.norm(); std::abs(norm - 1.0) > 1e-6) {
    refuse(what, " quaternion is not unit (norm " + std::to_string(norm) + ")");
  }
}

void validateMotion(const Motion& motion, std::string_view what) {
  if (const Index k = firstNonFinite(motion.v); k >= 0) {
    refuse(what, " velocity v has a non-finite entry at (" + std::to_string(k) + ", 0)");
  }
  if (const Index k = firstNonFinite(motion.omega); k >= 0) {
    refuse(what, " angular velocity omega has a non-finite entry at (" + std::to_string(k) + ", 0)");
  }
}

void validateShape(const Sphere& sphere, std::string_view what) { requireLength(sphere.radius, what, "sphere radius"); }

void refuseBadBox(const Box& box, std::string_view what) {
  static constexpr const char* fields[] = {"box half extent 0", "box half extent 1", "box half extent 2"};
  for (int i = 0; i < 3; ++i) requireLength(box.half_extents[i], what, fields[i]);
}

void validateShape(const Capsule& capsule, std::string_view what) {
  requireLength(capsule.radius, what, "capsule radius");
  requireLength(capsule.half_height, what, "capsule half height");
}

void validateShape(const Plane& plane, std::string_view what) {
  if (const double length = plane.normal.norm(); !(std::abs(length - 1.0) <= 1e-9)) {
    refuse(what, ": plane normal must be a finite unit vector, got length " + std::to_string(length));
  }
  if (!std::isfinite(plane.offset)) refuse(what, ": plane offset must be finite, got " + std::to_string(plane.offset));
}

void validateShape(const Triangle& triangle, std::string_view what) {
  const std::array<Vec3, 3>& c = triangle.corners;
  for (int k = 0; k < 3; ++k) {
    if (firstNonFinite(c[k]) >= 0) refuse(what, ": triangle corner " + std::to_string(k) + " is not finite");
  }
  const double scale = std::max({(c[1] - c[0]).norm(), (c[2] - c[1]).norm(), (c[0] - c[2]).norm()});
  if (!((c[1] - c[0]).cross(c[2] - c[0]).norm() > 1e-12 * scale * scale)) {
    refuse(what, ": triangle is degenerate (zero area)");
  }
}

void validateShape(const ConvexPolyhedron& polyhedron, std::string_view what) {
  const ConvexPolyhedron& p = polyhedron;
  const int n = static_cast<int>(p.vertices.size());
  const std::size_t faces = p.faces.size();
  if (n < 4 || faces < 4) refuse(what, ": convex polyhedron needs at least 4 vertices and 4 faces");
  for (int i = 0; i < n; ++i) {
    if (firstNonFinite(p.vertices[i]) >= 0) {
      refuse(what, ": convex polyhedron vertex " + std::to_string(i) + " is not finite");
    }
  }
  if (p.normals.size() != faces || p.offsets.size() != faces) {
    refuse(what, ": convex polyhedron needs one normal and one offset per face");
  }
  auto inRange = [n](int i) { return i >= 0 && i < n; };
  for (std::size_t f = 0; f < faces; ++f) {
    const std::vector<int>& face = p.faces[f];
    if (face.size() < 3 || face.size() > 32 || !std::all_of(face.begin(), face.end(), inRange)) {
      refuse(what, ": convex polyhedron face " + std::to_string(f) + " needs 3 to 32 vertex indices in range");
    }
    if (!(std::abs(p.normals[f].norm() - 1.0) <= 1e-9)) {
      refuse(what, ": convex polyhedron normal " + std::to_string(f) + " must be a finite unit vector");
    }
    if (!std::isfinite(p.offsets[f])) {
      refuse(what, ": convex polyhedron offset " + std::to_string(f) + " is not finite");
    }
  }
  for (const std::array<int, 2>& edge : p.edges) {
    if (!inRange(edge[0]) || !inRange(edge[1])) {
      refuse(what, ": convex polyhedron edge has a vertex index out of range");
    }
  }
}

void validateShape(const Shape& shape, std::string_view what) {
  std::visit([what](const auto& s) { validateShape(s, what); }, shape);
}

Pose advance(const Pose& pose, const Motion& motion, double t) {
  Pose moved;
  moved.x = pose.x + t * motion.v;
  const double angle = motion.omega.norm() * t;
  moved.q = angle == 0.0 ? pose.q : (Quat(Eigen::AngleAxisd(angle, motion.omega.normalized())) * pose.q).normalized();
  return moved;
}

Sphere::Sphere(double radius_) : radius(radius_) { requirePositive(radius, "sphere radius"); }

Box::Box(const Vec3& half_extents_) : half_extents(half_extents_) {
  for (int i = 0; i < 3; ++i) requirePositive(half_extents[i], "box half extent " + std::to_string(i));
}

Capsule::Capsule(double radius_, double half_height_) : radius(radius_), half_height(half_height_) {
  requirePositive(radius, "capsule radius");
  requirePositive(half_height, "capsule half height");
}

std::array<Vec3, 2> Capsule::segment(const Pose& pose) const {
  const Vec3 axis = pose.q * Vec3(0.0, 0.0, half_height);
  return {pose.x - axis, pose.x + axis};
}

Plane::Plane(const Vec3& normal_, double offset_) : normal(normal_), offset(offset_) {
  requireFinite(normal, "plane normal");
  if (!std::isfinite(offset)) throw InvalidInput("plane offset must be finite");
  const double length = normal.norm();
  if (!(length > 0.0)) throw InvalidInput("plane normal is zero");
  normal /= length;
  offset /= length;
}

Triangle::Triangle(const Vec3& a, const Vec3& b, const Vec3& c) : corners{a, b, c} {
  for (const Vec3& p : corners) requireFinite(p, "triangle corner");
  const double scale = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  if (!((b - a).cross(c - a).norm() > 1e-12 * scale * scale)) throw InvalidInput("triangle is degenerate (zero area)");
}

ConvexPolyhedron::ConvexPolyhedron(std::vector<Vec3> vertices_, std::vector<std::vector<int>> faces_)
    : vertices(std::move(vertices_)), faces(std::move(faces_)) {
  const int n = static_cast<int>(vertices.size());
  if (n < 4) throw InvalidInput("convex polyhedron needs at least 4 vertices, got " + std::to_string(n));
  for (const Vec3& v : vertices) requireFinite(v, "convex polyhedron vertex");
  if (faces.size() < 4) throw InvalidInput("convex polyhedron needs at least 4 faces");
  Vec3 lo = vertices[0], hi = vertices[0];
  for (const Vec3& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double tolerance = 1e-9 * (hi - lo).norm();  // round-off of coordinates of this size
  std::map<std::pair<int, int>, int> directed;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::vector<int>& face = faces[f];
    const std::string name = "convex polyhedron face " + std::to_string(f);
    if (face.size() < 3 || face.size() > 32) throw InvalidInput(name + " must have 3 to 32 vertices");
    for (int i : face) {
      if (i < 0 || i >= n) throw InvalidInput(name + " has a vertex index out of range");
    }
    const Vec3 area = newellNormal(vertices, face);
    if (!(area.norm() > tolerance * tolerance)) throw InvalidInput(name + " is degenerate (zero area)");
    const Vec3 normal = area.normalized();
    Vec3 centre = Vec3::Zero();
    for (int i : face) centre += vertices[i];
    centre /= static_cast<double>(face.size());
    const double offset = normal.dot(centre);
    for (int i : face) {
      if (std::abs(normal.dot(vertices[i]) - offset) > tolerance) throw InvalidInput(name + " is not planar");
    }
    for (const Vec3& v : vertices) {
      if (normal.dot(v) - offset > tolerance) {
        throw InvalidInput(name + " has vertices outside its plane (not convex, or wound clockwise)");
      }
    }
    normals.push_back(normal);
    offsets.push_back(offset);
    for (std::size_t k = 0; k < face.size(); ++k) {
      const std::pair<int, int> edge(face[k], face[(k + 1) % face.size()]);
      if (++directed[edge] > 1) throw InvalidInput(name + " repeats an edge: faces are inconsistent");
    }
  }
  for (const auto& [edge, count] : directed) {
    (void)count;
    if (directed.count({edge.second, edge.first}) != 1) {
      throw InvalidInput("convex polyhedron edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) +
                         " is not shared by two faces in opposite directions: faces are inconsistent");
    }
    if (edge.first < edge.second) edges.push_back({edge.first, edge.second});
  }
  double height = 0.0;
  for (const Vec3& v : vertices) height = std::max(height, std::abs(normals[0].dot(v) - offsets[0]));
  if (!(height > tolerance)) throw InvalidInput("convex polyhedron vertices are coplanar");
}

ConvexPolyhedron ConvexPolyhedron::box(const Vec3& h) {
  for (int i = 0; i < 3; ++i) requirePositive(h[i], "box half extent " + std::to_string(i));
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  std::vector<std::vector<int>> f = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  for (auto& face : f) orientOutward(v, face, Vec3::Zero());
  return ConvexPolyhedron(std::move(v), std::move(f));
}

ConvexPolyhedron ConvexPolyhedron::tetrahedron(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  std::vector<Vec3> v = {a, b, c, d};
  for (const Vec3& p : v) requireFinite(p, "tetrahedron corner");
  const double scale = std::max({(b - a).norm(), (c - a).norm(), (d - a).norm()});
  if (!(std::abs((b - a).cross(c - a).dot(d - a)) > 1e-12 * scale * scale * scale)) {
    throw InvalidInput("tetrahedron is degenerate (its corners are coplanar)");
  }
  const Vec3 centroid = (a + b + c + d) / 4.0;
  std::vector<std::vector<int>> f = {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  for (auto& face : f) orientOutward(v, face, centroid);
  return ConvexPolyhedron(std::move(v), std::move(f));
}

const char* shapeName(const Shape& shape) {
  static constexpr const char* names[] = {"sphere", "box", "capsule", "plane", "convex polyhedron", "triangle"};
  return names[shape.index()];
}

double margin(const Shape& shape) {
  if (const auto* s = std::get_if<Sphere>(&shape)) return s->radius;
  if (const auto* c = std::get_if<Capsule>(&shape)) return c->radius;
  return 0.0;
}

Vec3 coreSupport(const Shape& shape, const Pose& pose, const Vec3& d) {
  const Vec3 db = pose.q.conjugate() * d;  // the direction in the body frame
  switch (shape.index()) {
    case 0:
      return pose.x;
    case 1: {
      const Vec3& h = std::get<Box>(shape).half_extents;
      return pose.toWorld(Vec3(db.x() >= 0 ? h.x() : -h.x(), db.y() >= 0 ? h.y() : -h.y(), db.z() >= 0 ? h.z() : -h.z()));
    }
    case 2: {
      const double h = std::get<Capsule>(shape).half_height;
      return pose.toWorld(Vec3(0.0, 0.0, db.z() >= 0 ? h : -h));
    }
    case 3:
      throw InvalidInput("a plane has no support point (it is unbounded)");
    case 4: {
      const std::vector<Vec3>& v = std::get<ConvexPolyhedron>(shape).vertices;
      std::size_t best = 0;
      double best_value = db.dot(v[0]);
      for (std::size_t i = 1; i < v.size(); ++i) {
        const double value = db.dot(v[i]);
        if (value > best_value) best_value = value, best = i;
      }
      return pose.toWorld(v[best]);
    }
    default: {
      const std::array<Vec3, 3>& c = std::get<Triangle>(shape).corners;
      int best = 0;
      for (int i = 1; i < 3; ++i) {
        if (db.dot(c[i]) > db.dot(c[best])) best = i;
      }
      return pose.toWorld(c[best]);
    }
  }
}

Vec3 support(const Shape& shape, const Pose& pose, const Vec3& d) {
  const Vec3 core = coreSupport(shape, pose, d);
  const double r = margin(shape), length = d.norm();
  return (r == 0.0 || length == 0.0) ? core : Vec3(core + (r / length) * d);
}

Aabb aabb(const Shape& shape, const Pose& pose) {
  if (const auto* plane = std::get_if<Plane>(&shape)) {
    Aabb box{Vec3::Constant(-kInf), Vec3::Constant(kInf)};
    for (int k = 0; k < 3; ++k) {
      if (plane->normal[k] == 1.0) box.max[k] = plane->offset;
      if (plane->normal[k] == -1.0) box.min[k] = -plane->offset;
    }
    return box;
  }
  // A box reaches |R| h from its centre along the world axes, where its support points along
  // them lie (the general path below, with no search)
  if (const auto* b = std::get_if<Box>(&shape)) {
    const Vec3 reach = pose.q.toRotationMatrix().cwiseAbs() * b->half_extents;
    return {pose.x - reach, pose.x + reach};
  }
  // The support points along the six axis directions bound the shape exactly.
  Aabb box;
  for (int k = 0; k < 3; ++k) {
    box.max[k] = support(shape, pose, Vec3::Unit(k))[k];
    box.min[k] = support(shape, pose, -Vec3::Unit(k))[k];
  }
  return box;
}

double boundingRadius(const Shape& shape) {
  switch (shape.index()) {
    case 0:
      return std::get<Sphere>(shape).radius;
    case 1:
      return std::get<Box>(shape).half_extents.norm();
    case 2:
      return std::get<Capsule>(shape).half_height + std::get<Capsule>(shape).radius;
    case 3:
      return kInf;
    case 4: {
      double r = 0.0;
      for (const Vec3& v : std::get<ConvexPolyhedron>(shape).vertices) r = std::max(r, v.norm());
      return r;
    }
    default: {
      double r = 0.0;
      for (const Vec3& v : std::get<Triangle>(shape).corners) r = std::max(r, v.norm());
      return r;
    }
  }
}

double innerRadius(const Shape& shape) {
  switch (shape.index()) {
    case 0:
      return std::get<Sphere>(shape).radius;
    case 1:
      return std::get<Box>(shape).half_extents.minCoeff();
    case 2:
      return std::get<Capsule>(shape).radius;
    case 3:
      return kInf;
    case 4: {
      const ConvexPolyhedron& p = std::get<ConvexPolyhedron>(shape);
      double r = kInf;
      for (double o : p.offsets) r = std::min(r, o);
      return std::max(r, 0.0);
    }
    default:
      return 0.0;
  }
}

void validatePolygon(const ContactPolygon& polygon, std::string_view what) {
  if (polygon.count < 0 || polygon.count > ContactPolygon::kCapacity) {
    refuse(what, " count " + std::to_string(polygon.count) + " is outside [0, " +
                     std::to_string(ContactPolygon::kCapacity) + "]");
  }
  // One sum is finite exactly when every term is (barring overflow): the search only on failure
  double sum = 0.0;
  for (int i = 0; i < polygon.count; ++i) sum += polygon.points[i].position.sum() + polygon.points[i].depth;
  if (std::isfinite(sum)) return;
  for (int i = 0; i < polygon.count; ++i) {
    const ContactPoint& p = polygon.points[i];
    if (firstNonFinite(p.position) >= 0 || !std::isfinite(p.depth)) {
      refuse(what, " point " + std::to_string(i) + " has a position or depth that is not finite");
    }
  }
}

double Manifold::maxDepth() const {
  double deepest = 0.0;
  for (int i = 0; i < count; ++i) deepest = std::max(deepest, points[i].depth);
  return deepest;
}

double approachSpeedBound(const Shape& a, const Motion& motion_a, const Shape& b, const Motion& motion_b,
                          const Vec3& n) {
  const bool a_static = std::holds_alternative<Plane>(a), b_static = std::holds_alternative<Plane>(b);
  const Vec3 va = a_static ? Vec3::Zero() : motion_a.v, vb = b_static ? Vec3::Zero() : motion_b.v;
  double mu = (vb - va).dot(n);
  if (!a_static) mu += motion_a.omega.norm() * boundingRadius(a);
  if (!b_static) mu += motion_b.omega.norm() * boundingRadius(b);
  return mu;
}

}  // namespace physlab
