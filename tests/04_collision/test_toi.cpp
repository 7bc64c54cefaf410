// Lab 4 graded tests, time of impact: both methods against the analytic time of two spheres, a
// spinning box falling on a plane, a fast body and a thin wall, and their cost in queries.
#include <algorithm>
#include <cmath>
#include <vector>

#include "collision_support.hpp"
#include "physlab/collision.hpp"
#include "physlab/error.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

using ToiMethod = ToiResult (*)(const Shape&, const Pose&, const Motion&, const Shape&, const Pose&, const Motion&,
                                double, double);
const ToiMethod kMethods[] = {toiBisection, toiConservativeAdvancement};
const char* const kMethodNames[] = {"bisection", "conservative advancement"};

// Two spheres that touch at time t_c: relative position R u at t_c, approaching.
struct SpherePair {
  double ra, rb, t_contact;
  Pose pa, pb;
  Motion ma, mb;
  double gap(double t) const {
    return (pa.x + t * ma.v - pb.x - t * mb.v).norm() - ra - rb;
  }
};

SpherePair approachingSpheres(double h) {
  SpherePair s;
  s.ra = uniform(0.1, 0.5);
  s.rb = uniform(0.1, 0.5);
  s.t_contact = uniform(0.2, 0.8) * h;
  const Vec3 u = randomUnit();
  s.mb.v = randomVec3(3.0);
  s.ma.v = s.mb.v - uniform(5.0, 20.0) * (u + randomVec3(0.5)).normalized();  // relative velocity
  if ((s.ma.v - s.mb.v).dot(u) > -1.0) s.ma.v -= 2.0 * u;                          // towards B along u
  s.pb.x = randomVec3(2.0);
  s.pa.x = s.pb.x + (s.ra + s.rb) * u - s.t_contact * (s.ma.v - s.mb.v);
  return s;
}

}  // namespace

TEST_CASE("toi: two spheres on straight lines touch at the analytic time", "[lab04][pts=2][sec=9]") {
  const double h = 1.0 / 60, tol = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    const SpherePair s = approachingSpheres(h);
    // The first root of |dx + dv t|^2 = (ra + rb)^2.
    const Vec3 dx = s.pa.x - s.pb.x, dv = s.ma.v - s.mb.v;
    const double R = s.ra + s.rb, a = dv.squaredNorm(), b = 2 * dx.dot(dv), c = dx.squaredNorm() - R * R;
    const double t_exact = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
    REQUIRE(t_exact == Approx(s.t_contact).margin(1e-12));  // the construction, checked
    for (int k = 0; k < 2; ++k) {
      const ToiResult r = kMethods[k](Sphere(s.ra), s.pa, s.ma, Sphere(s.rb), s.pb, s.mb, h, tol);
      INFO(kMethodNames[k] << ", trial " << trial);
      REQUIRE(r.hit);
      // Apart (or touching) at the reported time, by at most the tolerance, and never late.
      CHECK(s.gap(r.time) >= -1e-12);
      CHECK(s.gap(r.time) <= tol + 1e-12);
      CHECK(r.time <= t_exact + 1e-12);
    }
  }
}

TEST_CASE("toi: spheres that pass each other or meet after the step report no contact", "[lab04][pts=1][sec=9]") {
  const double h = 1.0 / 60;
  SpherePair late = approachingSpheres(h);
  // Start them farther back along their paths: contact at 1.5 h to 3 h.
  const double extra = uniform(1.3, 2.8) * h;
  late.pa.x -= extra * late.ma.v;
  late.pb.x -= extra * late.mb.v;
  // A miss: B offset sideways by more than the sum of the radii from A's path.
  SpherePair miss = approachingSpheres(h);
  const Vec3 dv = miss.ma.v - miss.mb.v;
  const Vec3 side = dv.cross(randomUnit()).normalized();
  miss.pb.x += (miss.ra + miss.rb + uniform(0.01, 0.5)) * side;
  for (int k = 0; k < 2; ++k) {
    INFO(kMethodNames[k]);
    CHECK_FALSE(kMethods[k](Sphere(late.ra), late.pa, late.ma, Sphere(late.rb), late.pb, late.mb, h, 1e-6).hit);
    // The closest approach of the miss, from the relative motion, is known to be positive.
    const Vec3 dx = miss.pa.x - miss.pb.x;
    const double t_min = std::clamp(-dx.dot(dv) / dv.squaredNorm(), 0.0, h);
    if (miss.gap(t_min) > 1e-3) {
      CHECK_FALSE(kMethods[k](Sphere(miss.ra), miss.pa, miss.ma, Sphere(miss.rb), miss.pb, miss.mb, h, 1e-6).hit);
    }
  }
}

