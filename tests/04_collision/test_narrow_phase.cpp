// Lab 4 graded tests, narrow phase: properties every pair must have (no contact when apart,
// symmetry under swapping, invariance under rigid motions, points inside both shapes), closed
// forms for spheres and resting boxes, and the triangle-triangle test.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "collision_support.hpp"
#include "physlab/collision.hpp"
#include "physlab/error.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// Every pair the narrow phase covers, by the kinds of A and B.
const std::vector<std::pair<Kind, Kind>> kPairs = {
    {Kind::Sphere, Kind::Sphere}, {Kind::Sphere, Kind::Plane},   {Kind::Sphere, Kind::Box},
    {Kind::Capsule, Kind::Sphere}, {Kind::Capsule, Kind::Capsule}, {Kind::Box, Kind::Plane},
    {Kind::Box, Kind::Box},        {Kind::Tetrahedron, Kind::Tetrahedron}};

// The pairs whose routine takes two shapes of one kind, so that swapping calls the same routine.
Manifold collideSameKind(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb) {
  if (a.index() != b.index()) return collide(a, pa, b, pb);
  switch (a.index()) {
    case 0:
      return collideSphereSphere(std::get<Sphere>(a), pa, std::get<Sphere>(b), pb);
    case 1:
      return collideBoxBox(std::get<Box>(a), pa, std::get<Box>(b), pb);
    case 2:
      return collideCapsuleCapsule(std::get<Capsule>(a), pa, std::get<Capsule>(b), pb);
    default:
      return collideConvexConvex(std::get<ConvexPolyhedron>(a), pa, std::get<ConvexPolyhedron>(b), pb);
  }
}

// A random configuration of the pair whose projections on a random direction overlap by
// `overlap` (negative: a gap).
struct Config {
  Shape a, b;
  Pose pa, pb;
};
Config randomConfig(Kind ka, Kind kb, double overlap) {
  Config c{randomShape(ka), randomShape(kb), randomPose(1.0), randomPose(1.0)};
  placeAlong(c.a, c.pa, c.b, c.pb, randomUnit(), -overlap);
  return c;
}

// The manifold's point with the given id, or nullptr.
const ContactPoint* findId(const Manifold& m, std::uint32_t id) {
  for (int i = 0; i < m.count; ++i) {
    if (m.points[i].id == id) return &m.points[i];
  }
  return nullptr;
}

}  // namespace

TEST_CASE("narrow phase: shapes apart by any margin have no contact", "[lab04][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  for (const auto& [ka, kb] : kPairs) {
    for (int trial = 0; trial < 50; ++trial) {
      // Gaps from 1e-4 m to 0.5 m, log-uniform: the small ones catch an inclusive test at d > 0.
      const Config c = randomConfig(ka, kb, -std::exp(uniform(std::log(1e-4), std::log(0.5))));
      INFO(pairName(c.a, c.b) << ", trial " << trial);
      CHECK(collide(c.a, c.pa, c.b, c.pb).empty());
    }
  }
}

TEST_CASE("narrow phase: swapping A and B flips the normal and keeps depths and points", "[lab04][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  for (Kind k : {Kind::Sphere, Kind::Capsule, Kind::Box, Kind::Tetrahedron}) {
    int touching = 0;
    for (int trial = 0; trial < 50; ++trial) {
      const Config c = randomConfig(k, k, uniform(0.01, 0.2));
      const Manifold ab = collideSameKind(c.a, c.pa, c.b, c.pb), ba = collideSameKind(c.b, c.pb, c.a, c.pa);
      INFO(pairName(c.a, c.b) << ", trial " << trial);
      REQUIRE(ab.count == ba.count);
      if (ab.empty()) continue;
      ++touching;
      // Both are computed from the same numbers in another order: round-off only.
      CHECK((ab.normal + ba.normal).norm() < 1e-9);
      for (int i = 0; i < ab.count; ++i) {
        bool matched = false;
        for (int j = 0; j < ba.count; ++j) {
          // The same points, in any order: round-off of clipping in the other box's frame.
          matched = matched || ((ab.points[i].position - ba.points[j].position).norm() < 1e-9 &&
                                std::abs(ab.points[i].depth - ba.points[j].depth) < 1e-9);
        }
        CHECK(matched);
      }
    }
    CHECK(touching > 15);  // extreme points pushed into each other: most trials touch
  }
}

