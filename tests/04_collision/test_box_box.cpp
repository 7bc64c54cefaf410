// Lab 4 graded tests, separating axes: box-box face, edge and depth cases against constructions
// with known answers, clipping and reduction, and convex polyhedra against boxes.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "collision_support.hpp"
#include "physlab/collision.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

using Vec2 = Eigen::Vector2d;

// The corners of the intersection of two convex polygons (counter-clockwise corner lists):
// corners of each inside the other, and crossings of their edges.
std::vector<Vec2> intersectionCorners(const std::vector<Vec2>& P, const std::vector<Vec2>& R) {
  auto inside = [](const std::vector<Vec2>& poly, const Vec2& x) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec2 e = poly[(i + 1) % poly.size()] - poly[i], r = x - poly[i];
      if (e.x() * r.y() - e.y() * r.x() < -1e-12) return false;
    }
    return true;
  };
  std::vector<Vec2> corners;
  for (const Vec2& p : P) if (inside(R, p)) corners.push_back(p);
  for (const Vec2& r : R) if (inside(P, r)) corners.push_back(r);
  for (std::size_t i = 0; i < P.size(); ++i) {
    for (std::size_t j = 0; j < R.size(); ++j) {
      const Vec2 p = P[i], e = P[(i + 1) % P.size()] - p, q = R[j], f = R[(j + 1) % R.size()] - q;
      const double den = e.x() * f.y() - e.y() * f.x();
      if (std::abs(den) < 1e-14) continue;
      const Vec2 w = q - p;
      const double s = (w.x() * f.y() - w.y() * f.x()) / den, t = (w.x() * e.y() - w.y() * e.x()) / den;
      if (s >= 0 && s <= 1 && t >= 0 && t <= 1) corners.push_back(p + s * e);
    }
  }
  return corners;
}

// A rectangle of half extents (hx, hy) turned by angle about its centre c, counter-clockwise.
std::vector<Vec2> rectangle(const Vec2& c, double hx, double hy, double angle) {
  const Eigen::Rotation2Dd R(angle);
  return {c + R * Vec2(-hx, -hy), c + R * Vec2(hx, -hy), c + R * Vec2(hx, hy), c + R * Vec2(-hx, hy)};
}

// The least overlap of two shapes' projections over the 15 box-box axes (both senses),
// computed with the framework's support points.
double leastOverlap15(const Box& a, const Pose& pa, const Box& b, const Pose& pb) {
  const Mat3 Ra = pa.q.toRotationMatrix(), Rb = pb.q.toRotationMatrix();
  std::vector<Vec3> axes;
  for (int i = 0; i < 3; ++i) {
    axes.push_back(Ra.col(i));
    axes.push_back(Rb.col(i));
    for (int j = 0; j < 3; ++j) {
      const Vec3 L = Ra.col(i).cross(Rb.col(j));
      if (L.norm() > 1e-6) axes.push_back(L.normalized());
    }
  }
  double least = 1e300;
  for (const Vec3& L : axes) {
    least = std::min({least, overlapAlong(a, pa, b, pb, L), overlapAlong(a, pa, b, pb, -L)});
  }
  return least;
}

// Two seeded random boxes at random poses, pressed into each other along a random direction by
// 0.01 to 0.3 (placeAlong: their extreme points that far past each other).
std::tuple<Box, Pose, Box, Pose> pressedBoxes() {
  const Box a(Vec3(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0)));
  const Box b(Vec3(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0)));
  Pose pa = randomPose(1.0), pb = randomPose(1.0);
  Shape sb = b;
  placeAlong(Shape(a), pa, sb, pb, randomUnit(), -uniform(0.01, 0.3));
  return {a, pa, b, pb};
}

}  // namespace

