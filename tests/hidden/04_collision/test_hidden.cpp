// Lab 4 hidden tests (instructor only, shown after grades are published).
#include <cmath>
#include <vector>

#include "../../04_collision/collision_support.hpp"
#include "physlab/collision.hpp"

using namespace physlab;
using namespace physlab::test;

TEST_CASE("hidden: each box of a stack rests on the one below at 4 corners with the stack's overlap", "[lab04][pts=2][hidden][sec=5]") {
  const double overlap = uniform(0.001, 0.02);
  const std::vector<CollisionBody> stack = boxStack(4, overlap);
  // Turn the whole stack by a random rigid motion: the contacts must follow it.
  const Mat3 Q = randomRotation();
  const Vec3 T = randomVec3(3.0);
  for (std::size_t i = 1; i < stack.size(); ++i) {
    const Shape below = moved(stack[i - 1].shape, Q, T);
    const Manifold m = collide(stack[i].shape, moved(stack[i].pose, Q, T), below, moved(stack[i - 1].pose, Q, T));
    INFO("box " << i);
    REQUIRE(m.count == 4);
    CHECK((m.normal - Q * Vec3::UnitZ()).norm() < 1e-9);  // round-off of the rotation
    for (int k = 0; k < 4; ++k) CHECK(m.points[k].depth == Approx(overlap).margin(1e-9));
  }
}

TEST_CASE("hidden: parallel capsules lying side by side touch at both ends of their overlap", "[lab04][pts=1][hidden][sec=3]") {
  const Capsule a(uniform(0.1, 0.3), uniform(0.5, 1.0)), b(uniform(0.1, 0.3), uniform(0.5, 1.0));
  const Pose frame = randomPose(1.0);
  const double overlap = uniform(0.001, 0.05), shift = uniform(-0.3, 0.3);
  Pose pa = frame, pb = frame;
  pa.x = frame.toWorld(Vec3(a.radius + b.radius - overlap, 0.0, shift));
  const Manifold m = collideCapsuleCapsule(a, pa, b, pb);
  REQUIRE(m.count == 2);
  CHECK((m.normal - frame.q * Vec3::UnitX()).norm() < 1e-9);  // round-off of the rotation
  const double lo = std::max(-a.half_height + shift, -b.half_height), hi = std::min(a.half_height + shift, b.half_height);
  std::vector<double> heights;
  for (int k = 0; k < 2; ++k) {
    CHECK(m.points[k].depth == Approx(overlap).margin(1e-9));
    heights.push_back(frame.toBody(m.points[k].position).z());
  }
  CHECK(std::min(heights[0], heights[1]) == Approx(lo).margin(1e-9));
  CHECK(std::max(heights[0], heights[1]) == Approx(hi).margin(1e-9));
  CHECK(m.points[0].id != m.points[1].id);  // ids are unique within a manifold (warm starting)
}

TEST_CASE("hidden: both time-of-impact methods agree on random pairs from a shape soup", "[lab04][pts=1][hidden][sec=9]") {
  // Soups until ten pairs hit in both methods, so that every seed checks as much as any other
  // (one soup of a few seeds has no pair that meets within the step)
  const double h = 0.5, tol = 1e-6;
  int both_hit = 0;
  for (int attempt = 0; attempt < 100 && both_hit < 10; ++attempt) {
    const std::vector<CollisionBody> soup = shapeSoup(12, 3.0, static_cast<std::uint64_t>(uniform(0, 1e9)));
    for (std::size_t i = 0; i < soup.size(); ++i) {
      for (std::size_t j = i + 1; j < soup.size(); ++j) {
        const CollisionBody &A = soup[i], &B = soup[j];
        const ToiResult bis = toiBisection(A.shape, A.pose, A.motion, B.shape, B.pose, B.motion, h, tol);
        const ToiResult ca = toiConservativeAdvancement(A.shape, A.pose, A.motion, B.shape, B.pose, B.motion, h, tol);
        INFO(pairName(A.shape, B.shape) << " (" << i << ", " << j << ")");
        // Bisection samples the step only as finely as its thin-shape bound: both see the same hits
        // except for grazing contacts, which neither must report later than the other's time.
        if (bis.hit && ca.hit) {
          ++both_hit;
          const DistanceResult at_bis = distance(A.shape, advance(A.pose, A.motion, bis.time), B.shape,
                                                 advance(B.pose, B.motion, bis.time));
          const DistanceResult at_ca = distance(A.shape, advance(A.pose, A.motion, ca.time), B.shape,
                                                advance(B.pose, B.motion, ca.time));
          // Each reports a time when the pair is apart by at most the tolerance (GJK's 1e-7 slack).
          CHECK(at_bis.distance <= tol + 1e-7);
          CHECK(at_ca.distance <= tol + 1e-7);
          // They agree, except where the pair grazes within `tol` before it touches: conservative
          // advancement may stop at the graze (a gap within tolerance), bisection sees no overlap
          // there and goes on to the touch. Never the other way round.
          INFO("bisection " << bis.time << " s, advancement " << ca.time << " s");
          CHECK((std::abs(bis.time - ca.time) < 1e-3 || ca.time < bis.time));
        } else if (ca.hit != bis.hit) {
          // Only conservative advancement can see a touch between bisection's samples.
          CHECK(ca.hit);
        }
      }
    }
  }
  CHECK(both_hit >= 10);
}