TEST_CASE("narrow phase: a rigid motion of the whole configuration moves the manifold with it", "[lab04][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  for (const auto& [ka, kb] : kPairs) {
    for (int trial = 0; trial < 30; ++trial) {
      const Config c = randomConfig(ka, kb, uniform(0.01, 0.2));
      const Mat3 Q = randomRotation();
      const Vec3 T = randomVec3(5.0);
      const Shape b2 = moved(c.b, Q, T);
      const Manifold m = collide(c.a, c.pa, c.b, c.pb), m2 = collide(c.a, moved(c.pa, Q, T), b2, moved(c.pb, Q, T));
      INFO(pairName(c.a, c.b) << ", trial " << trial);
      REQUIRE(m.count == m2.count);
      if (m.empty()) continue;
      // Positions up to 6 m from the origin: round-off, amplified a little by clipping.
      CHECK((Q * m.normal - m2.normal).norm() < 1e-8);
      for (int i = 0; i < m.count; ++i) {
        const ContactPoint* p = findId(m2, m.points[i].id);
        REQUIRE(p != nullptr);  // the same features touch, so the same ids
        CHECK((Q * m.points[i].position + T - p->position).norm() < 1e-8);
        CHECK(std::abs(m.points[i].depth - p->depth) < 1e-8);
      }
    }
  }
}

TEST_CASE("narrow phase: every contact lies on or inside both shapes within its depth", "[lab04][pts=2][sec=2][sec=3][sec=4][sec=5]") {
  for (const auto& [ka, kb] : kPairs) {
    int touching = 0;
    for (int trial = 0; trial < 50; ++trial) {
      const Config c = randomConfig(ka, kb, uniform(0.01, 0.3));
      const Manifold m = collide(c.a, c.pa, c.b, c.pb);
      INFO(pairName(c.a, c.b) << ", trial " << trial);
      if (m.empty()) continue;
      ++touching;
      CHECK(m.normal.norm() == Approx(1.0).epsilon(1e-12));  // unit, to round-off
      CHECK(m.count <= Manifold::kMaxPoints);
      // No contact is deeper than the overlap of the two projections on its own normal.
      const double overlap = overlapAlong(c.a, c.pa, c.b, c.pb, m.normal);
      for (int i = 0; i < m.count; ++i) {
        const ContactPoint& p = m.points[i];
        CHECK(p.depth >= 0.0);
        CHECK(p.depth <= overlap + 1e-9);  // round-off of the support points
        // The midpoint of two surface points p.depth apart is within p.depth / 2 of each surface.
        CHECK(signedDistance(c.a, c.pa, p.position) <= 0.5 * p.depth + 1e-9);
        CHECK(signedDistance(c.b, c.pb, p.position) <= 0.5 * p.depth + 1e-9);
      }
    }
    CHECK(touching > 20);  // extreme points pushed into each other: most trials touch
  }
}

TEST_CASE("narrow phase: collideSphereSphere gives the closed-form depth, normal and point", "[lab04][pts=1][sec=2]") {
  const double ra = uniform(0.2, 1.0), rb = uniform(0.2, 1.0), overlap = uniform(0.01, 0.19);
  const Vec3 u = randomUnit();
  Pose pa, pb;
  pb.x = randomVec3(2.0);
  pa.x = pb.x + (ra + rb - overlap) * u;
  INFO("spheres of radii " << ra << " and " << rb << " overlapping by " << overlap);
  const Manifold ss = collideSphereSphere(Sphere(ra), pa, Sphere(rb), pb);
  REQUIRE(ss.count == 1);
  // Closed forms evaluated in another order: round-off only.
  CHECK(ss.points[0].depth == Approx(overlap).margin(1e-12));
  CHECK((ss.normal - u).norm() < 1e-12);
  CHECK((ss.points[0].position - (pb.x + (rb - 0.5 * overlap) * u)).norm() < 1e-12);
}