TEST_CASE("toi: a step or tolerance that is not positive is refused by name", "[lab04][pts=1][sec=9]") {
  // Two spheres at rest far apart: with valid arguments no contact, and a method that forgets a
  // check returns normally here instead of looping on a bracket it can never shrink.
  const Pose pa = randomPose(1.0);
  Pose pb = pa;
  pb.x += 5.0 * randomUnit();
  const Sphere a(uniform(0.1, 0.5)), b(uniform(0.1, 0.5));
  const double nan = std::nan("");
  for (int k = 0; k < 2; ++k) {
    INFO(kMethodNames[k]);
    const auto query = [&](double h, double tolerance) {
      return kMethods[k](a, pa, Motion{}, b, pb, Motion{}, h, tolerance);
    };
    CHECK_FALSE(query(1.0 / 60, 1e-6).hit);
    for (double h : {0.0, -1.0 / 60, nan}) {
      CHECK_THROWS_AS(query(h, 1e-6), InvalidInput);
      CHECK_THROWS_WITH(query(h, 1e-6), Catch::Contains("step h"));
    }
    for (double tolerance : {0.0, -1e-6, nan}) {
      CHECK_THROWS_AS(query(1.0 / 60, tolerance), InvalidInput);
      CHECK_THROWS_WITH(query(1.0 / 60, tolerance), Catch::Contains("tolerance"));
    }
  }
}

TEST_CASE("toi: a pair already overlapping at the start is hit at time 0, after one query", "[lab04][pts=1][sec=9]") {
  // Two spheres overlapping at t = 0 and flying apart fast enough to separate within the step:
  // the first contact is at 0, and the one test (or distance query) at t = 0 shows it.
  const double h = 1.0 / 60, tol = 1e-6;
  const double ra = uniform(0.1, 0.5), rb = uniform(0.1, 0.5), overlap = uniform(0.01, 0.05);
  const Vec3 u = randomUnit();
  Pose pa, pb;
  pb.x = randomVec3(2.0);
  pa.x = pb.x + (ra + rb - overlap) * u;
  const Motion ma{uniform(6.0, 10.0) * u, Vec3::Zero()}, mb{-uniform(6.0, 10.0) * u, Vec3::Zero()};
  // Apart by (12 to 20 m/s) h - overlap >= 0.15 m at the end of the step.
  REQUIRE_FALSE(distance(Sphere(ra), advance(pa, ma, h), Sphere(rb), advance(pb, mb, h)).overlap);
  for (int k = 0; k < 2; ++k) {
    const ToiResult r = kMethods[k](Sphere(ra), pa, ma, Sphere(rb), pb, mb, h, tol);
    INFO(kMethodNames[k]);
    CHECK(r.hit);
    CHECK(r.time == 0.0);
    CHECK(r.queries == 1);
  }
}

TEST_CASE("toi: a contact exactly at the end of the step is a hit", "[lab04][pts=1][sec=9]") {
  // Spheres of radius 1/4, 1/4 m apart, closing at 2 m/s: they touch at t = 1/8 s = h exactly
  // (binary fractions: the positions advance() gives at 1/8 s are exact). The step is [0, h].
  const double h = 0.125, tol = 1e-6;
  const Vec3 u = Vec3::Unit(static_cast<Index>(uniform(0.0, 2.999)));
  Pose pa, pb;
  pa.x = 0.75 * u;
  const Motion ma{-2.0 * u, Vec3::Zero()};
  auto gap = [&](double t) { return 0.25 - 2.0 * t; };
  for (int k = 0; k < 2; ++k) {
    const ToiResult r = kMethods[k](Sphere(0.25), pa, ma, Sphere(0.25), pb, Motion{}, h, tol);
    INFO(kMethodNames[k]);
    REQUIRE(r.hit);
    CHECK(r.time <= h);
    CHECK(gap(r.time) >= -1e-15);       // apart or touching, to one rounding
    CHECK(gap(r.time) <= tol + 1e-15);  // by at most the tolerance
  }
}

