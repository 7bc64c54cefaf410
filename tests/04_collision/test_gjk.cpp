// Lab 4 graded tests, GJK: distances and closest points against closed forms, and against a
// brute-force minimum over sampled surface points for random convex pairs.
#include <algorithm>
#include <cmath>
#include <vector>

#include "collision_support.hpp"
#include "physlab/collision.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// Points spread over the surface of a posed shape: support points along random directions
// (every surface point of a convex shape with a unique normal is one).
std::vector<Vec3> surfaceSamples(const Shape& s, const Pose& pose, int n) {
  std::vector<Vec3> points;
  for (int k = 0; k < n; ++k) points.push_back(support(s, pose, randomUnit()));
  return points;
}

}  // namespace

TEST_CASE("gjk: two spheres are |x_A - x_B| - r_A - r_B apart along the line of centres", "[lab04][pts=1][sec=8]") {
  const double ra = uniform(0.2, 1.0), rb = uniform(0.2, 1.0), gap = uniform(0.01, 2.0);
  const Vec3 u = randomUnit();
  Pose pa = randomPose(2.0), pb = randomPose(2.0);
  pa.x = pb.x + (ra + rb + gap) * u;
  const DistanceResult d = gjkDistance(Sphere(ra), pa, Sphere(rb), pb);
  REQUIRE_FALSE(d.overlap);
  // Sphere cores are points: GJK is exact, round-off only.
  CHECK(d.distance == Approx(gap).margin(1e-12));
  CHECK((d.point_a - (pa.x - ra * u)).norm() < 1e-12);
  CHECK((d.point_b - (pb.x + rb * u)).norm() < 1e-12);
}

TEST_CASE("gjk: a box above a flat slab is as far as its lowest corner", "[lab04][pts=1][sec=8]") {
  // The slab's top face stands for a plane at height 0, wide enough that the box is above it.
  const Box slab(Vec3(20.0, 20.0, 0.5));
  Pose ps;
  ps.x = Vec3(0.0, 0.0, -0.5);
  const Box box(Vec3(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0)));
  Pose pa = randomPose(1.0);
  const Mat3 R = pa.q.toRotationMatrix();
  const double reach_down = R.row(2).cwiseAbs().dot(box.half_extents.transpose());
  const double gap = uniform(0.01, 1.0);
  pa.x.z() = reach_down + gap;
  const DistanceResult d = gjkDistance(box, pa, slab, ps);
  REQUIRE_FALSE(d.overlap);
  CHECK(d.distance == Approx(gap).margin(1e-9));  // flat faces: exact up to round-off
  CHECK(d.point_a.z() == Approx(gap).margin(1e-9));
  CHECK(d.point_b.z() == Approx(0.0).margin(1e-9));
  CHECK((d.point_a - d.point_b).norm() == Approx(d.distance).margin(1e-9));
}

TEST_CASE("gjk: a point (a sphere's centre) is as far from a box as its clamped copy", "[lab04][pts=1][sec=8]") {
  for (int trial = 0; trial < 20; ++trial) {
    const Box box(Vec3(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0)));
    const Pose pb = randomPose(1.0);
    const double r = uniform(0.01, 0.1);
    Pose pa;
    Vec3 local;
    do local = randomVec3(2.0);
    while ((local - local.cwiseMax(-box.half_extents).cwiseMin(box.half_extents)).norm() < r + 0.01);
    pa.x = pb.toWorld(local);
    const Vec3 clamped = local.cwiseMax(-box.half_extents).cwiseMin(box.half_extents);
    const DistanceResult d = gjkDistance(Sphere(r), pa, box, pb);
    INFO("trial " << trial);
    REQUIRE_FALSE(d.overlap);
    CHECK(d.distance == Approx((local - clamped).norm() - r).margin(1e-9));  // round-off
    CHECK((d.point_b - pb.toWorld(clamped)).norm() < 1e-9);
  }
}

