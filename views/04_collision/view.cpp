// Lab 4 scenes for the 3-D viewer (./physlab view 04): shapes moved along set paths (no dynamics:
// that is Lab 5) and the narrow phase's manifold of every touching pair, frame by frame.
#include <cmath>
#include <cstdint>
#include <vector>

#include "physlab/collision.hpp"
#include "physlab/replay.hpp"
#include "physlab/view.hpp"

using namespace physlab;

namespace {

constexpr double kHalfPi = 1.5707963267948966;  // a quarter turn [rad]

// Appends every touching pair's manifold (collide()) to `frame`, the impulse left at 0.
void addContacts(const std::vector<Shape>& shapes, const std::vector<Pose>& poses, ReplayFrame& frame) {
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    for (std::size_t j = i + 1; j < shapes.size(); ++j) {
      if (std::holds_alternative<Plane>(shapes[i]) && std::holds_alternative<Plane>(shapes[j])) continue;
      const Manifold m = collide(shapes[i], poses[i], shapes[j], poses[j]);
      for (int k = 0; k < m.count; ++k) {
        ReplayContact& c = frame.contacts.emplace_back();
        c.a = static_cast<std::uint32_t>(i);
        c.b = static_cast<std::uint32_t>(j);
        const Vec3& p = m.points[static_cast<std::size_t>(k)].position;
        c.p = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
        c.n = {static_cast<float>(m.normal.x()), static_cast<float>(m.normal.y()), static_cast<float>(m.normal.z())};
        c.depth = static_cast<float>(m.points[static_cast<std::size_t>(k)].depth);
      }
    }
  }
}

// Shapes in pairs that pass through each other: a box sliding and rocking over the ground into a
// fixed box, a sphere circling through a capsule, two polyhedra (a box and a tetrahedron)
// crossing, a capsule rolling over the ground. 6 s at 50 frames a second.
Replay passingShapes() {
  const std::vector<Shape> shapes = {
      Plane(Vec3::UnitZ(), 0.0),
      Box(Vec3(0.3, 0.2, 0.1)),
      Box(Vec3(0.2, 0.2, 0.25)),
      Sphere(0.15),
      Capsule(0.1, 0.3),
      ConvexPolyhedron::box(Vec3(0.15, 0.15, 0.15)),
      ConvexPolyhedron::tetrahedron(Vec3(0.25, 0, -0.1), Vec3(-0.15, 0.2, -0.1), Vec3(-0.15, -0.2, -0.1),
                                    Vec3(0, 0, 0.25)),
      Capsule(0.08, 0.25),
  };
  const std::vector<bool> fixed = {true, false, true, false, true, false, false, false};
  Replay replay;
  replay.title = "Lab 4: shapes passing through each other, with their contact manifolds";
  replay.settings = "kinematic paths (no dynamics); contacts from collide() of every pair";
  for (std::size_t i = 0; i < shapes.size(); ++i) replay.bodies.push_back(replayBody(shapes[i], fixed[i]));
  std::vector<Pose> poses(shapes.size());
  const double h = 0.02;
  for (int n = 0; n <= 300; ++n) {
    const double t = n * h;
    poses[1].x = Vec3(-1.2 + 0.3 * t, 0.0, 0.09 + 0.03 * std::sin(3 * t));
    poses[1].q = Quat(Eigen::AngleAxisd(0.4 * t, Vec3::UnitZ()) * Eigen::AngleAxisd(0.15 * std::sin(2 * t), Vec3::UnitX()));
    poses[2].x = Vec3(0.2, 0.0, 0.25);
    poses[3].x = Vec3(0.3 * std::cos(t), 1.0 + 0.3 * std::sin(t), 0.6);
    poses[4].x = Vec3(0.0, 1.0, 0.6);
    poses[4].q = Quat(Eigen::AngleAxisd(kHalfPi, Vec3::UnitX()));
    poses[5].x = Vec3(-0.6 + 0.2 * t, -1.0, 0.5);
    poses[5].q = Quat(Eigen::AngleAxisd(0.5 * t, Vec3(1, 1, 0).normalized()));
    poses[6].x = Vec3(0.6 - 0.2 * t, -1.0, 0.45);
    poses[6].q = Quat(Eigen::AngleAxisd(-0.7 * t, Vec3::UnitZ()));
    poses[7].x = Vec3(1.0, -0.8 + 0.3 * t, 0.07);
    poses[7].q = Quat(Eigen::AngleAxisd(kHalfPi, Vec3::UnitY()) * Eigen::AngleAxisd(0.3 * t / 0.08, Vec3::UnitZ()));
    std::vector<Vec3> x;
    std::vector<Quat> q;
    for (const Pose& pose : poses) {
      x.push_back(pose.x);
      q.push_back(pose.q);
    }
    recordPoses(replay, t, x, q, 0.0, 0.0);
    addContacts(shapes, poses, replay.frames.back());
  }
  return replay;
}

}  // namespace

int main(int argc, char** argv) {
  return runView(argc, argv, {{"passing", "shapes passing through each other, with their contact manifolds", passingShapes}});
}
