// Lab 4: shapes, poses and queries refuse input that makes no sense, with a message naming it.
// The framework's checks ([common]: constructors, collide(), distance()) and the polyhedron
// builders and scenes first; then the graded checks of the student routines themselves.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

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

// ---------------------------------------------------------------------------------------------
// Graded: every student routine refuses bad shapes, poses, motions and points itself, naming the
// argument, before it computes anything (a NaN pose used to give a contact of depth NaN).

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A pose at x with the identity orientation.
Pose at(const Vec3& x) {
  Pose p;
  p.x = x;
  return p;
}

// Poses every routine must refuse, each with the words its message must add to the pose's name.
std::vector<std::pair<Pose, std::string>> badPoses() {
  Pose nan_x, inf_x, nan_q, twice, zero;
  nan_x.x.y() = kNan;
  inf_x.x.z() = -kInf;
  nan_q.q.coeffs()(static_cast<Index>(uniform(0, 3.999))) = kNan;
  twice.q = Quat(2, 0, 0, 0);
  zero.q = Quat(0, 0, 0, 0);
  return {{nan_x, " position"}, {inf_x, " position"}, {nan_q, " quaternion"}, {twice, " quaternion"},
          {zero, " quaternion"}};
}

// `call(pose_a, pose_b)` accepts the good poses (and a quaternion off unit by round-off) and
// refuses each bad pose in either place, naming "pose_a" or "pose_b"; `has_b` false: a plane's
// routine, whose B has no pose (the second argument is ignored).
template <class Call>
void checkPoses(const Call& call, const Pose& good_a, const Pose& good_b, bool has_b = true) {
  Pose rounded = good_a;
  rounded.q.coeffs() *= 1.0 + 1e-9;
  CHECK_NOTHROW(call(rounded, good_b));
  for (const auto& [bad, words] : badPoses()) {
    INFO("expected: " << words);
    CHECK_THROWS_AS(call(bad, good_b), InvalidInput);
    CHECK_THROWS_WITH(call(bad, good_b), Contains("pose_a" + words));
    if (has_b) CHECK_THROWS_WITH(call(good_a, bad), Contains("pose_b" + words));
  }
}

// A sphere, box, capsule or plane spoiled after construction, with the words its message must contain.
template <class S>
using Spoiled = std::vector<std::pair<S, std::string>>;

Spoiled<Sphere> badSpheres(const Sphere& good) {
  Spoiled<Sphere> bad;
  for (const double r : {-good.radius, 0.0, kNan, kInf}) {
    bad.emplace_back(good, "sphere radius");
    bad.back().first.radius = r;
  }
  return bad;
}

Spoiled<Box> badBoxes(const Box& good) {
  Spoiled<Box> bad;
  for (int k = 0; k < 3; ++k) {
    bad.emplace_back(good, "box half extent " + std::to_string(k));
    bad.back().first.half_extents[k] = k == 1 ? kNan : -good.half_extents[k];
  }
  return bad;
}

Spoiled<Capsule> badCapsules(const Capsule& good) {
  Spoiled<Capsule> bad = {{good, "capsule radius"}, {good, "capsule half height"}, {good, "capsule half height"}};
  bad[0].first.radius = kNan;
  bad[1].first.half_height = 0.0;
  bad[2].first.half_height = -kInf;
  return bad;
}

Spoiled<Plane> badPlanes(const Plane& good) {
  Spoiled<Plane> bad = {{good, "plane normal"}, {good, "plane normal"}, {good, "plane normal"}, {good, "plane offset"}};
  bad[0].first.normal *= 2.0;
  bad[1].first.normal *= 1.0 - 1e-8;
  bad[2].first.normal.x() = kNan;
  bad[3].first.offset = kNan;
  return bad;
}

// Polyhedra whose public fields were changed after construction.
Spoiled<ConvexPolyhedron> badPolyhedra(const ConvexPolyhedron& good) {
  Spoiled<ConvexPolyhedron> bad(6, {good, ""});
  bad[0] = {good, "convex polyhedron vertex 3"};
  bad[0].first.vertices[3].z() = kNan;
  bad[1] = {good, "convex polyhedron face 2"};
  bad[1].first.faces[2][1] = static_cast<int>(good.vertices.size());
  bad[2] = {good, "convex polyhedron face 1"};
  bad[2].first.faces[1][0] = -1;
  bad[3] = {good, "convex polyhedron normal 4"};
  bad[3].first.normals[4] *= 3.0;
  bad[4] = {good, "convex polyhedron needs one normal and one offset per face"};
  bad[4].first.normals.pop_back();
  bad[5] = {good, "convex polyhedron edge"};
  bad[5].first.edges[5][1] = 99;
  return bad;
}