TEST_CASE("narrow phase: collideSpherePlane gives the closed-form depth, normal and point", "[lab04][pts=1][sec=2]") {
  const double ra = uniform(0.2, 1.0), overlap = uniform(0.01, 0.19), d = uniform(-1.0, 1.0);
  const Vec3 u = randomUnit();
  const Plane ground(u, d);
  Pose pa;
  pa.x = randomVec3(2.0);
  pa.x += (d + ra - overlap - u.dot(pa.x)) * u;  // the centre at height r - overlap
  INFO("a sphere of radius " << ra << " sunk " << overlap << " into the plane");
  const Manifold sp = collideSpherePlane(Sphere(ra), pa, ground);
  REQUIRE(sp.count == 1);
  CHECK(sp.points[0].depth == Approx(overlap).margin(1e-12));  // round-off only
  CHECK((sp.normal - u).norm() < 1e-12);
  CHECK((sp.points[0].position - (pa.x - (ra - 0.5 * overlap) * u)).norm() < 1e-12);
}

TEST_CASE("narrow phase: collideCapsuleSphere beside the core's middle gives the perpendicular depth and normal", "[lab04][pts=1][sec=3]") {
  // A sphere beside the middle of a capsule's core: the distance to the core is perpendicular.
  const double rb = uniform(0.2, 1.0), overlap = uniform(0.01, 0.19);
  const Capsule capsule(uniform(0.1, 0.5), uniform(0.5, 1.0));
  const Pose pc = randomPose(1.0);
  const Vec3 axis = pc.q * Vec3::UnitZ();
  const Vec3 side = axis.cross(randomUnit()).normalized();
  const Vec3 core = pc.x + uniform(-0.4, 0.4) * axis;
  Pose pb;
  pb.x = core - (capsule.radius + rb - overlap) * side;
  INFO("a sphere of radius " << rb << " overlapping a capsule of radius " << capsule.radius << " by " << overlap);
  const Manifold cs = collideCapsuleSphere(capsule, pc, Sphere(rb), pb);
  REQUIRE(cs.count == 1);
  CHECK(cs.points[0].depth == Approx(overlap).margin(1e-12));  // round-off only
  CHECK((cs.normal - side).norm() < 1e-12);
}

TEST_CASE("narrow phase: collideSphereBox over a face and off a corner gives the closed-form depth and normal", "[lab04][pts=1][sec=2]") {
  // A sphere over a face of a box, and one off a corner (closest point = the corner).
  const double ra = uniform(0.2, 1.0), overlap = uniform(0.01, 0.19);
  const Box box(Vec3(uniform(0.3, 1.0), uniform(0.3, 1.0), uniform(0.3, 1.0)));
  const Pose pbox = randomPose(1.0);
  Pose pa;
  pa.x = pbox.toWorld(Vec3(uniform(-0.2, 0.2), uniform(-0.2, 0.2), box.half_extents.z() + ra - overlap));
  {
    INFO("over the +z face, sunk " << overlap);
    const Manifold face = collideSphereBox(Sphere(ra), pa, box, pbox);
    REQUIRE(face.count == 1);
    CHECK(face.points[0].depth == Approx(overlap).margin(1e-12));  // round-off only
    CHECK((face.normal - pbox.q * Vec3::UnitZ()).norm() < 1e-12);
  }
  const Vec3 diagonal = Vec3(1, 1, 1).normalized();
  pa.x = pbox.toWorld(box.half_extents + (ra - overlap) * diagonal);
  INFO("off the (+x, +y, +z) corner, sunk " << overlap);
  const Manifold corner = collideSphereBox(Sphere(ra), pa, box, pbox);
  REQUIRE(corner.count == 1);
  CHECK(corner.points[0].depth == Approx(overlap).margin(1e-12));  // round-off only
  CHECK((corner.normal - pbox.q * diagonal).norm() < 1e-12);
}

