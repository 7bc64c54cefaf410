// Framework tests for Lab 4: shapes, poses and queries refuse input that makes no sense, with a
// message naming it; the polyhedron builders and scenes produce valid descriptions.
#include <cmath>
#include <limits>

#include "collision_support.hpp"
#include "physlab/collision.hpp"
#include "physlab/error.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

TEST_CASE("collision validation: sizes must be positive and finite", "[common]") {
  const double nan = std::nan("");
  CHECK_THROWS_WITH(Sphere(0.0), Contains("sphere radius"));
  CHECK_THROWS_WITH(Sphere(-1.0), Contains("sphere radius"));
  CHECK_THROWS_WITH(Sphere(nan), Contains("sphere radius"));
  CHECK_THROWS_WITH(Box(Vec3(1.0, 0.0, 1.0)), Contains("box half extent 1"));
  CHECK_THROWS_WITH(Box(Vec3(1.0, 1.0, -2.0)), Contains("box half extent 2"));
  CHECK_THROWS_WITH(Capsule(0.0, 1.0), Contains("capsule radius"));
  CHECK_THROWS_WITH(Capsule(1.0, -1.0), Contains("capsule half height"));
  CHECK_THROWS_WITH(Plane(Vec3::Zero(), 1.0), Contains("plane normal is zero"));
  CHECK_THROWS_WITH(Plane(Vec3(nan, 0, 1), 1.0), Contains("plane normal has a non-finite entry"));
  CHECK_THROWS_WITH(Triangle(Vec3::Zero(), Vec3::UnitX(), Vec3(2, 0, 0)), Contains("triangle is degenerate"));
  const Plane scaled(Vec3(0, 0, 2), 4.0);  // the same half-space z <= 2, normalised
  CHECK(scaled.normal == Vec3::UnitZ());
  CHECK(scaled.offset == 2.0);
}

TEST_CASE("collision validation: degenerate or inconsistent polyhedra are refused", "[common]") {
  const std::vector<Vec3> square = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  CHECK_THROWS_WITH(ConvexPolyhedron({Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()}, {{0, 1, 2}}),
                    Contains("at least 4 vertices"));
  CHECK_THROWS_WITH(ConvexPolyhedron::tetrahedron(square[0], square[1], square[2], square[3]), Contains("degenerate"));
  // A tetrahedron with one face wound the wrong way.
  const std::vector<Vec3> tet = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  CHECK_NOTHROW(ConvexPolyhedron(tet, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}));
  CHECK_THROWS_WITH(ConvexPolyhedron(tet, {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}), Contains("face 0"));
  // A missing face leaves edges with one face only.
  CHECK_THROWS_WITH(ConvexPolyhedron(tet, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {1, 2, 3}}), Contains("inconsistent"));
  CHECK_THROWS_WITH(ConvexPolyhedron(tet, {{0, 2, 1}, {0, 1, 3}, {1, 2, 9}, {0, 3, 2}}), Contains("out of range"));
  std::vector<Vec3> bad = tet;
  bad[3].z() = std::nan("");
  CHECK_THROWS_WITH(ConvexPolyhedron(bad, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}),
                    Contains("convex polyhedron vertex has a non-finite entry"));
  const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(1, 2, 3));
  CHECK(cube.vertices.size() == 8);
  CHECK(cube.faces.size() == 6);
  CHECK(cube.edges.size() == 12);
  CHECK_THROWS_WITH(ConvexPolyhedron::box(Vec3(1, 0, 1)), Contains("box half extent 1"));
}