// `call(a, b)` refuses each spoiled A and each spoiled B, naming "shape a: ..." or "shape b: ...".
template <class Call, class A, class B>
void checkShapes(const Call& call, const A& good_a, const Spoiled<A>& bad_a, const B& good_b, const Spoiled<B>& bad_b) {
  for (const auto& [bad, words] : bad_a) {
    INFO("expected: shape a: " << words);
    CHECK_THROWS_AS(call(bad, good_b), InvalidInput);
    CHECK_THROWS_WITH(call(bad, good_b), Contains("shape a: " + words));
  }
  for (const auto& [bad, words] : bad_b) {
    INFO("expected: shape b: " << words);
    CHECK_THROWS_AS(call(good_a, bad), InvalidInput);
    CHECK_THROWS_WITH(call(good_a, bad), Contains("shape b: " + words));
  }
}

}  // namespace

TEST_CASE("bad input: sphere routines refuse spoiled spheres, boxes and planes and bad poses, naming them", "[lab04][pts=1][sec=2]") {
  const Sphere big(1.0), small(0.5);
  const Box box(Vec3(1.0, 1.0, 1.0));
  const Plane ground(Vec3::UnitZ(), 0.0);
  // Valid: the closed forms
  const Manifold spheres = collideSphereSphere(big, at(Vec3::Zero()), small, at(Vec3(1.2, 0, 0)));
  REQUIRE(spheres.count == 1);
  CHECK(spheres.points[0].depth == Approx(0.3));
  CHECK(collideSpherePlane(big, at(Vec3(0, 0, 0.5)), ground).points[0].depth == Approx(0.5));
  CHECK(collideSphereBox(small, at(Vec3(0, 0, 1.3)), box, at(Vec3::Zero())).points[0].depth == Approx(0.2));
  const Pose pa = at(Vec3::Zero()), pb = at(Vec3(1.2, 0, 0)), high = at(Vec3(0, 0, 0.5));
  checkPoses([&](const Pose& a, const Pose& b) { return collideSphereSphere(big, a, small, b); }, pa, pb);
  checkPoses([&](const Pose& a, const Pose&) { return collideSpherePlane(big, a, ground); }, high, Pose{}, false);
  checkPoses([&](const Pose& a, const Pose& b) { return collideSphereBox(small, a, box, b); }, at(Vec3(0, 0, 1.3)),
             Pose{});
  checkShapes([&](const Sphere& a, const Sphere& b) { return collideSphereSphere(a, pa, b, pb); }, big, badSpheres(big),
              small, badSpheres(small));
  checkShapes([&](const Sphere& a, const Plane& b) { return collideSpherePlane(a, high, b); }, big, badSpheres(big),
              ground, badPlanes(ground));
  checkShapes([&](const Sphere& a, const Box& b) { return collideSphereBox(a, at(Vec3(0, 0, 1.3)), b, Pose{}); }, small,
              badSpheres(small), box, badBoxes(box));
}

TEST_CASE("bad input: capsule routines and closest points of segments refuse bad shapes, poses and ends, naming them", "[lab04][pts=1][sec=3]") {
  // Valid: crossed segments meet at their middles
  const Vec3 ends[4] = {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 1), Vec3(0, 1, 1)};
  const std::array<double, 2> st = closestSegmentParameters(ends[0], ends[1], ends[2], ends[3]);
  CHECK(st[0] == Approx(0.5));
  CHECK(st[1] == Approx(0.5));
  const Capsule upright(0.5, 1.0);
  const Sphere ball(0.5);
  const Pose pa = at(Vec3::Zero()), pb = at(Vec3(0.8, 0, 0.3));
  Pose lying = at(Vec3(0.8, 0, 0));
  lying.q = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
  CHECK(collideCapsuleSphere(upright, pa, ball, pb).points[0].depth == Approx(0.2));
  CHECK(collideCapsuleCapsule(upright, pa, upright, lying).points[0].depth == Approx(0.2));
  const char* names[4] = {"segment end p1", "segment end q1", "segment end p2", "segment end q2"};
  for (int k = 0; k < 4; ++k) {
    for (const double bad : {kNan, kInf}) {
      Vec3 e[4] = {ends[0], ends[1], ends[2], ends[3]};
      e[k][static_cast<Index>(uniform(0, 2.999))] = bad;
      INFO("expected: " << names[k]);
      CHECK_THROWS_AS(closestSegmentParameters(e[0], e[1], e[2], e[3]), InvalidInput);
      CHECK_THROWS_WITH(closestSegmentParameters(e[0], e[1], e[2], e[3]), Contains(names[k]));
    }
  }
  checkPoses([&](const Pose& a, const Pose& b) { return collideCapsuleSphere(upright, a, ball, b); }, pa, pb);
  checkPoses([&](const Pose& a, const Pose& b) { return collideCapsuleCapsule(upright, a, upright, b); }, pa, lying);
  checkShapes([&](const Capsule& a, const Sphere& b) { return collideCapsuleSphere(a, pa, b, pb); }, upright,
              badCapsules(upright), ball, badSpheres(ball));
  checkShapes([&](const Capsule& a, const Capsule& b) { return collideCapsuleCapsule(a, pa, b, lying); }, upright,
              badCapsules(upright), upright, badCapsules(upright));
}