TEST_CASE("narrow phase: a sphere whose centre is inside a box leaves through the nearest face", "[lab04][pts=1][sec=2]") {
  // Every face in turn, on every run: the nearest face is on the - side as often as on the + side.
  const Box box(Vec3(0.5, 0.7, 0.9));
  const Pose pbox = randomPose(1.0);
  for (int face = 0; face < 6; ++face) {
    const int i = face / 2;
    const double sign = face % 2 == 0 ? 1.0 : -1.0;
    const double r = uniform(0.1, 0.3), inside = uniform(0.05, 0.2);
    // The centre `inside` from face (i, sign), within 0.2 of the middle on the other axes, which
    // leaves them at least 0.3 of room: face (i, sign) is the nearest.
    Vec3 c(uniform(-0.2, 0.2), uniform(-0.2, 0.2), uniform(-0.2, 0.2));
    c[i] = sign * (box.half_extents[i] - inside);
    Pose pa;
    pa.x = pbox.toWorld(c);
    const Manifold m = collideSphereBox(Sphere(r), pa, box, pbox);
    INFO("face " << (sign > 0 ? "+" : "-") << "xyz"[i]);
    REQUIRE(m.count == 1);
    CHECK(m.points[0].depth == Approx(r + inside).margin(1e-12));  // round-off only
    const Vec3 n_body = sign * Vec3::Unit(i);
    CHECK((m.normal - pbox.q * n_body).norm() < 1e-12);  // round-off of the pose's rotation
    // Midway between the sphere's deepest point c - r n and the face point beyond the centre
    // (c with its i-th coordinate on the face), in the box frame; round-off of the pose only.
    const Vec3 centre = pbox.toBody(pa.x);
    Vec3 on_face = centre;
    on_face[i] = sign * box.half_extents[i];
    const Vec3 expected = 0.5 * (centre - r * n_body + on_face);
    CHECK((pbox.toBody(m.points[0].position) - expected).norm() < 1e-12);
  }
}

TEST_CASE("narrow phase: shapes touching at depth exactly 0 have contacts of depth 0", "[lab04][pts=1][sec=2][sec=3][sec=4][sec=5]") {
  // Touching is not apart: each routine must report the contact, with depth 0. Every number
  // below is a binary fraction and the poses are unrotated, so the depths are exactly 0.
  const Vec3 shift(uniform(-0.25, 0.25), uniform(-0.25, 0.25), 0.0);  // slides along the contact plane
  auto at = [](const Vec3& x) {
    Pose p;
    p.x = x;
    return p;
  };
  auto touching = [](const Manifold& m, int count, const Vec3& normal) {
    REQUIRE(m.count == count);
    CHECK(m.normal == normal);  // a coordinate axis, computed from exact differences
    for (int k = 0; k < m.count; ++k) CHECK(m.points[k].depth == 0.0);
  };
  {
    INFO("sphere on sphere");
    const Manifold m = collideSphereSphere(Sphere(0.25), at(Vec3(0.0, 0.0, 0.75)), Sphere(0.5), at(Vec3::Zero()));
    touching(m, 1, Vec3::UnitZ());
    CHECK(m.points[0].position == Vec3(0.0, 0.0, 0.5));  // both surface points
  }
  {
    INFO("sphere on a plane");
    const Manifold m = collideSpherePlane(Sphere(0.25), at(Vec3(0.0, 0.0, 0.75) + shift), Plane(Vec3::UnitZ(), 0.5));
    touching(m, 1, Vec3::UnitZ());
    CHECK((m.points[0].position - (Vec3(0.0, 0.0, 0.5) + shift)).norm() < 1e-15);  // one rounding of the shift
  }
  {
    INFO("sphere on a box face");
    const Manifold m = collideSphereBox(Sphere(0.25), at(Vec3(0.0, 0.0, 0.75) + shift), Box(Vec3(0.5, 0.5, 0.5)),
                                        at(Vec3::Zero()));
    touching(m, 1, Vec3::UnitZ());
  }
  {
    INFO("sphere beside a capsule's core");
    const Manifold m = collideCapsuleSphere(Capsule(0.25, 0.5), at(Vec3::Zero()), Sphere(0.5), at(Vec3(-0.75, 0.0, 0.125)));
    touching(m, 1, Vec3::UnitX());
  }
  {
    INFO("box on a plane");
    const Manifold m = collideBoxPlane(Box(Vec3(0.5, 0.25, 0.125)), at(Vec3(0.0, 0.0, 0.125) + shift), Plane(Vec3::UnitZ(), 0.0));
    touching(m, 4, Vec3::UnitZ());
  }
  {
    INFO("box on a box");
    const Manifold m = collideBoxBox(Box(Vec3(0.5, 0.5, 0.25)), at(Vec3(0.0, 0.0, 0.75) + shift), Box(Vec3(1.0, 1.0, 0.5)),
                                     at(Vec3::Zero()));
    touching(m, 4, Vec3::UnitZ());
  }
  {
    INFO("box on a box, as convex polyhedra");
    const Manifold m = collideConvexConvex(ConvexPolyhedron::box(Vec3(0.5, 0.5, 0.25)), at(Vec3(0.0, 0.0, 0.75) + shift),
                                           ConvexPolyhedron::box(Vec3(1.0, 1.0, 0.5)), at(Vec3::Zero()));
    touching(m, 4, Vec3::UnitZ());
  }
}

