// Framework tests (not graded): distance()'s closed forms for a sphere against a sphere or a box,
// which time of impact uses, so that its tests need no GJK of the student's.
#include <cmath>

#include "collision_support.hpp"
#include "physlab/collision.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

Pose placedAt(const Vec3& x, const Quat& q = Quat::Identity()) {
  Pose p;
  p.x = x;
  p.q = q;
  return p;
}

}  // namespace

TEST_CASE("collision framework: distance of two spheres is |x_A - x_B| - r_A - r_B, by hand", "[common]") {
  const DistanceResult d = distance(Sphere(1.0), placedAt(Vec3(0, 0, 0)), Sphere(0.5), placedAt(Vec3(3, 4, 0)));
  CHECK_FALSE(d.overlap);
  CHECK(d.distance == Approx(3.5).epsilon(1e-15));  // 5 - 1 - 0.5, one rounding
  CHECK((d.point_a - Vec3(0.6, 0.8, 0.0)).norm() < 1e-15);
  CHECK((d.point_b - Vec3(2.7, 3.6, 0.0)).norm() < 1e-15);
  CHECK(d.iterations == 1);
  // Exactly touching is overlap at distance 0, as GJK reports it; coincident centres too.
  const DistanceResult touching = distance(Sphere(1.0), Pose{}, Sphere(1.0), placedAt(Vec3(2, 0, 0)));
  CHECK(touching.overlap);
  CHECK(touching.distance == 0.0);
  const DistanceResult same = distance(Sphere(1.0), Pose{}, Sphere(2.0), Pose{});
  CHECK(same.overlap);
  CHECK(same.distance == 0.0);
}

TEST_CASE("collision framework: distance of a sphere and a box clamps the centre to the box, either order", "[common]") {
  const Box box(Vec3(1.0, 2.0, 3.0));
  // Turned a quarter about z: in the world the box spans x in [8, 12], y in [-1, 1], z in [-3, 3].
  const Pose turned = placedAt(Vec3(10, 0, 0), Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())));
  struct Case {
    Vec3 centre, nearest;  // world frame
  };
  const Case cases[] = {
      {Vec3(10, 3, 0), Vec3(10, 1, 0)},    // off a face
      {Vec3(14, 3, 0), Vec3(12, 1, 0)},    // off an edge
      {Vec3(14, 3, 5), Vec3(12, 1, 3)},    // off a corner
  };
  for (const Case& c : cases) {
    INFO("centre " << c.centre.transpose());
    const DistanceResult d = distance(Sphere(0.5), placedAt(c.centre), box, turned);
    const double expected = (c.centre - c.nearest).norm() - 0.5;
    CHECK_FALSE(d.overlap);
    CHECK(std::abs(d.distance - expected) < 1e-12);  // a rotation and a clamp: a few roundings
    CHECK((d.point_b - c.nearest).norm() < 1e-12);
    CHECK((d.point_a - (c.centre + 0.5 * (c.nearest - c.centre).normalized())).norm() < 1e-12);
    const DistanceResult swapped = distance(box, turned, Sphere(0.5), placedAt(c.centre));
    CHECK(swapped.distance == d.distance);
    CHECK(swapped.point_a == d.point_b);
    CHECK(swapped.point_b == d.point_a);
  }
  // A centre inside the box, and a sphere exactly touching a face, overlap.
  CHECK(distance(Sphere(0.5), placedAt(Vec3(10.5, 0.5, 1)), box, turned).overlap);
  CHECK(distance(Sphere(1.0), placedAt(Vec3(0, 0, 4)), box, Pose{}).overlap);
  CHECK_FALSE(distance(Sphere(1.0), placedAt(Vec3(0, 0, 4 + 1e-9)), box, Pose{}).overlap);
}