TEST_CASE("gjk: random convex pairs are no farther apart than any two sampled surface points", "[lab04][pts=2][sec=8]") {
  const Kind kinds[] = {Kind::Sphere, Kind::Box, Kind::Capsule, Kind::Tetrahedron};
  for (Kind ka : kinds) {
    for (Kind kb : kinds) {
      for (int trial = 0; trial < 5; ++trial) {
        const Shape a = randomShape(ka);
        Shape b = randomShape(kb);
        Pose pa = randomPose(1.0), pb = randomPose(1.0);
        placeAlong(a, pa, b, pb, randomUnit(), uniform(0.05, 1.0));
        const DistanceResult d = gjkDistance(a, pa, b, pb);
        INFO(pairName(a, b) << ", trial " << trial);
        REQUIRE_FALSE(d.overlap);
        // The closest points are on the shapes' surfaces and the distance apart.
        CHECK(std::abs(signedDistance(a, pa, d.point_a)) < 1e-7);  // GJK's relative tolerance
        CHECK(std::abs(signedDistance(b, pb, d.point_b)) < 1e-7);
        CHECK((d.point_a - d.point_b).norm() == Approx(d.distance).margin(1e-9));
        // The brute-force minimum over sampled pairs can only be larger (upper bound).
        const std::vector<Vec3> sa = surfaceSamples(a, pa, 300), sb = surfaceSamples(b, pb, 300);
        double brute = 1e300;
        for (const Vec3& p : sa) {
          for (const Vec3& q : sb) brute = std::min(brute, (p - q).norm());
        }
        CHECK(d.distance <= brute + 1e-9);
        // And no separating plane through the closest points is crossed (it is a lower bound).
        const Vec3 n = (d.point_a - d.point_b).normalized();
        CHECK(n.dot(support(a, pa, -n)) - n.dot(support(b, pb, n)) == Approx(d.distance).margin(1e-7));
      }
    }
  }
}

TEST_CASE("gjk: polyhedra a hair apart, faces parallel, are never reported overlapping", "[lab04][pts=1][sec=8]") {
  // Face against face gives simplices whose new vertex lies in the plane of the others (a flat
  // tetrahedron): its side tests are round-off, and a GJK that trusts them claims contact.
  int trials = 0;
  for (const Kind kb : {Kind::Box, Kind::Tetrahedron}) {
    for (int trial = 0; trial < 400; ++trial, ++trials) {
      const Shape a = randomShape(Kind::Box);
      Shape b = randomShape(kb);
      Pose pa = randomPose(1.0), pb = randomPose(1.0);
      pb.q = pa.q;  // the same orientation: A's faces parallel to B's (boxes), or to a face normal
      const Vec3 u = pa.q * Vec3::Unit(static_cast<Index>(uniform(0.0, 2.999)));
      const double gap = uniform(1e-5, 1e-3);
      placeAlong(a, pa, b, pb, u, gap);
      const DistanceResult d = gjkDistance(a, pa, b, pb);
      INFO(pairName(a, b) << ", trial " << trial << ", gap " << gap);
      REQUIRE_FALSE(d.overlap);
      // Apart by at least the gap along u (a separating plane), to GJK's relative tolerance.
      CHECK(d.distance >= gap - 1e-7);
    }
  }
  CHECK(trials == 800);
}

TEST_CASE("gjk: overlapping shapes are reported as overlapping", "[lab04][pts=1][sec=8]") {
  const Kind kinds[] = {Kind::Sphere, Kind::Box, Kind::Capsule, Kind::Tetrahedron};
  for (Kind ka : kinds) {
    for (Kind kb : kinds) {
      const Shape a = randomShape(ka), b = randomShape(kb);
      Pose pa = randomPose(1.0), pb = randomPose(1.0);
      pa.x = pb.x + randomVec3(0.02);  // each contains a ball of 0.05 m about its centre
      INFO(pairName(a, b));
      const DistanceResult d = gjkDistance(a, pa, b, pb);
      CHECK(d.overlap);
      CHECK(d.distance == 0.0);  // documented: 0 when overlapping, never a negative depth
    }
  }
  // Touching counts as overlapping: two spheres exactly r_A + r_B apart (binary fractions, so
  // the core distance is exactly the sum of the margins).
  const Vec3 u = Vec3::Unit(static_cast<Index>(uniform(0.0, 2.999)));
  Pose pa, pb;
  pa.x = 0.75 * u;
  const DistanceResult touch = gjkDistance(Sphere(0.25), pa, Sphere(0.5), pb);
  INFO("spheres touching");
  CHECK(touch.overlap);
  CHECK(touch.distance == 0.0);
}