TEST_CASE("narrow phase: spheres with coincident centres separate along +z", "[lab04][pts=1][sec=2]") {
  // The line of centres is undefined: the documented fallback is +z, and the depth is then the
  // sum of the radii. A's deepest point c - r_A e_z and B's c + r_B e_z have their midpoint at
  // c + (r_B - r_A)/2 e_z.
  const double ra = uniform(0.2, 1.0), rb = uniform(0.2, 1.0);
  Pose pa = randomPose(2.0), pb = randomPose(2.0);
  pb.x = pa.x;
  const Manifold m = collideSphereSphere(Sphere(ra), pa, Sphere(rb), pb);
  REQUIRE(m.count == 1);
  CHECK((m.normal - Vec3::UnitZ()).norm() == 0.0);  // a constant, not a computed direction
  CHECK(m.points[0].depth == Approx(ra + rb).margin(1e-12));  // one addition
  CHECK((m.points[0].position - (pa.x + 0.5 * (rb - ra) * Vec3::UnitZ())).norm() < 1e-12);  // round-off only
}

TEST_CASE("narrow phase: crossed capsules touch at one point between their cores, normal from B to A", "[lab04][pts=1][sec=3]") {
  for (int trial = 0; trial < 20; ++trial) {
    // In a frame F: B's core along x through the origin, A's core at height H = r_A + r_B - overlap,
    // at an angle phi to B's in the horizontal plane, crossing above (px, 0). The closest points
    // of the two lines are (px, 0, 0) and (px, 0, H), inside both cores.
    const Capsule a(uniform(0.1, 0.4), uniform(0.5, 1.0)), b(uniform(0.1, 0.4), uniform(0.5, 1.0));
    const double overlap = uniform(0.001, 0.05), phi = uniform(0.3, M_PI - 0.3);
    const double px = uniform(-0.4, 0.4), s = uniform(-0.4, 0.4);
    const double H = a.radius + b.radius - overlap;
    const Pose frame = randomPose(2.0);
    const Vec3 dir_a(std::cos(phi), std::sin(phi), 0.0);
    Pose pa, pb;
    pb.q = (frame.q * rotationTaking(Vec3::UnitZ(), Vec3::UnitX())).normalized();
    pb.x = frame.x;
    pa.q = (frame.q * rotationTaking(Vec3::UnitZ(), dir_a)).normalized();
    pa.x = frame.toWorld(Vec3(px, 0.0, H) + s * dir_a);
    const Manifold m = collideCapsuleCapsule(a, pa, b, pb);
    INFO("trial " << trial);
    REQUIRE(m.count == 1);
    CHECK((m.normal - frame.q * Vec3::UnitZ()).norm() < 1e-9);  // round-off of the rotations
    CHECK(m.points[0].depth == Approx(overlap).margin(1e-9));
    // Midway between A's lowest point (px, 0, H - r_A) and B's highest (px, 0, r_B).
    const Vec3 expected(px, 0.0, 0.5 * (H - a.radius + b.radius));
    CHECK((frame.toBody(m.points[0].position) - expected).norm() < 1e-9);
  }
}