TEST_CASE("collision validation: poses need a finite position and a unit quaternion", "[common]") {
  const Shape s = Sphere(1.0);
  Pose good, unnormalised, zero, nan;
  unnormalised.q = Quat(2, 0, 0, 0);
  zero.q = Quat(0, 0, 0, 0);
  nan.x = Vec3(0, std::nan(""), 0);
  CHECK_THROWS_WITH(collide(s, unnormalised, s, good), Contains("pose of shape A quaternion is not unit"));
  CHECK_THROWS_WITH(collide(s, good, s, zero), Contains("pose of shape B quaternion is not unit"));
  CHECK_THROWS_WITH(collide(s, nan, s, good), Contains("pose of shape A position has a non-finite entry"));
  CHECK_THROWS_WITH(distance(s, good, s, nan), Contains("pose of shape B position has a non-finite entry"));
  CHECK_THROWS_WITH(validatePose(unnormalised, "body 3"), Contains("body 3 quaternion is not unit"));
}

TEST_CASE("collision validation: pairs without a routine and planes are refused by name", "[common]") {
  const Shape plane = Plane(Vec3::UnitZ(), 0.0), tri = Triangle(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY());
  CHECK_THROWS_WITH(collide(plane, Pose{}, plane, Pose{}), Contains("plane against a plane"));
  CHECK_THROWS_WITH(collide(tri, Pose{}, Shape(Sphere(1.0)), Pose{}), Contains("triangle against a sphere"));
  CHECK_THROWS_WITH(distance(plane, Pose{}, plane, Pose{}), Contains("two planes"));
  CHECK_THROWS_WITH(support(plane, Pose{}, Vec3::UnitZ()), Contains("plane has no support point"));
}

TEST_CASE("collision framework: support points, bounding boxes and the plane distance", "[common]") {
  const Box box(Vec3(1, 2, 3));
  Pose pose;
  pose.x = Vec3(1, 1, 1);
  pose.q = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
  // Turned a quarter about z: body x is world y, body y is world -x.
  CHECK((support(box, pose, Vec3(1, 1, 1)) - Vec3(1 + 2, 1 + 1, 1 + 3)).norm() < 1e-12);
  const Aabb bounds = aabb(box, pose);
  CHECK((bounds.min - Vec3(-1, 0, -2)).norm() < 1e-12);
  CHECK((bounds.max - Vec3(3, 2, 4)).norm() < 1e-12);
  const Aabb ground = aabb(Plane(Vec3::UnitZ(), 0.5), Pose{});
  CHECK(ground.max.z() == 0.5);
  CHECK(std::isinf(ground.min.z()));
  CHECK(support(Capsule(0.5, 1.0), Pose{}, Vec3(0, 0, 2)).isApprox(Vec3(0, 0, 1.5)));
  // A sphere of radius 0.5 at height 2 is 1.5 above the ground.
  Pose up;
  up.x = Vec3(0, 0, 2);
  const DistanceResult d = distance(Sphere(0.5), up, Plane(Vec3::UnitZ(), 0.0), Pose{});
  CHECK(d.distance == Approx(1.5));
  CHECK(d.point_b.isApprox(Vec3(0, 0, 0)));
  // Scenes are valid and reproducible.
  CHECK(shapeSoup(20, 5.0, 7).size() == 20);
  CHECK(boxStack(3).size() == 4);
  CHECK(boxPyramid(3).size() == 7);
  const Pose turned = advance(Pose{}, Motion{Vec3(1, 0, 0), Vec3(0, 0, M_PI)}, 0.5);
  CHECK(turned.x.isApprox(Vec3(0.5, 0, 0)));
  CHECK(turned.q.angularDistance(Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()))) < 1e-12);
}