TEST_CASE("toi: queries counts every overlap test and distance query made", "[lab04][pts=1][sec=9]") {
  const double tol = 1e-6;
  // At rest, apart: the speed bound is 0, so bisection samples the step once (N = 1, tests at 0
  // and h) and advancement stops after its first distance query (no approach at all).
  {
    Pose pa;
    pa.x = Vec3(uniform(1.0, 2.0), 0.0, 0.0);
    for (int k = 0; k < 2; ++k) {
      const ToiResult r = kMethods[k](Sphere(0.25), pa, Motion{}, Sphere(0.25), Pose{}, Motion{}, 0.1, tol);
      INFO(kMethodNames[k] << " at rest");
      CHECK_FALSE(r.hit);
      CHECK(r.queries == (k == 0 ? 2 : 1));
    }
    // Two triangles have inner radii 0 (no sampling bound), yet at rest nothing approaches:
    // still one sample, not 0 / 0.
    const Triangle t1(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)), t2(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1));
    Pose p2;
    p2.x = Vec3(uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(0.5, 1.0));  // above t1's plane
    for (int k = 0; k < 2; ++k) {
      const ToiResult r = kMethods[k](t1, Pose{}, Motion{}, t2, p2, Motion{}, 0.1, tol);
      INFO(kMethodNames[k] << ", triangles at rest");
      CHECK_FALSE(r.hit);
      CHECK(r.queries == (k == 0 ? 2 : 1));
    }
  }
  // Head on: radii 1/4, gap g in [0.1, 0.25] m, closing at 3 m/s, h = 0.1 s. Bisection: mu h =
  // 0.3 m is less than the inner radii (0.5 m), so N = 1; the test at 0 is apart and the one at h
  // overlaps (the gap would be g - 0.3 < 0); then m halvings of [0, h], the fewest with
  // 3 h / 2^m <= tol. Advancement: the first advance, g / 3, lands on the contact, where the
  // second query finds the gap (0, to round-off) within the tolerance.
  {
    const double g = uniform(0.1, 0.25), h = 0.1;
    Pose pa;
    pa.x = Vec3(0.5 + g, 0.0, 0.0);
    const Motion ma{Vec3(-3.0, 0.0, 0.0), Vec3::Zero()};
    int halvings = 0;
    while (3.0 * h / std::pow(2.0, halvings) > tol) ++halvings;  // 19: 5.7e-7 <= 1e-6 < 1.1e-6
    const ToiResult bis = toiBisection(Sphere(0.25), pa, ma, Sphere(0.25), Pose{}, Motion{}, h, tol);
    const ToiResult ca = toiConservativeAdvancement(Sphere(0.25), pa, ma, Sphere(0.25), Pose{}, Motion{}, h, tol);
    INFO("head on, gap " << g << " m");
    REQUIRE((bis.hit && ca.hit));
    CHECK(bis.queries == 2 + halvings);
    CHECK(ca.queries == 2);
  }
}