TEST_CASE("narrow phase: parallel capsules touch at both ends of their overlap, either way round and overhanging", "[lab04][pts=1][sec=3]") {
  // Cores along z, side by side along x, overlapping by 1/16 m; one core longer than the other,
  // so the longer one overhangs at both ends, and B either way up (a half turn about x swaps its
  // ends). The overlap of the cores is the shorter core: the contacts are at its two ends.
  const double overlap = 0.0625;
  for (const bool a_longer : {false, true}) {
    for (const bool b_flipped : {false, true}) {
      const Capsule a(0.25, a_longer ? 1.0 : 0.5), b(0.125, a_longer ? 0.5 : 1.0);
      Pose pa, pb;
      pa.x = Vec3(a.radius + b.radius - overlap, 0.0, 0.125);
      if (b_flipped) pb.q = Quat(0.0, 1.0, 0.0, 0.0);  // a half turn about x: z -> -z exactly
      const Manifold m = collideCapsuleCapsule(a, pa, b, pb);
      INFO((a_longer ? "A" : "B") << " longer, B " << (b_flipped ? "upside down" : "upright"));
      REQUIRE(m.count == 2);
      CHECK(m.normal == Vec3::UnitX());  // exact differences of the unrotated cores
      CHECK(m.points[0].id != m.points[1].id);
      // The ends of the shorter core (A's runs from 0.125 - h_A to 0.125 + h_A, B's from -h_B to h_B);
      // midway between A's surface at x = overlap and B's at x = r_B: binary fractions, exact.
      const double lo = a_longer ? -b.half_height : 0.125 - a.half_height;
      const double hi = a_longer ? b.half_height : 0.125 + a.half_height;
      std::vector<double> heights;
      for (int k = 0; k < 2; ++k) {
        CHECK(m.points[k].depth == Approx(overlap).margin(1e-15));  // exact up to one rounding
        CHECK(m.points[k].position.x() == Approx(0.5 * (overlap + b.radius)).margin(1e-15));  // likewise
        heights.push_back(m.points[k].position.z());
      }
      CHECK(std::min(heights[0], heights[1]) == Approx(lo).margin(1e-15));  // an end, to one rounding
      CHECK(std::max(heights[0], heights[1]) == Approx(hi).margin(1e-15));  // the other end, likewise
    }
  }
}

TEST_CASE("closest points of segments: a segment reduced to a point", "[lab04][pts=1][sec=3]") {
  // The parameters must lie in [0, 1] and give the closest points; a single point has one
  // parameter that does not matter, but it must still be a number in [0, 1].
  const Vec3 p(-1.0, 0.0, 0.0), q(1.0, 0.0, 0.0);  // a segment along x
  struct Case {
    const char* what;
    Vec3 point;
    double t;  // parameter of the segment's closest point
  };
  const Case cases[] = {{"before the segment's start", Vec3(-3.0, 1.0, 0.0), 0.0},
                        {"beside its middle", Vec3(0.5, 2.0, -1.0), 0.75},
                        {"past its end", Vec3(3.0, -1.0, 2.0), 1.0}};
  auto in01 = [](double s) { return s >= 0.0 && s <= 1.0; };  // false for NaN
  for (const Case& c : cases) {
    INFO("a point " << c.what);
    // The point first, then second: the other parameter is the segment's, exact in binary.
    const std::array<double, 2> first = closestSegmentParameters(c.point, c.point, p, q);
    CHECK(in01(first[0]));
    CHECK(first[1] == c.t);
    const std::array<double, 2> second = closestSegmentParameters(p, q, c.point, c.point);
    CHECK(second[0] == c.t);
    CHECK(in01(second[1]));
  }
  const std::array<double, 2> points = closestSegmentParameters(p, p, q, q);
  INFO("two points");
  CHECK(in01(points[0]));
  CHECK(in01(points[1]));
}