TEST_CASE("box-box: face on face, turned about the normal, touches at the overlap polygon's corners", "[lab04][pts=3][sec=5]") {
  for (int trial = 0; trial < 20; ++trial) {
    const Box a(Vec3(uniform(0.3, 1.0), uniform(0.3, 1.0), uniform(0.2, 1.0)));
    const Box b(Vec3(uniform(0.3, 1.0), uniform(0.3, 1.0), uniform(0.2, 1.0)));
    const Pose pb = randomPose(1.0);
    const double angle = uniform(0.1, 1.4), overlap = uniform(0.001, 0.1);
    const Vec2 offset(uniform(-0.3, 0.3), uniform(-0.3, 0.3));
    // A sits on B's top face (B's frame), turned about B's z by `angle`.
    Pose pa;
    pa.q = (pb.q * Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()))).normalized();
    pa.x = pb.toWorld(Vec3(offset.x(), offset.y(), b.half_extents.z() + a.half_extents.z() - overlap));
    const std::vector<Vec2> corners =
        intersectionCorners(rectangle(Vec2::Zero(), b.half_extents.x(), b.half_extents.y(), 0.0),
                            rectangle(offset, a.half_extents.x(), a.half_extents.y(), angle));
    const Manifold m = collideBoxBox(a, pa, b, pb);
    INFO("trial " << trial << ", " << corners.size() << " corners");
    REQUIRE(m.count == std::min<int>(4, static_cast<int>(corners.size())));
    CHECK((m.normal - pb.q * Vec3::UnitZ()).norm() < 1e-9);  // round-off of the two rotations
    for (int i = 0; i < m.count; ++i) {
      CHECK(m.points[i].depth == Approx(overlap).margin(1e-9));  // round-off of the rotations
      const Vec3 p = pb.toBody(m.points[i].position);
      // Midway between A's bottom and B's top face.
      CHECK(p.z() == Approx(b.half_extents.z() - 0.5 * overlap).margin(1e-9));
      double nearest = 1e300;
      for (const Vec2& c : corners) nearest = std::min(nearest, (c - p.head<2>()).norm());
      CHECK(nearest < 1e-9);  // one of the corners, to the round-off of clipping
      for (int j = 0; j < i; ++j) CHECK(m.points[i].id != m.points[j].id);
    }
  }
}

TEST_CASE("box-box: a small box resting inside a large box's face touches at its 4 bottom corners", "[lab04][pts=2][sec=5]") {
  const Box a(Vec3(uniform(0.1, 0.3), uniform(0.1, 0.3), uniform(0.1, 0.3)));
  const Box b(Vec3(uniform(1.0, 2.0), uniform(1.0, 2.0), uniform(0.5, 1.0)));
  const Pose pb = randomPose(1.0);
  const double overlap = uniform(0.001, 0.05);
  Pose pa;
  pa.q = (pb.q * Quat(Eigen::AngleAxisd(uniform(0.0, 6.28), Vec3::UnitZ()))).normalized();
  pa.x = pb.toWorld(Vec3(uniform(-0.5, 0.5), uniform(-0.5, 0.5), b.half_extents.z() + a.half_extents.z() - overlap));
  const Manifold m = collideBoxBox(a, pa, b, pb);
  REQUIRE(m.count == 4);
  for (int i = 0; i < 4; ++i) {
    CHECK(m.points[i].depth == Approx(overlap).margin(1e-9));  // round-off of the rotations
    // Moved down by half the depth, the point is a bottom corner of A.
    const Vec3 corner = pa.toBody(m.points[i].position - 0.5 * overlap * m.normal);
    CHECK((corner.cwiseAbs() - a.half_extents).norm() < 1e-9);
    CHECK(corner.z() < 0.0);
  }
  // Swapped, B is A: the same points, the normal reversed.
  const Manifold s = collideBoxBox(b, pb, a, pa);
  REQUIRE(s.count == 4);
  CHECK((s.normal + m.normal).norm() < 1e-12);
}