TEST_CASE("bad input: a box on a plane refuses a spoiled box or plane and a bad pose, naming them", "[lab04][pts=1][sec=4]") {
  const Box box(Vec3(1.0, 1.0, 1.0));
  const Plane ground(Vec3::UnitZ(), 0.0);
  const Manifold m = collideBoxPlane(box, at(Vec3(0, 0, 0.9)), ground);
  REQUIRE(m.count == 4);
  for (int i = 0; i < 4; ++i) CHECK(m.points[i].depth == Approx(0.1));
  checkPoses([&](const Pose& a, const Pose&) { return collideBoxPlane(box, a, ground); }, at(Vec3(0, 0, 0.9)), Pose{},
             false);
  checkShapes([&](const Box& a, const Plane& b) { return collideBoxPlane(a, at(Vec3(0, 0, 0.9)), b); }, box,
              badBoxes(box), ground, badPlanes(ground));
}

TEST_CASE("bad input: box-box refuses spoiled boxes and bad poses, naming them", "[lab04][pts=1][sec=5]") {
  const Box box(Vec3(1.0, 1.0, 1.0));
  const Pose above = at(Vec3(0, 0, 1.9)), below = at(Vec3::Zero());
  const Manifold m = collideBoxBox(box, above, box, below);
  REQUIRE(m.count == 4);
  CHECK(m.normal.isApprox(Vec3::UnitZ()));
  for (int i = 0; i < 4; ++i) CHECK(m.points[i].depth == Approx(0.1));
  checkPoses([&](const Pose& a, const Pose& b) { return collideBoxBox(box, a, box, b); }, above, below);
  checkShapes([&](const Box& a, const Box& b) { return collideBoxBox(a, above, b, below); }, box, badBoxes(box), box,
              badBoxes(box));
}

TEST_CASE("bad input: clipping and reduction refuse counts past the points, NaN points and planes, naming them", "[lab04][pts=1][sec=5]") {
  ContactPolygon square;
  for (std::uint32_t k = 0; k < 4; ++k) square.add(Vec3(k == 1 || k == 2 ? 1 : -1, k >= 2 ? 1 : -1, 0), 0.1, k);
  // Valid: cut by x <= 0, the left half and the two crossings
  const ContactPolygon half = clipPolygon(square, Vec3::UnitX(), 0.0, 7);
  CHECK(half.count == 4);
  ContactPolygon hexagon;
  for (std::uint32_t k = 0; k < 6; ++k) hexagon.add(Vec3(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0), 0.1 * k, k);
  CHECK(reduceContacts(Vec3::UnitZ(), hexagon).count == 4);
  // Only the first `count` points count: a NaN past them is allowed
  ContactPolygon trailing = square;
  trailing.points[4].depth = kNan;
  CHECK(clipPolygon(trailing, Vec3::UnitX(), 0.0, 7).count == 4);
  CHECK(reduceContacts(Vec3::UnitZ(), trailing).count == 4);
  std::vector<std::pair<ContactPolygon, std::string>> bad(4, {square, ""});
  bad[0] = {square, " count 65"};
  bad[0].first.count = ContactPolygon::kCapacity + 1;
  bad[1] = {square, " count -1"};
  bad[1].first.count = -1;
  bad[2] = {square, " point 3"};
  bad[2].first.points[3].position.y() = kInf;
  bad[3] = {square, " point 2"};
  bad[3].first.points[2].depth = kNan;
  for (const auto& [polygon, words] : bad) {
    INFO("expected: " << words);
    CHECK_THROWS_AS(clipPolygon(polygon, Vec3::UnitX(), 0.0, 7), InvalidInput);
    CHECK_THROWS_WITH(clipPolygon(polygon, Vec3::UnitX(), 0.0, 7), Contains("clipPolygon polygon" + words));
    CHECK_THROWS_AS(reduceContacts(Vec3::UnitZ(), polygon), InvalidInput);
    CHECK_THROWS_WITH(reduceContacts(Vec3::UnitZ(), polygon), Contains("reduceContacts candidates" + words));
  }
  CHECK_THROWS_WITH(clipPolygon(square, Vec3(kNan, 0, 0), 0.0, 7), Contains("clipPolygon plane_normal"));
  CHECK_THROWS_WITH(clipPolygon(square, Vec3::UnitX(), -kInf, 7), Contains("clipPolygon plane_offset"));
  CHECK_THROWS_WITH(clipPolygon(square, Vec3::UnitX(), kNan, 7), Contains("clipPolygon plane_offset"));
  CHECK_THROWS_WITH(reduceContacts(Vec3(0, kInf, 1), hexagon), Contains("reduceContacts normal"));
}