TEST_CASE("narrow phase: a box resting on a plane touches at its 4 bottom corners", "[lab04][pts=2][sec=4]") {
  const Vec3 n = randomUnit();
  const double d = uniform(-1.0, 1.0), overlap = uniform(0.001, 0.1);
  const Box box(Vec3(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0)));
  // Turn the box's -z face to face -n, then spin it about n by a random angle.
  const Quat down = rotationTaking(Vec3::UnitZ(), n);
  Pose pose;
  pose.q = Quat(Eigen::AngleAxisd(uniform(0.0, 6.28), n)) * down;
  pose.x = randomVec3(2.0);
  pose.x += (d + box.half_extents.z() - overlap - n.dot(pose.x)) * n;
  const Manifold m = collideBoxPlane(box, pose, Plane(n, d));
  REQUIRE(m.count == 4);
  CHECK((m.normal - n).norm() < 1e-12);  // round-off only
  for (int i = 0; i < 4; ++i) {
    CHECK(m.points[i].depth == Approx(overlap).margin(1e-12));  // round-off only
    // The point is a bottom corner moved half the depth up to the plane.
    const Vec3 corner = pose.toBody(m.points[i].position - 0.5 * overlap * n);
    CHECK((corner.cwiseAbs() - box.half_extents).norm() < 1e-9);  // round-off of two rotations
  }
}

TEST_CASE("narrow phase: triangles intersect exactly when an edge pierces the other", "[lab04][pts=2][sec=7]") {
  for (int trial = 0; trial < 200; ++trial) {
    const Triangle t1(randomVec3(1.0), randomVec3(1.0), randomVec3(1.0));
    const Vec3 &a = t1.corners[0], &b = t1.corners[1], &c = t1.corners[2];
    const Vec3 n = (b - a).cross(c - a).normalized();
    // A point inside the first triangle and a second triangle through it (p is the midpoint of
    // the median from p + u): they intersect.
    double wa = uniform(0.05, 1.0), wb = uniform(0.05, 1.0), wc = uniform(0.05, 1.0);
    const Vec3 p = (wa * a + wb * b + wc * c) / (wa + wb + wc);
    const Vec3 u = uniform(0.1, 1.0) * (n + randomVec3(0.5)), w = randomVec3(1.0);
    if (std::abs(u.dot(n)) < 0.05) continue;  // keep the second triangle clearly across the plane
    const Pose pa = randomPose(1.0);
    const Triangle t2(p + u, p - u + w, p - u - w);
    INFO("trial " << trial);
    CHECK(trianglesIntersect(t1, pa, t2, pa));
    CHECK(trianglesIntersect(t2, pa, t1, pa));
    // The same triangle moved clear of t1's plane (all its corners beyond a margin): apart.
    const double lift = 1.1 * std::max({std::abs(n.dot(p + u - a)), std::abs(n.dot(p - u + w - a)),
                                        std::abs(n.dot(p - u - w - a))}) + 0.01;
    const Triangle t3(p + u + lift * n + std::abs(n.dot(u)) * n, p - u + w + lift * n, p - u - w + lift * n);
    bool beyond = true;
    for (const Vec3& q : t3.corners) beyond = beyond && n.dot(q - a) > 0.0;
    if (beyond) CHECK_FALSE(trianglesIntersect(t1, pa, t3, pa));
  }
}