TEST_CASE("box-box: a tilted box pressed into a face touches at each bottom corner with its own depth, as on a plane", "[lab04][pts=2][sec=5]") {
  for (int trial = 0; trial < 20; ++trial) {
    // B is a wide slab; A is tilted by a small angle about B's x, so its 4 bottom corners lie at
    // different heights, all below B's top face (z = 0.5 in B's frame) and well inside it.
    const Box a(Vec3(uniform(0.2, 0.4), uniform(0.2, 0.4), uniform(0.2, 0.4)));
    const Box b(Vec3(2.0, 2.0, 0.5));
    const Pose pb = randomPose(1.0);
    const Mat3 tilt = (Eigen::AngleAxisd(uniform(0.03, 0.1), Vec3::UnitX()) *
                       Eigen::AngleAxisd(uniform(0.0, 6.28), Vec3::UnitZ())).toRotationMatrix();
    std::vector<Vec3> corners;  // A's bottom corners about A's centre, in B's frame
    for (int k = 0; k < 4; ++k) {
      corners.push_back(tilt * Vec3((k & 1) ? a.half_extents.x() : -a.half_extents.x(),
                                    (k & 2) ? a.half_extents.y() : -a.half_extents.y(), -a.half_extents.z()));
    }
    double low = 1e300, high = -1e300;
    for (const Vec3& c : corners) low = std::min(low, c.z()), high = std::max(high, c.z());
    // The deepest corner `deepest` below the face, the shallowest still 0.005-0.02 m below it.
    const double deepest = (high - low) + uniform(0.005, 0.02);
    const Vec3 centre(uniform(-0.5, 0.5), uniform(-0.5, 0.5), 0.5 - deepest - low);
    Pose pa;
    pa.q = (pb.q * Quat(tilt)).normalized();
    pa.x = pb.toWorld(centre);
    const Vec3 n = pb.q * Vec3::UnitZ();
    const Manifold boxes = collideBoxBox(a, pa, b, pb);
    const Manifold plane = collideBoxPlane(a, pa, Plane(n, n.dot(pb.x) + 0.5));
    INFO("trial " << trial << ", depths from " << deepest - (high - low) << " to " << deepest);
    for (const Manifold& m : {boxes, plane}) {
      REQUIRE(m.count == 4);
      CHECK((m.normal - n).norm() < 1e-9);  // B's top face, to the round-off of the rotations
      for (const Vec3& c : corners) {
        // The corner's own depth below the face, and the point half of it above the corner.
        const double depth = 0.5 - (centre + c).z();
        const Vec3 expected = pb.toWorld(centre + c + 0.5 * depth * Vec3::UnitZ());
        bool found = false;
        for (int i = 0; i < m.count; ++i) {
          found = found || ((m.points[i].position - expected).norm() < 1e-9 &&  // round-off of the poses
                            std::abs(m.points[i].depth - depth) < 1e-9);
        }
        CHECK(found);
      }
    }
  }
}

TEST_CASE("box-box: a box resting face down keeps its feature ids when the scene moves rigidly", "[lab04][pts=1][sec=5]") {
  // A's bottom face and B's top face are exact ties on the SAT (the same overlap); which wins
  // must not be left to round-off, or the ids (warm starting in Lab 5) flicker from step to step.
  const Box a(Vec3(uniform(0.1, 0.3), uniform(0.1, 0.3), uniform(0.1, 0.3)));
  const Box b(Vec3(uniform(1.0, 2.0), uniform(1.0, 2.0), uniform(0.5, 1.0)));
  const double overlap = uniform(0.001, 0.05);
  Pose pb;
  Pose pa;
  pa.q = Quat(Eigen::AngleAxisd(uniform(0.0, 6.28), Vec3::UnitZ()));
  pa.x = Vec3(uniform(-0.5, 0.5), uniform(-0.5, 0.5), b.half_extents.z() + a.half_extents.z() - overlap);
  const Manifold m0 = collideBoxBox(a, pa, b, pb);
  REQUIRE(m0.count == 4);
  std::vector<std::uint32_t> ids0;
  for (int i = 0; i < 4; ++i) ids0.push_back(m0.points[i].id);
  std::sort(ids0.begin(), ids0.end());
  for (int trial = 0; trial < 30; ++trial) {
    const Mat3 Q = randomRotation();
    const Vec3 T = randomVec3(5.0);
    const Manifold m = collideBoxBox(a, moved(pa, Q, T), b, moved(pb, Q, T));
    INFO("motion " << trial);
    REQUIRE(m.count == 4);
    std::vector<std::uint32_t> ids;
    for (int i = 0; i < 4; ++i) ids.push_back(m.points[i].id);
    std::sort(ids.begin(), ids.end());
    CHECK(ids == ids0);
  }
}