TEST_CASE("bad input: convex polyhedra changed after construction and bad poses are refused, naming them", "[lab04][pts=1][sec=6]") {
  const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(1.0, 1.0, 1.0));
  const Pose above = at(Vec3(0, 0, 1.9)), below = at(Vec3::Zero());
  const Manifold m = collideConvexConvex(cube, above, cube, below);
  REQUIRE(m.count == 4);
  for (int i = 0; i < 4; ++i) CHECK(m.points[i].depth == Approx(0.1));
  checkPoses([&](const Pose& a, const Pose& b) { return collideConvexConvex(cube, a, cube, b); }, above, below);
  auto collideCubes = [&](const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
    return collideConvexConvex(a, above, b, below);
  };
  checkShapes(collideCubes, cube, badPolyhedra(cube), cube, badPolyhedra(cube));
}

TEST_CASE("bad input: the triangle test refuses spoiled triangles and bad poses, naming them", "[lab04][pts=1][sec=7]") {
  const Triangle flat(Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0));
  const Triangle upright(Vec3(0, -0.5, -1), Vec3(0, 0.5, -1), Vec3(0, 0, 1));
  const bool through = trianglesIntersect(flat, Pose{}, upright, Pose{});
  CHECK(through);
  CHECK_FALSE(trianglesIntersect(flat, Pose{}, upright, at(Vec3(0, 0, 5))));
  checkPoses([&](const Pose& a, const Pose& b) { return trianglesIntersect(flat, a, upright, b); }, Pose{}, Pose{});
  Spoiled<Triangle> bad(3, {flat, ""});
  bad[0] = {flat, "triangle corner 1"};
  bad[0].first.corners[1].x() = kNan;
  bad[1] = {flat, "triangle corner 2"};
  bad[1].first.corners[2].z() = kInf;
  bad[2] = {flat, "triangle is degenerate"};
  bad[2].first.corners[2] = Vec3(3, -1, 0);  // on the line through the other two
  checkShapes([&](const Triangle& a, const Triangle& b) { return trianglesIntersect(a, Pose{}, b, Pose{}); }, flat, bad,
              upright, bad);
}

TEST_CASE("bad input: GJK refuses spoiled shapes and bad poses, naming them", "[lab04][pts=1][sec=8]") {
  const Sphere big(1.0), small(0.5);
  const Pose pa = at(Vec3::Zero()), pb = at(Vec3(3, 0, 0));
  const DistanceResult d = gjkDistance(big, pa, small, pb);
  CHECK(d.distance == Approx(1.5));
  checkPoses([&](const Pose& a, const Pose& b) { return gjkDistance(big, a, small, b); }, pa, pb);
  checkShapes([&](const Sphere& a, const Sphere& b) { return gjkDistance(a, pa, b, pb); }, big, badSpheres(big), small,
              badSpheres(small));
  const Box box(Vec3(0.5, 0.5, 0.5));
  const ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(0.5, 0.5, 0.5));
  checkShapes([&](const Box& a, const ConvexPolyhedron& b) { return gjkDistance(a, pa, b, pb); }, box, badBoxes(box),
              cube, badPolyhedra(cube));
}

