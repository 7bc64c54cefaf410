// Recording a World: its shapes once (startReplay), then a frame per call (recordFrame).
#include <algorithm>
#include <type_traits>
#include <variant>

#include "physlab/error.hpp"
#include "physlab/replay.hpp"
#include "physlab/world.hpp"

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

ReplayBody recordedShape(const BodyDescription& description) {
  ReplayBody body;
  body.fixed = description.fixed;
  std::visit(
      [&body](const auto& shape) {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, Sphere>) {
          body.kind = ReplayShapeKind::Sphere;
          body.size[0] = static_cast<float>(shape.radius);
        } else if constexpr (std::is_same_v<T, Box>) {
          body.kind = ReplayShapeKind::Box;
          const std::array<float, 3> h = floats(shape.half_extents);
          std::copy(h.begin(), h.end(), body.size.begin());
        } else if constexpr (std::is_same_v<T, Capsule>) {
          body.kind = ReplayShapeKind::Capsule;
          body.size[0] = static_cast<float>(shape.radius);
          body.size[1] = static_cast<float>(shape.half_height);
        } else if constexpr (std::is_same_v<T, Plane>) {
          body.kind = ReplayShapeKind::Plane;
          const std::array<float, 3> n = floats(shape.normal);
          std::copy(n.begin(), n.end(), body.size.begin());
          body.size[3] = static_cast<float>(shape.offset);
        } else if constexpr (std::is_same_v<T, ConvexPolyhedron>) {
          addMesh(body, shape.vertices, shape.faces);
        } else {
          static_assert(std::is_same_v<T, Triangle>, "every Shape is recorded");
          addMesh(body, {shape.corners.begin(), shape.corners.end()}, {{0, 1, 2}, {0, 2, 1}});
        }
      },
      description.shape);
  return body;
}

}  // namespace

Replay startReplay(const World& world, std::string title) {
  Replay replay;
  replay.title = std::move(title);
  replay.settings = world.describe();
  replay.bodies.reserve(world.bodies().size());
  for (const BodyDescription& description : world.bodies()) replay.bodies.push_back(recordedShape(description));
  return replay;
}

void recordFrame(const World& world, Replay& replay) {
  const std::vector<BodyState>& states = world.states();
  if (states.size() != replay.bodies.size()) {
    throw InvalidInput("recordFrame: the World has " + std::to_string(states.size()) + " bodies, the replay " +
                       std::to_string(replay.bodies.size()));
  }
  const Diagnostics& diagnostics = world.diagnostics();
  ReplayFrame& frame = replay.frames.emplace_back();
  frame.time = static_cast<float>(world.time());
  frame.kinetic_energy = static_cast<float>(diagnostics.kinetic_energy);
  frame.potential_energy = static_cast<float>(diagnostics.potential_energy);
  frame.iterations = static_cast<std::uint32_t>(diagnostics.iterations);
  frame.poses.reserve(7 * states.size());
  for (const BodyState& s : states) {
    for (double v : {s.x.x(), s.x.y(), s.x.z(), s.q.w(), s.q.x(), s.q.y(), s.q.z()}) {
      frame.poses.push_back(static_cast<float>(v));
    }
  }
  frame.contacts.reserve(world.contacts().size());
  for (const Contact& c : world.contacts()) {
    ReplayContact& r = frame.contacts.emplace_back();
    r.a = static_cast<std::uint32_t>(c.a);
    r.b = static_cast<std::uint32_t>(c.b);
    r.p = floats(c.p);
    r.n = floats(c.n);
    r.depth = static_cast<float>(c.depth);
    r.j = static_cast<float>(c.j);
  }
}

}  // namespace physlab