TEST_CASE("box-box: crossed edges touch at one point between the two edges", "[lab04][pts=2][sec=5]") {
  for (int trial = 0; trial < 20; ++trial) {
    // In a frame F: A turned 45 degrees about x (lowest edge along x), B about y (top edge along y).
    const double ea = uniform(0.2, 0.6), eb = uniform(0.2, 0.6), overlap = uniform(0.001, 0.05);
    const Box a(Vec3(uniform(0.5, 1.0), ea, ea)), b(Vec3(eb, uniform(0.5, 1.0), eb));
    const Pose frame = randomPose(2.0);
    const double s2 = std::sqrt(2.0);
    Pose pa, pb;
    pa.q = (frame.q * Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()))).normalized();
    pb.q = (frame.q * Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitY()))).normalized();
    const Vec2 shift(uniform(-0.1, 0.1), uniform(-0.1, 0.1));  // where the edges cross, in F
    pa.x = frame.toWorld(Vec3(uniform(-0.3, 0.3), shift.y(), ea * s2 + eb * s2 - overlap));
    pb.x = frame.toWorld(Vec3(shift.x(), uniform(-0.3, 0.3), 0.0));
    const Manifold m = collideBoxBox(a, pa, b, pb);
    INFO("trial " << trial);
    REQUIRE(m.count == 1);
    CHECK((m.normal - frame.q * Vec3::UnitZ()).norm() < 1e-9);  // round-off of the rotations
    CHECK(m.points[0].depth == Approx(overlap).margin(1e-9));
    // The edges cross above (shift.x, shift.y): A's edge at height eb s2 - overlap, B's at eb s2.
    const Vec3 expected = frame.toWorld(Vec3(shift.x(), shift.y(), eb * s2 - 0.5 * overlap));
    CHECK((m.points[0].position - expected).norm() < 1e-9);
  }
}

TEST_CASE("box-box: the normal is the axis of least overlap over the 15 axes", "[lab04][pts=2][sec=5]") {
  int touching = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const auto [a, pa, b, pb] = pressedBoxes();
    const Manifold m = collideBoxBox(a, pa, b, pb);
    const double least = leastOverlap15(a, pa, b, pb);
    INFO("trial " << trial << ", least overlap " << least);
    CHECK(m.empty() == (least < 0.0));  // separated exactly when some axis shows a gap
    if (m.empty()) continue;
    ++touching;
    // An independent search: no sampled direction shows less overlap than the 15 axes (the
    // overlap grows away from its minimum, so samples only bound it from above).
    double sampled = 1e300;
    for (int k = 0; k < 2000; ++k) {
      const Vec3 u = randomUnit();
      sampled = std::min(sampled, overlapAlong(a, pa, b, pb, u));
    }
    CHECK(least <= sampled + 1e-12);
    // The reported normal is that axis: a face may win over an edge within kEdgeAxisBias.
    const double along = overlapAlong(a, pa, b, pb, m.normal);
    CHECK(along >= least - 1e-9);  // round-off of the support points
    CHECK(along <= least / (1.0 - kEdgeAxisBias) + 1e-9);
    CHECK(m.maxDepth() <= along + 1e-9);
  }
  CHECK(touching > 20);  // extreme points pushed into each other: most trials touch
}