TEST_CASE("bad input: time of impact refuses bad shapes, poses and motions, naming them", "[lab04][pts=1][sec=9]") {
  const Sphere ball(0.5);
  const Pose pa = at(Vec3::Zero()), pb = at(Vec3(2, 0, 0));
  const Motion still, coming{Vec3(-10, 0, 0), Vec3::Zero()};
  const ToiResult bisection = toiBisection(ball, pa, still, ball, pb, coming, 1.0, 1e-6);
  CHECK(bisection.hit);
  CHECK(bisection.time == Approx(0.1).margin(1e-6));
  CHECK(toiConservativeAdvancement(ball, pa, still, ball, pb, coming, 1.0, 1e-6).time == Approx(0.1).margin(1e-6));
  using Toi = ToiResult (*)(const Shape&, const Pose&, const Motion&, const Shape&, const Pose&, const Motion&, double,
                            double);
  for (const Toi toi : {&toiBisection, &toiConservativeAdvancement}) {
    checkPoses([&](const Pose& a, const Pose& b) { return toi(ball, a, still, ball, b, coming, 1.0, 1e-6); }, pa, pb);
    checkShapes([&](const Sphere& a, const Sphere& b) { return toi(a, pa, still, b, pb, coming, 1.0, 1e-6); }, ball,
                badSpheres(ball), ball, badSpheres(ball));
    const std::pair<Motion, std::string> bad[] = {{{Vec3(kNan, 0, 0), Vec3::Zero()}, " velocity v"},
                                                  {{Vec3::Zero(), Vec3(0, -kInf, 0)}, " angular velocity omega"}};
    for (const auto& [motion, words] : bad) {
      INFO("expected: " << words);
      CHECK_THROWS_AS(toi(ball, pa, motion, ball, pb, coming, 1.0, 1e-6), InvalidInput);
      CHECK_THROWS_WITH(toi(ball, pa, motion, ball, pb, coming, 1.0, 1e-6), Contains("motion_a" + words));
      CHECK_THROWS_WITH(toi(ball, pa, still, ball, pb, motion, 1.0, 1e-6), Contains("motion_b" + words));
    }
  }
}

TEST_CASE("bad input: shapes apart are refused all the same when spoiled, before any early return", "[lab04][pts=1][sec=2][sec=3][sec=4][sec=5][sec=6][sec=7]") {
  // Far apart: a routine that returns "no contact" before its checks lets a NaN through
  const Pose origin = at(Vec3::Zero()), far = at(Vec3(100, 100, 100));
  const Plane ground(Vec3::UnitZ(), -200.0);
  Sphere sphere(0.5);
  Box box(Vec3(0.5, 0.5, 0.5));
  Capsule capsule(0.5, 1.0);
  const Manifold apart = collideSphereSphere(sphere, origin, sphere, far);
  CHECK(apart.empty());
  sphere.radius = kNan;
  box.half_extents.y() = -1.0;
  capsule.half_height = kNan;
  const Sphere ball(0.5);
  CHECK_THROWS_WITH(collideSphereSphere(ball, origin, sphere, far), Contains("shape b: sphere radius"));
  CHECK_THROWS_WITH(collideSpherePlane(sphere, origin, ground), Contains("shape a: sphere radius"));
  CHECK_THROWS_WITH(collideSphereBox(ball, origin, box, far), Contains("shape b: box half extent 1"));
  CHECK_THROWS_WITH(collideCapsuleSphere(capsule, origin, ball, far), Contains("shape a: capsule half height"));
  CHECK_THROWS_WITH(collideCapsuleCapsule(Capsule(0.5, 1.0), origin, capsule, far),
                    Contains("shape b: capsule half height"));
  CHECK_THROWS_WITH(collideBoxPlane(box, origin, ground), Contains("shape a: box half extent 1"));
  CHECK_THROWS_WITH(collideBoxBox(Box(Vec3(1, 1, 1)), origin, box, far), Contains("shape b: box half extent 1"));
  ConvexPolyhedron cube = ConvexPolyhedron::box(Vec3(0.5, 0.5, 0.5));
  cube.vertices[0].x() = kNan;
  CHECK_THROWS_WITH(collideConvexConvex(cube, origin, ConvexPolyhedron::box(Vec3(1, 1, 1)), far),
                    Contains("shape a: convex polyhedron vertex 0"));
  Triangle triangle(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY());
  triangle.corners[0].y() = kNan;
  CHECK_THROWS_WITH(trianglesIntersect(Triangle(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()), origin, triangle, far),
                    Contains("shape b: triangle corner 0"));
}