TEST_CASE("collision framework: spheres and capsules against boxes and polyhedra", "[common]") {
  const Box box(Vec3(uniform(0.5, 1.0), uniform(0.5, 1.0), uniform(0.3, 0.6)));
  const Pose pb = randomPose(1.0);
  const double r = uniform(0.1, 0.3), overlap = uniform(0.01, 0.05);
  const Vec3 up = pb.q * Vec3::UnitZ();
  // A sphere over the top face, and one whose centre is just inside it.
  Pose pa;
  pa.x = pb.toWorld(Vec3(0.1, -0.1, box.half_extents.z() + r - overlap));
  const Manifold shallow = collide(Sphere(r), pa, ConvexPolyhedron::box(box.half_extents), pb);
  REQUIRE(shallow.count == 1);
  CHECK(shallow.points[0].depth == Approx(overlap).margin(1e-9));  // golden-section search: ~1e-12
  CHECK((shallow.normal - up).norm() < 1e-9);
  pa.x = pb.toWorld(Vec3(0.1, -0.1, box.half_extents.z() - overlap));
  const Manifold deep = collide(Sphere(r), pa, ConvexPolyhedron::box(box.half_extents), pb);
  REQUIRE(deep.count == 1);
  CHECK(deep.points[0].depth == Approx(r + overlap).margin(1e-12));  // round-off only
  CHECK((deep.normal - up).norm() < 1e-12);
  // A capsule lying on the top face touches at both ends, shallow and deep; swapped, the normal flips.
  const Capsule capsule(r, 0.3);
  for (double sink : {overlap, r + overlap}) {
    Pose pc;
    pc.q = (pb.q * Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()))).normalized();
    pc.x = pb.toWorld(Vec3(0.0, 0.1, box.half_extents.z() + r - sink));
    const Manifold m = collide(capsule, pc, box, pb);
    INFO("sunk " << sink);
    REQUIRE(m.count == 2);
    CHECK((m.normal - up).norm() < 1e-9);
    for (int k = 0; k < 2; ++k) CHECK(m.points[k].depth == Approx(sink).margin(1e-9));
    const Manifold swapped = collide(box, pb, capsule, pc);
    CHECK((swapped.normal + up).norm() < 1e-9);
  }
  // Apart: nothing.
  pa.x = pb.toWorld(Vec3(0.0, 0.0, box.half_extents.z() + r + 0.01));
  CHECK(collide(Sphere(r), pa, ConvexPolyhedron::box(box.half_extents), pb).empty());
}

TEST_CASE("collision framework: rounded pairs are empty when apart and follow rigid motions", "[common]") {
  const std::pair<Kind, Kind> pairs[] = {{Kind::Sphere, Kind::Tetrahedron}, {Kind::Capsule, Kind::Box},
                                         {Kind::Capsule, Kind::Tetrahedron}};
  for (const auto& [ka, kb] : pairs) {
    int touching = 0;
    for (int trial = 0; trial < 40; ++trial) {
      const Shape a = randomShape(ka);
      Shape b = randomShape(kb), far = b;
      Pose pa = randomPose(1.0), pb = randomPose(1.0), pfar = pa;
      const Vec3 u = randomUnit();
      placeAlong(a, pfar, far, pb, u, uniform(1e-4, 0.5));
      placeAlong(a, pa, b, pb, u, -uniform(0.01, 0.2));
      INFO(pairName(a, b) << ", trial " << trial);
      CHECK(collide(a, pfar, far, pb).empty());
      const Manifold m = collide(a, pa, b, pb);
      if (m.empty()) continue;
      ++touching;
      const Mat3 Q = randomRotation();
      const Vec3 T = randomVec3(5.0);
      const Manifold m2 = collide(a, moved(pa, Q, T), b, moved(pb, Q, T));
      REQUIRE(m2.count == m.count);
      // A golden-section search finds a minimum only to ~sqrt(machine epsilon) of the core's length.
      CHECK((Q * m.normal - m2.normal).norm() < 1e-4);
      for (int i = 0; i < m.count; ++i) {
        CHECK((Q * m.points[i].position + T - m2.points[i].position).norm() < 1e-4);
        CHECK(signedDistance(a, pa, m.points[i].position) <= 0.5 * m.points[i].depth + 1e-8);
        CHECK(signedDistance(b, pb, m.points[i].position) <= 0.5 * m.points[i].depth + 1e-8);
      }
    }
    CHECK(touching > 10);  // extreme points pushed into each other: most trials touch
  }
}