TEST_CASE("box-box: every contact point is the midpoint of two surface points, one on each box, its depth apart along the normal", "[lab04][pts=1][sec=5]") {
  // How far a point lies outside a box (negative inside, 0 on its surface).
  const auto outside = [](const Box& box, const Pose& pose, const Vec3& p) {
    return (pose.toBody(p).cwiseAbs() - box.half_extents).maxCoeff();
  };
  // With n from B to A, A's surface point is p - d/2 n and B's p + d/2 n.
  const auto onBothSurfaces = [&](const Box& a, const Pose& pa, const Box& b, const Pose& pb, const Manifold& m) {
    for (int k = 0; k < m.count; ++k) {
      const ContactPoint& c = m.points[k];
      INFO("point " << k << ", depth " << c.depth);
      CHECK(c.depth >= 0.0);
      CHECK(std::abs(outside(a, pa, c.position - 0.5 * c.depth * m.normal)) < 1e-9);  // round-off of the rotations
      CHECK(std::abs(outside(b, pb, c.position + 0.5 * c.depth * m.normal)) < 1e-9);  // round-off of the rotations
    }
  };
  // Fixed: a unit cube turned 30 degrees about z sunk 0.1 into a 4 x 4 x 1 slab's top face
  // touches at its 4 bottom corners, each 0.1 deep, halfway between z = 0.4 and z = 0.5.
  {
    const Box a(Vec3(0.5, 0.5, 0.5)), b(Vec3(2.0, 2.0, 0.5));
    Pose pa, pb;
    pa.x = Vec3(0.3, -0.2, 0.9);
    pa.q = Quat(Eigen::AngleAxisd(M_PI / 6, Vec3::UnitZ()));
    const Manifold m = collideBoxBox(a, pa, b, pb);
    REQUIRE(m.count == 4);
    CHECK((m.normal - Vec3::UnitZ()).norm() < 1e-12);  // a face column of the identity, exactly
    for (int k = 0; k < m.count; ++k) {
      CHECK(m.points[k].depth == Approx(0.1).margin(1e-12));  // differences of numbers near 1
      CHECK(m.points[k].position.z() == Approx(0.45).margin(1e-12));
      const Vec3 corner = pa.toBody(m.points[k].position - Vec3(0.0, 0.0, 0.05));
      CHECK(corner.cwiseAbs().isApprox(Vec3(0.5, 0.5, 0.5), 1e-12));  // a bottom corner of A
    }
    onBothSurfaces(a, pa, b, pb, m);
  }
  // Seeded random boxes pressed into each other along random directions: faces and edges alike.
  int touching = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const auto [a, pa, b, pb] = pressedBoxes();
    const Manifold m = collideBoxBox(a, pa, b, pb);
    INFO("trial " << trial);
    touching += !m.empty();
    onBothSurfaces(a, pa, b, pb, m);
  }
  CHECK(touching > 150);  // extreme points pushed into each other: most trials touch
}

