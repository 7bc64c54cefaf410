// Shapes as a replay records them (physlab/replay.hpp): sizes, or a triangle mesh for polyhedra.
#include <algorithm>
#include <type_traits>
#include <variant>

#include "physlab/collision.hpp"
#include "physlab/replay.hpp"

namespace physlab {
namespace {

std::array<float, 3> floats(const Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

// A polygon mesh as triangles: each face a fan from its first vertex.
void addMesh(ReplayBody& body, const std::vector<Vec3>& vertices, const std::vector<std::vector<int>>& faces) {
  body.kind = ReplayShapeKind::Convex;
  for (const Vec3& v : vertices) {
    for (float c : floats(v)) body.vertices.push_back(c);
  }
  for (const std::vector<int>& face : faces) {
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      for (int v : {face[0], face[k], face[k + 1]}) body.triangles.push_back(static_cast<std::uint32_t>(v));
    }
  }
}

}  // namespace

ReplayBody replayBody(const Shape& shape, bool fixed) {
  ReplayBody body;
  body.fixed = fixed;
  std::visit(
      [&body](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Sphere>) {
          body.kind = ReplayShapeKind::Sphere;
          body.size[0] = static_cast<float>(s.radius);
        } else if constexpr (std::is_same_v<T, Box>) {
          body.kind = ReplayShapeKind::Box;
          const std::array<float, 3> h = floats(s.half_extents);
          std::copy(h.begin(), h.end(), body.size.begin());
        } else if constexpr (std::is_same_v<T, Capsule>) {
          body.kind = ReplayShapeKind::Capsule;
          body.size[0] = static_cast<float>(s.radius);
          body.size[1] = static_cast<float>(s.half_height);
        } else if constexpr (std::is_same_v<T, Plane>) {
          body.kind = ReplayShapeKind::Plane;
          const std::array<float, 3> n = floats(s.normal);
          std::copy(n.begin(), n.end(), body.size.begin());
          body.size[3] = static_cast<float>(s.offset);
        } else if constexpr (std::is_same_v<T, ConvexPolyhedron>) {
          addMesh(body, s.vertices, s.faces);
        } else {
          static_assert(std::is_same_v<T, Triangle>, "every Shape is recorded");
          addMesh(body, {s.corners.begin(), s.corners.end()}, {{0, 1, 2}, {0, 2, 1}});
        }
      },
      shape);
  return body;
}

}  // namespace physlab