TEST_CASE("toi: a spinning box falling on a plane is caught at its first touch", "[lab04][pts=2][sec=9]") {
  const double h = 0.1, tol = 1e-6;
  const Box box(Vec3(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0)));
  const Plane ground(Vec3::UnitZ(), 0.0);
  Pose pose = randomPose(1.0);
  const Motion motion{Vec3(uniform(-2, 2), uniform(-2, 2), -40.0), randomUnit() * uniform(5.0, 20.0)};
  // The lowest corner's height, from the rotation written out here.
  auto gap = [&](double t) {
    const double angle = motion.omega.norm() * t;
    const Mat3 R = Eigen::AngleAxisd(angle, motion.omega.normalized()).toRotationMatrix() * pose.q.toRotationMatrix();
    return pose.x.z() + t * motion.v.z() - R.row(2).cwiseAbs().dot(box.half_extents.transpose());
  };
  pose.x.z() += uniform(0.3, 1.0) - gap(0.0);  // the lowest corner 0.3 m to 1 m up
  // The first touch by a dense scan (a corner moves at most ~60 m/s: 2e4 samples of 5e-6 s
  // cannot skip a dip below the plane deeper than 3e-4 m) refined by bisection.
  double lo = 0.0, hi = h;
  for (int k = 1; k <= 20000; ++k) {
    if (gap(h * k / 20000) <= 0.0) {
      hi = h * k / 20000;
      break;
    }
    lo = h * k / 20000;
  }
  for (int k = 0; k < 60; ++k) (gap(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  for (int k = 0; k < 2; ++k) {
    const ToiResult r = kMethods[k](box, pose, motion, ground, Pose{}, Motion{}, h, tol);
    INFO(kMethodNames[k]);
    REQUIRE(r.hit);
    CHECK(gap(r.time) >= -1e-12);       // apart, to round-off
    CHECK(gap(r.time) <= tol + 1e-12);  // by at most the tolerance
    CHECK(r.time <= hi + 1e-12);        // not after the first touch
  }
}

TEST_CASE("toi: a box spinning in place is caught when its edge first dips to the plane", "[lab04][pts=1][sec=9]") {
  // No linear motion at all: only the spin brings the box down, so a speed bound without the
  // spin term sees nothing coming. Turned by theta about its x axis, the box reaches
  // r(theta) = h_y |sin theta| + h_z |cos theta| below its centre, rising from h_z at theta = 0 to
  // rho = |(h_y, h_z)| at theta = phi = atan2(h_y, h_z). The centre is h_z + g above the plane, so
  // the box first touches at theta* = phi - acos((h_z + g) / rho): t* = theta* / omega.
  const double tol = 1e-6;
  for (int trial = 0; trial < 10; ++trial) {
    const Box box(Vec3(uniform(0.2, 1.0), uniform(0.2, 1.0), uniform(0.2, 1.0)));
    const double hy = box.half_extents.y(), hz = box.half_extents.z();
    const double rho = std::hypot(hy, hz), phi = std::atan2(hy, hz);
    const double g = uniform(0.2, 0.8) * (rho - hz);
    const double omega = uniform(5.0, 20.0) * (uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0);
    const double t_contact = (phi - std::acos((hz + g) / rho)) / std::abs(omega);
    // The step ends at theta = phi, the deepest dip: overlapping there, so one sample suffices.
    const double h = phi / std::abs(omega);
    const double yaw = uniform(0.0, 6.28);
    Pose pose;
    pose.q = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()));
    pose.x = Vec3(uniform(-1.0, 1.0), uniform(-1.0, 1.0), hz + g);
    const Motion motion{Vec3::Zero(), omega * (pose.q * Vec3::UnitX())};
    auto gap = [&](double t) {
      const double theta = omega * t;
      return hz + g - (hy * std::abs(std::sin(theta)) + hz * std::abs(std::cos(theta)));
    };
    REQUIRE(gap(t_contact) == Approx(0.0).margin(1e-12));  // the construction, checked
    for (int k = 0; k < 2; ++k) {
      const ToiResult r = kMethods[k](box, pose, motion, Plane(Vec3::UnitZ(), 0.0), Pose{}, Motion{}, h, tol);
      INFO(kMethodNames[k] << ", trial " << trial << ", contact at " << t_contact << " s");
      REQUIRE(r.hit);
      CHECK(gap(r.time) >= -1e-12);       // apart, to the round-off of advance()
      CHECK(gap(r.time) <= tol + 1e-12);  // by at most the tolerance
      CHECK(r.time <= t_contact + 1e-12);  // not after the first touch
    }
  }
}

TEST_CASE("toi: a fast body is caught at a thin wall that a check at the step's end misses", "[lab04][pts=2][sec=9]") {
  const double speed = uniform(200.0, 400.0), h = 1.0 / 60, tol = 1e-6;
  const std::vector<CollisionBody> scene = bulletAndWall(speed);
  const CollisionBody &wall = scene[0], &bullet = scene[1];
  // At the end of the step the bullet is metres past the wall: the discrete check sees nothing.
  REQUIRE_FALSE(distance(bullet.shape, advance(bullet.pose, bullet.motion, h), wall.shape, wall.pose).overlap);
  const double t_contact = (1.0 - 0.01 - 0.05) / speed;  // 1 m to go, less wall and bullet half widths
  for (int k = 0; k < 2; ++k) {
    const ToiResult r = kMethods[k](bullet.shape, bullet.pose, bullet.motion, wall.shape, wall.pose, wall.motion, h, tol);
    INFO(kMethodNames[k]);
    REQUIRE(r.hit);
    CHECK(r.time <= t_contact + 1e-12);  // never late, to round-off
    CHECK(r.time >= t_contact - tol / speed - 1e-12);  // the gap at r.time is at most tol
  }
}

TEST_CASE("toi: conservative advancement needs fewer distance queries than bisection needs overlap tests", "[lab04][pts=1][sec=9]") {
  const double h = 1.0 / 60;
  for (double tol : {1e-3, 1e-6, 1e-9}) {
    const SpherePair s = approachingSpheres(h);
    const ToiResult bis = toiBisection(Sphere(s.ra), s.pa, s.ma, Sphere(s.rb), s.pb, s.mb, h, tol);
    const ToiResult ca = toiConservativeAdvancement(Sphere(s.ra), s.pa, s.ma, Sphere(s.rb), s.pb, s.mb, h, tol);
    INFO("tolerance " << tol << ": bisection " << bis.queries << ", advancement " << ca.queries);
    REQUIRE((bis.hit && ca.hit));
    CHECK(ca.queries < bis.queries);
    // Bisection halves a bracket per test: it needs about log2(speed h / tol) of them.
    CHECK(bis.queries >= static_cast<int>(std::log2((s.ma.v - s.mb.v).norm() * h / tol)) - 4);
  }
}