TEST_CASE("clipping: a square cut by a plane keeps its inside part and the two crossings", "[lab04][pts=1][sec=5]") {
  ContactPolygon square;
  square.add(Vec3(-1, -1, 0), 0.1, 1);
  square.add(Vec3(1, -1, 0), 0.2, 2);
  square.add(Vec3(1, 1, 0), 0.3, 3);
  square.add(Vec3(-1, 1, 0), 0.4, 4);
  const double c = uniform(-0.9, 0.9);
  const ContactPolygon cut = clipPolygon(square, Vec3::UnitX(), c, 7);
  REQUIRE(cut.count == 4);
  int crossings = 0;
  for (int i = 0; i < cut.count; ++i) {
    CHECK(cut.points[i].position.x() <= c + 1e-15);  // exact up to one rounding
    // A crossing takes the id of its edge's first point: edges 1-2 and 3-4 cross the plane.
    if (cut.points[i].id == combineFeatures(1, 7) || cut.points[i].id == combineFeatures(3, 7)) {
      ++crossings;
      CHECK(cut.points[i].position.x() == Approx(c).margin(1e-15));
      CHECK(cut.points[i].depth == 0.0);  // documented: a crossing is made with depth 0
    } else {
      // A kept corner is copied unchanged: corner k (id k) had depth 0.1 k (to one rounding).
      CHECK(cut.points[i].depth == Approx(0.1 * cut.points[i].id).epsilon(1e-15));
    }
  }
  CHECK(crossings == 2);
  CHECK(clipPolygon(square, Vec3::UnitX(), -2.0, 7).count == 0);
  CHECK(clipPolygon(square, Vec3::UnitX(), 2.0, 7).count == 4);
  // The kept part is closed (m . p <= o): a plane through an edge keeps that edge's corners,
  // unchanged and once each, and adds no crossing where an edge only starts or ends on it.
  const ContactPolygon on_right = clipPolygon(square, Vec3::UnitX(), 1.0, 7);  // the whole square
  REQUIRE(on_right.count == 4);
  for (int i = 0; i < 4; ++i) {
    CHECK(on_right.points[i].id == square.points[i].id);
    CHECK(on_right.points[i].position == square.points[i].position);
  }
  const ContactPolygon on_left = clipPolygon(square, Vec3::UnitX(), -1.0, 7);  // the edge x = -1
  REQUIRE(on_left.count == 2);
  for (int i = 0; i < 2; ++i) {
    const std::uint32_t id = on_left.points[i].id;
    REQUIRE((id == 1 || id == 4));  // the corners (-1, -1) and (-1, 1)
    CHECK(on_left.points[i].position == square.points[id - 1].position);
    CHECK(on_left.points[i].depth == square.points[id - 1].depth);
  }
  CHECK(on_left.points[0].id != on_left.points[1].id);
}

TEST_CASE("reduction: 4 of a polygon's points, the deepest first, spanning most of its area", "[lab04][pts=1][sec=5]") {
  ContactPolygon octagon;
  const double phase = uniform(0.0, 1.0);
  int deepest = static_cast<int>(uniform(0.0, 8.0)) % 8;
  for (int k = 0; k < 8; ++k) {
    const double t = phase + k * M_PI / 4;
    octagon.add(Vec3(std::cos(t), std::sin(t), 0.0), k == deepest ? 0.5 : 0.1, static_cast<std::uint32_t>(10 + k));
  }
  const Manifold m = reduceContacts(Vec3::UnitZ(), octagon);
  REQUIRE(m.count == 4);
  CHECK(m.points[0].id == static_cast<std::uint32_t>(10 + deepest));
  // The kept points are candidates, unchanged.
  for (int i = 0; i < 4; ++i) {
    const int k = static_cast<int>(m.points[i].id) - 10;
    REQUIRE((k >= 0 && k < 8));
    CHECK(m.points[i].position == octagon.points[k].position);
  }
  // Deepest, its opposite corner, and one corner each side of that diagonal: a square of area 2
  // (the octagon's is 2.83); any other choice of 4 spans less.
  const Vec3 &p0 = m.points[0].position, &p1 = m.points[1].position, &p2 = m.points[2].position,
             &p3 = m.points[3].position;
  const double area = 0.5 * std::abs((p1 - p0).cross(p2 - p0).z()) + 0.5 * std::abs((p1 - p0).cross(p3 - p0).z());
  CHECK(area == Approx(2.0).epsilon(1e-12));
  // Distances and areas are measured in the plane normal to the normal: lifting every other
  // corner 0.8 along it (as contact midpoints at different depths are) changes nothing.
  ContactPolygon lifted = octagon;
  for (int k = 1; k < 8; k += 2) lifted.points[k].position.z() += 0.8;
  const Manifold l = reduceContacts(Vec3::UnitZ(), lifted);
  REQUIRE(l.count == 4);
  for (int i = 0; i < 4; ++i) CHECK(l.points[i].id == m.points[i].id);
  // At most 4 candidates, 4 included, are all kept in their order, even when they span no area
  // that a choice of fewer would lose: a triangle with a deeper point inside it, and 4 points on
  // one line.
  ContactPolygon triangle;
  triangle.add(Vec3(-1.0, -1.0, 0.0), 0.1, 1);
  triangle.add(Vec3(1.0, -1.0, 0.0), 0.1, 2);
  triangle.add(Vec3(uniform(-0.2, 0.2), uniform(-0.2, 0.2), 0.0), 0.3, 3);  // inside
  triangle.add(Vec3(0.0, 1.0, 0.0), 0.1, 4);
  ContactPolygon line;
  for (int k = 0; k < 4; ++k) line.add(Vec3(uniform(-1.0, 1.0), 0.0, 0.0), uniform(0.0, 0.2), static_cast<std::uint32_t>(k + 1));
  for (const ContactPolygon* few : {&triangle, &line}) {
    const Manifold kept = reduceContacts(Vec3::UnitZ(), *few);
    REQUIRE(kept.count == 4);
    for (int i = 0; i < 4; ++i) {
      CHECK(kept.points[i].id == few->points[i].id);
      CHECK(kept.points[i].position == few->points[i].position);
      CHECK(kept.points[i].depth == few->points[i].depth);
    }
  }
}

TEST_CASE("convex polyhedra: two boxes as polyhedra give the box-box normal and depth", "[lab04][pts=2][sec=6]") {
  int touching = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec3 ha(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0));
    const Vec3 hb(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0));
    Pose pa = randomPose(1.0), pb = randomPose(1.0);
    Shape sb = Box(hb);
    placeAlong(Shape(Box(ha)), pa, sb, pb, randomUnit(), -uniform(0.01, 0.3));
    const Manifold boxes = collideBoxBox(Box(ha), pa, Box(hb), pb);
    const Manifold polys = collideConvexConvex(ConvexPolyhedron::box(ha), pa, ConvexPolyhedron::box(hb), pb);
    INFO("trial " << trial);
    REQUIRE(boxes.empty() == polys.empty());
    if (boxes.empty()) continue;
    ++touching;
    // The same axes by another route: the least overlaps agree to round-off, the normals too
    // unless two axes tie within the face preference (then both are right: compare overlaps).
    const Shape A = Box(ha);
    CHECK(overlapAlong(A, pa, sb, pb, polys.normal) ==
          Approx(overlapAlong(A, pa, sb, pb, boxes.normal)).margin(1e-9));
    CHECK(polys.maxDepth() == Approx(boxes.maxDepth()).margin(1e-9));
    CHECK(polys.count == boxes.count);
  }
  CHECK(touching > 20);  // extreme points pushed into each other: most trials touch
}

TEST_CASE("convex polyhedra: a tetrahedron's corner pressed into a box face is one contact", "[lab04][pts=1][sec=6]") {
  const Box box(Vec3(1.0, 1.0, 0.5));
  const Pose pb = randomPose(1.0);
  // A tetrahedron pointing down (-z in B's frame) with its apex at the origin of its frame.
  const double s = uniform(0.3, 0.6), overlap = uniform(0.001, 0.05);
  const ConvexPolyhedron tet = ConvexPolyhedron::tetrahedron(Vec3(0, 0, 0), Vec3(s, 0, s), Vec3(-0.5 * s, 0.8 * s, s),
                                                             Vec3(-0.5 * s, -0.8 * s, s));
  Pose pa;
  pa.q = pb.q;
  pa.x = pb.toWorld(Vec3(uniform(-0.5, 0.5), uniform(-0.5, 0.5), 0.5 - overlap));
  const Manifold m = collideConvexConvex(tet, pa, ConvexPolyhedron::box(box.half_extents), pb);
  REQUIRE(m.count == 1);
  CHECK((m.normal - pb.q * Vec3::UnitZ()).norm() < 1e-9);  // round-off of the rotations
  CHECK(m.points[0].depth == Approx(overlap).margin(1e-9));
  CHECK((m.points[0].position - (pa.x + 0.5 * overlap * m.normal)).norm() < 1e-9);
}
