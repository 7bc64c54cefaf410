// Lab 5 graded tests of one impulse: the particle-plane response, the rigid impulse magnitude j
// against the lecture's closed form, and what applying it conserves, reverses and dissipates.
#include <cmath>
#include <limits>

#include "impulse_support.hpp"
#include "physlab/error.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

TEST_CASE("particle-plane: the normal velocity reverses and shrinks by epsilon, the tangential stays", "[lab05][pts=1][sec=1]") {
  const double m = uniform(0.1, 10.0), epsilon = uniform(0.0, 1.0);
  const Vec3 n = randomVec3(1.0).normalized();
  Vec3 v = randomVec3(5.0);
  if (v.dot(n) > 0) v = -v;
  const Vec3 v_plus = particlePlaneResponse(m, v, n, epsilon);
  // What a failure needs to name its bug: the inputs, and v+ = v - (1 + epsilon)(v . n) n
  CAPTURE(m, epsilon);
  INFO("n = " << n.transpose() << ", v- = " << v.transpose());
  INFO("expected v+ = " << (v - (1.0 + epsilon) * v.dot(n) * n).transpose() << ", yours " << v_plus.transpose());
  // One multiply-add per component: round-off relative to |v|.
  CHECK(std::abs(v_plus.dot(n) + epsilon * v.dot(n)) <= 1e-12 * v.norm());
  CHECK((v_plus - v_plus.dot(n) * n - (v - v.dot(n) * n)).norm() <= 1e-12 * v.norm());
  // A particle leaving the plane is left alone: exactly.
  CHECK(particlePlaneResponse(m, -v, n, epsilon) == -v);
  // Both ends of epsilon's range [0, 1]: a dead stop along n and a perfect bounce (round-off as above)
  CHECK(std::abs(particlePlaneResponse(m, v, n, 0.0).dot(n)) <= 1e-12 * v.norm());
  CHECK(std::abs(particlePlaneResponse(m, v, n, 1.0).dot(n) + v.dot(n)) <= 1e-12 * v.norm());
  // Grazing, v . n = 0 exactly (in the plane z = 0 with n = z): not an approach, left alone exactly
  const Vec3 grazing(v.x(), v.y(), 0.0);
  CHECK(particlePlaneResponse(m, grazing, Vec3::UnitZ(), epsilon) == grazing);
}

TEST_CASE("rigid impulse: the world inverse inertia is R I_body^-1 R^T", "[lab05][pts=1][sec=2]") {
  const Mat3 I_body = randomInertiaTensor();
  const Quat q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));  // not unit length
  const Mat3 R = q.normalized().toRotationMatrix();
  // Two 3x3 products evaluated in another order: round-off only.
  CHECK(inverseInertiaWorld(I_body.inverse(), q).isApprox(R * I_body.inverse() * R.transpose(), 1e-12));
  // By hand, on every run: diag(1, 3, 5) turned by 45 degrees about z (q of length 2) is
  // [[2, -1, 0], [-1, 2, 0], [0, 0, 5]]; R^T I^-1 R would flip the off-diagonal sign.
  const double half = std::acos(-1.0) / 8.0;
  const Quat q45(2.0 * std::cos(half), 0.0, 0.0, 2.0 * std::sin(half));
  Mat3 expected;
  expected << 2.0, -1.0, 0.0, -1.0, 2.0, 0.0, 0.0, 0.0, 5.0;
  // A rotation matrix from cos and sin of 45 degrees: round-off of the unit entries only.
  CHECK((inverseInertiaWorld(Vec3(1.0, 3.0, 5.0).asDiagonal(), q45) - expected).norm() <= 1e-14);
}

TEST_CASE("rigid impulse: j equals the lecture's closed form", "[lab05][pts=2][sec=2]") {
  const RandomPair s = randomPair();
  const double epsilon = uniform(0.0, 1.0);
  const Vec3 r_a = s.p - s.A.x, r_b = s.p - s.B.x, n = s.n;
  const double denominator = 1.0 / s.m_a + 1.0 / s.m_b + n.dot((s.A.I_inv_world * r_a.cross(n)).cross(r_a)) +
                             n.dot((s.B.I_inv_world * r_b.cross(n)).cross(r_b));
  const double j = -(1.0 + epsilon) * vRel(s) / denominator;
  // The same formula evaluated in another order: round-off only.
  CHECK(impulseMagnitude(s.A, s.B, s.p, s.n, epsilon) == Approx(j).epsilon(1e-10));
  CHECK(inverseEffectiveMass(s.A, s.B, s.p, s.n) == Approx(denominator).epsilon(1e-12));
  // Separating points (every velocity reversed): the same formula, now negative; world.hpp leaves
  // the decision to apply it to the caller, so j is not clamped to zero
  RandomPair leaving = s;
  leaving.A.v = -s.A.v;
  leaving.A.omega = -s.A.omega;
  leaving.B.v = -s.B.v;
  leaving.B.omega = -s.B.omega;
  REQUIRE(vRel(leaving) > 0.0);
  CHECK(impulseMagnitude(leaving.A, leaving.B, leaving.p, leaving.n, epsilon) == Approx(-j).epsilon(1e-10));  // round-off only
}

TEST_CASE("rigid impulse: linear and angular momentum of the pair are conserved", "[lab05][pts=2][sec=2][sec=3]") {
  RandomPair s = randomPair();
  const Vec3 P0 = linearMomentum(s), L0 = angularMomentum(s);
  const double j = impulseMagnitude(s.A, s.B, s.p, s.n, uniform(0.0, 1.0));
  applyImpulse(s.A, s.B, s.p, j * s.n);
  // An equal and opposite impulse at one point: momenta change by round-off only (scale: the
  // momenta themselves, at most ~50 kg m/s here).
  CHECK((linearMomentum(s) - P0).norm() <= 1e-12 * (1.0 + P0.norm() + j));
  CHECK((angularMomentum(s) - L0).norm() <= 1e-11 * (1.0 + L0.norm() + j));
}

TEST_CASE("rigid impulse: the relative normal velocity after is -epsilon times before", "[lab05][pts=2][sec=2][sec=3]") {
  RandomPair s = randomPair();
  const double epsilon = uniform(0.0, 1.0), before = vRel(s);
  applyImpulse(s.A, s.B, s.p, impulseMagnitude(s.A, s.B, s.p, s.n, epsilon) * s.n);
  // v_rel is linear in j: round-off relative to the speeds involved (~10 m/s).
  CHECK(vRel(s) == Approx(-epsilon * before).margin(1e-10 * (1.0 + std::abs(before))));
}

TEST_CASE("rigid impulse: kinetic energy never increases, and is conserved for epsilon = 1", "[lab05][pts=2][sec=2][sec=3]") {
  RandomPair s = randomPair();
  RandomPair elastic = s;
  const double E0 = kineticEnergy(s), epsilon = uniform(0.0, 1.0);
  applyImpulse(s.A, s.B, s.p, impulseMagnitude(s.A, s.B, s.p, s.n, epsilon) * s.n);
  // Energy lost is (1 - epsilon^2) j^2 K / 2 >= 0; allow round-off of the sums.
  CHECK(kineticEnergy(s) <= E0 * (1.0 + 1e-12));
  applyImpulse(elastic.A, elastic.B, elastic.p, impulseMagnitude(elastic.A, elastic.B, elastic.p, elastic.n, 1.0) * elastic.n);
  // Elastic and frictionless: exactly conserved up to round-off of the sums.
  CHECK(kineticEnergy(elastic) == Approx(E0).epsilon(1e-11));
}

TEST_CASE("rigid impulse: a fixed body takes no momentum and the other bounces with -epsilon v_n", "[lab05][pts=1][sec=2][sec=3]") {
  RandomPair s = randomPair(true);
  const double epsilon = uniform(0.0, 1.0), before = vRel(s);
  applyImpulse(s.A, s.B, s.p, impulseMagnitude(s.A, s.B, s.p, s.n, epsilon) * s.n);
  // Zero inverse mass and inertia: the fixed body does not move at all (exactly).
  CHECK(s.B.v == Vec3::Zero());
  CHECK(s.B.omega == Vec3::Zero());
  // v_rel is linear in j: round-off relative to the speeds involved.
  CHECK(vRel(s) == Approx(-epsilon * before).margin(1e-10 * (1.0 + std::abs(before))));
}

TEST_CASE("rigid impulse: a body pinned at its centre (inverse mass 0, inverse inertia not) is not fixed: it turns", "[lab05][pts=2][sec=2][sec=3]") {
  // Fixed means both inverses zero (world.hpp): a wheel on an axle through its centre has
  // m^-1 = 0 but turns. By hand: I^-1 = 2 1, spinning at omega = (0, 3, 0), touching the fixed
  // ground at p = (1, 0, 0) with n = z. r x n = (0, -1, 0), so K = n . (I^-1 (r x n)) x r = 2;
  // the point moves at omega x r = (0, 0, -3): v_rel = -3, j = -(1 + 1/2)(-3) / 2 = 2.25, and
  // J = 2.25 n turns it by I^-1 (r x J) = (0, -4.5, 0) to omega = (0, -1.5, 0): the point leaves
  // at +1.5 = -epsilon v_rel. Small integers and halves: every step is exact.
  ContactBody wheel, ground;
  wheel.I_inv_world = 2.0 * Mat3::Identity();
  wheel.omega = Vec3(0.0, 3.0, 0.0);
  const Vec3 p(1.0, 0.0, 0.0), n = Vec3::UnitZ();
  CHECK(inverseEffectiveMass(wheel, ground, p, n) == 2.0);
  CHECK(inverseEffectiveMass(ground, wheel, p, -n) == 2.0);  // as B, normal from the wheel to the ground
  // Along its lever arm a pinned body cannot give at all: K = 0 exactly (no mass term, r x d = 0)
  CHECK(inverseEffectiveMass(wheel, ground, p, Vec3::UnitX()) == 0.0);
  CHECK(impulseMagnitude(wheel, ground, p, n, 0.5) == 2.25);
  CHECK(impulseMagnitude(ground, wheel, p, -n, 0.5) == 2.25);
  for (const bool wheel_is_a : {true, false}) {
    CAPTURE(wheel_is_a);
    ContactBody w = wheel, g = ground;
    if (wheel_is_a) {
      applyImpulse(w, g, p, 2.25 * n);
    } else {
      applyImpulse(g, w, p, -2.25 * n);  // -J on B: +2.25 n on the wheel again
    }
    CHECK(w.omega == Vec3(0.0, -1.5, 0.0));
    CHECK(w.v == Vec3::Zero());  // pinned: its centre stays
    CHECK(g.v == Vec3::Zero());
    CHECK(g.omega == Vec3::Zero());
  }
  // The other end of the rule: a body that translates but cannot turn (I^-1 = 0, m^-1 = 1/2) is not
  // fixed either: K = 1/2 along any direction, and J = 1 moves it by 1/2 along J, without a turn.
  ContactBody slider;
  slider.inv_mass = 0.5;
  CHECK(inverseEffectiveMass(slider, ground, p, n) == 0.5);
  applyImpulse(slider, ground, p, n);
  CHECK(slider.v == Vec3(0.0, 0.0, 0.5));
  CHECK(slider.omega == Vec3::Zero());
  // Seeded: a pinned body with a random inertia and spin against a random moving body (as A and
  // as B): K is the formula's, the impulse leaves v_rel = -epsilon v_rel-, the pinned centre stays.
  RandomPair s = randomPair();
  s.A.v = Vec3::Zero();
  s.A.inv_mass = 0.0;
  if (vRel(s) > 0.0) {
    s.A.omega = -s.A.omega;
    s.B.v = -s.B.v;
    s.B.omega = -s.B.omega;
  }
  scaleToApproach(s, -uniform(0.3, 3.0));  // well clear of a graze
  const double epsilon = uniform(0.0, 1.0), before = vRel(s);
  INFO("v_rel- " << before << ", epsilon " << epsilon);
  // The same formula evaluated in another order: round-off only.
  CHECK(inverseEffectiveMass(s.A, s.B, s.p, s.n) == Approx(oracleK(s.A, s.B, s.p, s.n)).epsilon(1e-12));
  CHECK(inverseEffectiveMass(s.B, s.A, s.p, -s.n) == Approx(oracleK(s.A, s.B, s.p, s.n)).epsilon(1e-12));
  for (const bool pinned_is_a : {true, false}) {
    CAPTURE(pinned_is_a);
    RandomPair t = s;
    const double j = pinned_is_a ? impulseMagnitude(t.A, t.B, t.p, t.n, epsilon) : impulseMagnitude(t.B, t.A, t.p, -t.n, epsilon);
    if (pinned_is_a) {
      applyImpulse(t.A, t.B, t.p, j * t.n);
    } else {
      applyImpulse(t.B, t.A, t.p, -j * t.n);
    }
    CHECK(t.A.v == Vec3::Zero());
    // v_rel is linear in j: round-off relative to the speeds involved (~10 m/s).
    CHECK(vRel(t) == Approx(-epsilon * before).margin(1e-10 * (1.0 + std::abs(before))));
    CHECK((t.A.omega - s.A.omega).norm() > 0.0);  // it turned
  }
}

TEST_CASE("friction: below mu j the contact sticks, above it slides with |j_t| = mu j", "[lab05][pts=1][sec=4]") {
  // A sphere on the fixed ground: touching point below its centre
  const double m = uniform(0.5, 5.0), r = uniform(0.05, 0.5);
  ContactBody A, ground;
  A.x = Vec3(0.0, 0.0, r);
  A.v = Vec3(uniform(-3, 3), uniform(-3, 3), 0.0);
  A.omega = randomVec3(2.0);
  A.inv_mass = 1.0 / m;
  A.I_inv_world = Mat3::Identity() / (0.4 * m * r * r);
  const Vec3 p = Vec3::Zero(), n = Vec3::UnitZ();
  const Vec3 v = A.v + A.omega.cross(p - A.x), v_t = v - v.dot(n) * n;
  INFO("sphere of mass " << m << " and radius " << r << " on the fixed ground (n = z), slip v_t = " << v_t.transpose());
  // Sticking: a large bound lets the impulse stop the sliding
  ContactBody stuck = A, ground_copy = ground;
  const Vec3 J = frictionImpulse(stuck, ground_copy, p, n, 1e6);
  applyImpulse(stuck, ground_copy, p, J);
  const Vec3 after = stuck.v + stuck.omega.cross(p - stuck.x);
  // Isotropic inertia: the stopping impulse is exact, up to round-off of the speeds (~10 m/s).
  CHECK((after - after.dot(n) * n).norm() <= 1e-12 * (1.0 + v_t.norm()));
  CHECK(std::abs(J.dot(n)) <= 1e-12 * J.norm());  // in the tangent plane: round-off only
  // Sliding: a small bound caps the impulse at mu j, opposite the sliding velocity
  const double j_max = 0.1 * J.norm();
  const Vec3 J_slide = frictionImpulse(A, ground, p, n, j_max);
  // A vector scaled to a given length: round-off only.
  CHECK(J_slide.norm() == Approx(j_max).epsilon(1e-12));
  CHECK(J_slide.dot(v_t) == Approx(-j_max * v_t.norm()).epsilon(1e-12));
  // A bound of 0 (mu = 0 or j = 0) leaves no friction at all, sliding or not: exactly zero.
  CHECK(frictionImpulse(A, ground, p, n, 0.0) == Vec3::Zero());
  // Not sliding: falling straight down without spin, v_t = v - (v . n) n is exactly zero, so there is
  // no direction t; the contract's answer is exactly zero, whatever the bound.
  ContactBody falling = A;
  falling.v = Vec3(0.0, 0.0, uniform(-3.0, -0.1));
  falling.omega = Vec3::Zero();
  CHECK(frictionImpulse(falling, ground, p, n, 1e6) == Vec3::Zero());
  CHECK(frictionImpulse(falling, ground, p, n, std::numeric_limits<double>::infinity()) == Vec3::Zero());
}

TEST_CASE("friction: the impulse opposes the tangential slip, stopping it along t or of length j_max", "[lab05][pts=2][sec=4]") {
  // Two moving bodies with random inertias: K along t has every rotational term
  const RandomPair s = approachingPair();
  const Vec3 v = oracleRelativeVelocity(s.A, s.B, s.p), v_t = v - v.dot(s.n) * s.n;
  const Vec3 t = v_t.normalized();
  const double j_stop = v_t.norm() / oracleK(s.A, s.B, s.p, t);
  INFO("|v_t| = " << v_t.norm() << ", j_stop = " << j_stop);
  // Sticking: a bound above the stopping impulse keeps it, and the slip along t stops
  ContactBody A = s.A, B = s.B;
  const Vec3 J = frictionImpulse(A, B, s.p, s.n, j_stop * uniform(1.2, 3.0));
  // The same formula evaluated in another order: round-off relative to the impulse.
  CHECK((J + j_stop * t).norm() <= 1e-10 * j_stop);
  oracleApply(A, B, s.p, J);
  // Along t the slip is gone, up to round-off of the speeds involved (~10 m/s).
  CHECK(std::abs(t.dot(oracleRelativeVelocity(A, B, s.p))) <= 1e-10 * (1.0 + v.norm()));
  // Sliding: a bound below it is the length, still opposite the slip and in the tangent plane
  const double j_max = j_stop * uniform(0.1, 0.8);
  const Vec3 J_slide = frictionImpulse(s.A, s.B, s.p, s.n, j_max);
  CHECK((J_slide + j_max * t).norm() <= 1e-10 * j_max);  // round-off only
}

TEST_CASE("friction: it sticks up to |v_t| = K_t j_max and slides beyond, for K_t j_max below and above 1 m/s", "[lab05][pts=1][sec=4]") {
  // The rule compares the stopping impulse |v_t| / K_t with j_max, that is |v_t| with K_t j_max
  // (a speed with a speed): squaring one side moves the threshold to sqrt(K_t j_max), wrong on
  // both sides of 1 m/s. By hand: a point mass (m^-1 = 1/2, no inertia, p at its centre, so
  // K_t = 1/2) sliding along x on the fixed ground; quarters and halves: exact.
  ContactBody ground, puck;
  puck.inv_mass = 0.5;
  const Vec3 p = Vec3::Zero(), n = Vec3::UnitZ();
  const auto impulseAt = [&](double speed, double j_max) {
    ContactBody A = puck;
    A.v = Vec3(speed, 0.0, -1.0);  // approaching; the normal part plays no role
    return frictionImpulse(A, ground, p, n, j_max);
  };
  // K_t j_max = 1/4 m/s (j_max = 1/2): sticking up to 0.25 m/s, the threshold itself included
  CHECK(impulseAt(0.125, 0.5) == Vec3(-0.25, 0.0, 0.0));
  CHECK(impulseAt(0.25, 0.5) == Vec3(-0.5, 0.0, 0.0));
  CHECK(impulseAt(0.375, 0.5) == Vec3(-0.5, 0.0, 0.0));  // sliding, though 0.375^2 < 1/4
  CHECK(impulseAt(0.4375, 0.5) == Vec3(-0.5, 0.0, 0.0));
  CHECK(impulseAt(2.0, 0.5) == Vec3(-0.5, 0.0, 0.0));
  // K_t j_max = 4 m/s (j_max = 8): sticking up to 4 m/s, though 3^2 > 4
  CHECK(impulseAt(2.5, 8.0) == Vec3(-5.0, 0.0, 0.0));
  CHECK(impulseAt(3.75, 8.0) == Vec3(-7.5, 0.0, 0.0));
  CHECK(impulseAt(4.0, 8.0) == Vec3(-8.0, 0.0, 0.0));
  CHECK(impulseAt(4.25, 8.0) == Vec3(-8.0, 0.0, 0.0));
  // Seeded: a random pair of moving bodies, its velocities scaled to a slow slip (0.05 to 0.5 m/s)
  // with j_max 1 to 10 % below the stopping impulse, then to a fast one (2 to 10 m/s) with j_max
  // 1 to 10 % above it: sliding at j_max, then sticking at j_stop.
  for (const bool fast : {false, true}) {
    RandomPair s = approachingPair();
    const Vec3 v0 = oracleRelativeVelocity(s.A, s.B, s.p), v0_t = v0 - v0.dot(s.n) * s.n;
    const double speed = fast ? uniform(2.0, 10.0) : uniform(0.05, 0.5), scale = speed / v0_t.norm();
    s.A.v *= scale;
    s.A.omega *= scale;
    s.B.v *= scale;
    s.B.omega *= scale;
    const Vec3 v = oracleRelativeVelocity(s.A, s.B, s.p), v_t = v - v.dot(s.n) * s.n;
    const Vec3 t = v_t.normalized();
    const double j_stop = v_t.norm() / oracleK(s.A, s.B, s.p, t);
    const double j_max = j_stop * (fast ? uniform(1.01, 1.1) : uniform(0.9, 0.99));
    INFO("|v_t| = " << v_t.norm() << " m/s, j_stop = " << j_stop << ", j_max = " << j_max);
    const Vec3 J = frictionImpulse(s.A, s.B, s.p, s.n, j_max);
    // The same formula evaluated in another order: round-off relative to the impulse.
    CHECK((J + (fast ? j_stop : j_max) * t).norm() <= 1e-10 * j_stop);
  }
}

TEST_CASE("penalty: the force is max(0, k depth - d v_rel) along n, never pulling", "[lab05][pts=1][sec=7]") {
  const double k = std::pow(10.0, uniform(3.0, 5.0)), d = uniform(1.0, 100.0), depth = uniform(1e-4, 1e-2);
  const Vec3 n = randomVec3(1.0).normalized();
  const double spring = k * depth;
  // Approaching (v_rel < 0): the damper adds to the spring
  const double approaching = uniform(-2.0, -0.1);
  // One multiply-add and a scaling: round-off only.
  CHECK((penaltyForce(depth, approaching, n, k, d) - (spring - d * approaching) * n).norm() <= 1e-12 * (spring - d * approaching));
  // Separating slowly: the damper takes some of the spring away
  const double slow = uniform(0.1, 0.9) * spring / d;
  CHECK((penaltyForce(depth, slow, n, k, d) - (spring - d * slow) * n).norm() <= 1e-12 * spring);
  // Separating fast: the damper would pull, so there is no force at all (exactly)
  const double fast = uniform(1.1, 3.0) * spring / d;
  CHECK(penaltyForce(depth, fast, n, k, d) == Vec3::Zero());
  // Just touching, depth exactly 0: the damper alone pushes an approaching point (round-off of one
  // product) and nothing acts on a leaving one (exactly)
  CHECK((penaltyForce(0.0, approaching, n, k, d) + d * approaching * n).norm() <= 1e-12 * d * -approaching);
  CHECK(penaltyForce(0.0, slow, n, k, d) == Vec3::Zero());
  // No damper, d = 0 (Settings' default): the spring alone, whatever the velocity (round-off only)
  CHECK((penaltyForce(depth, approaching, n, k, 0.0) - spring * n).norm() <= 1e-12 * spring);
  CHECK((penaltyForce(depth, fast, n, k, 0.0) - spring * n).norm() <= 1e-12 * spring);
}

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Every field of a body, exactly (a NaN inverse mass equal to a NaN one): a refused call must
// leave it as it was.
bool sameBody(const ContactBody& X, const ContactBody& Y) {
  const bool same_inv_mass = X.inv_mass == Y.inv_mass || (std::isnan(X.inv_mass) && std::isnan(Y.inv_mass));
  return X.x == Y.x && X.v == Y.v && X.omega == Y.omega && same_inv_mass && X.I_inv_world == Y.I_inv_world;
}

}  // namespace

TEST_CASE("particle-plane: bad input is refused naming it; epsilon exactly 0 and 1 and a normal off by round-off are allowed", "[lab05][pts=1][sec=1]") {
  const double m = uniform(0.1, 10.0);
  const Vec3 n = randomVec3(1.0).normalized();
  Vec3 v = randomVec3(2.0);
  if (v.dot(n) > 0.0) v = -v;
  // The ends of [0, 1] and a normal whose length is 1 up to round-off (far inside 1e-9) are valid
  CAPTURE(m);
  INFO("n = " << n.transpose() << ", v- = " << v.transpose());
  CHECK_NOTHROW(particlePlaneResponse(m, v, n, 0.0));
  CHECK_NOTHROW(particlePlaneResponse(m, v, n, 1.0));
  const Vec3 stopped = particlePlaneResponse(m, v, n, 0.0);
  INFO("epsilon 0: expected v+ = " << (v - v.dot(n) * n).transpose() << ", yours " << stopped.transpose());
  CHECK(std::abs(stopped.dot(n)) <= 1e-12 * v.norm());  // v - (v . n) n: round-off only
  CHECK(particlePlaneResponse(m, v, n, 1.0).dot(n) == Approx(-v.dot(n)).epsilon(1e-12));
  CHECK_NOTHROW(particlePlaneResponse(m, v, Vec3(n * (1.0 + 1e-12)), 0.5));
  // epsilon above 1 would gain energy; below 0 or NaN it is no restitution at all
  for (const double epsilon : {1.0 + 1e-9, 1.5, -1e-9, -0.1, kNan}) {
    INFO("epsilon " << epsilon);
    CHECK_THROWS_AS(particlePlaneResponse(m, v, n, epsilon), InvalidInput);
    CHECK_THROWS_WITH(particlePlaneResponse(m, v, n, epsilon), Contains("epsilon"));
  }
  for (const double bad : {0.0, -m, kNan, kInf}) {
    INFO("m " << bad);
    CHECK_THROWS_AS(particlePlaneResponse(bad, v, n, 0.5), InvalidInput);
    CHECK_THROWS_WITH(particlePlaneResponse(bad, v, n, 0.5), Contains("mass m"));
  }
  // A normal that is not unit scales the impulse; a NaN one gives a NaN velocity
  for (const Vec3& bad : {Vec3(2.0 * n), Vec3(n * (1.0 + 1e-8)), Vec3(Vec3::Zero()), Vec3(kNan, 0.0, 1.0)}) {
    INFO("n " << bad.transpose());
    CHECK_THROWS_AS(particlePlaneResponse(m, v, bad, 0.5), InvalidInput);
    CHECK_THROWS_WITH(particlePlaneResponse(m, v, bad, 0.5), Contains("normal n"));
  }
  CHECK_THROWS_WITH(particlePlaneResponse(m, Vec3(0.0, kInf, -1.0), n, 0.5), Contains("v_minus"));
}

TEST_CASE("rigid impulse: bad input to the impulse functions is refused naming it, and applyImpulse then changes neither body", "[lab05][pts=2][sec=2]") {
  const RandomPair s = randomPair(), fixed = randomPair(true);
  // Valid: the ends of epsilon, a fixed B (inverse mass exactly 0), a normal off by round-off
  const double j = impulseMagnitude(s.A, s.B, s.p, s.n, 0.0);
  CHECK(j > 0.0);
  CHECK(impulseMagnitude(s.A, s.B, s.p, s.n, 1.0) == Approx(2.0 * j).epsilon(1e-12));
  CHECK_NOTHROW(impulseMagnitude(fixed.A, fixed.B, fixed.p, Vec3(fixed.n * (1.0 - 1e-12)), 0.5));
  CHECK_NOTHROW(inverseEffectiveMass(fixed.A, fixed.B, fixed.p, Vec3(fixed.n * (1.0 + 1e-12))));
  // impulseMagnitude: epsilon outside [0, 1] or NaN, a normal that is not unit
  for (const double epsilon : {1.5, 1.0 + 1e-9, -1e-9, kNan}) {
    INFO("epsilon " << epsilon);
    CHECK_THROWS_AS(impulseMagnitude(s.A, s.B, s.p, s.n, epsilon), InvalidInput);
    CHECK_THROWS_WITH(impulseMagnitude(s.A, s.B, s.p, s.n, epsilon), Contains("epsilon"));
  }
  for (const Vec3& bad : {Vec3(1.5 * s.n), Vec3(s.n * (1.0 - 1e-8)), Vec3(Vec3::Zero()), Vec3(kNan, 0.0, 1.0)}) {
    INFO("n " << bad.transpose());
    CHECK_THROWS_WITH(impulseMagnitude(s.A, s.B, s.p, bad, 0.5), Contains("normal n"));
    CHECK_THROWS_WITH(inverseEffectiveMass(s.A, s.B, s.p, bad), Contains("direction d"));
  }
  // Negative or non-finite inverse masses, in A or in B
  for (const double bad : {-uniform(0.1, 1.0), kNan, kInf}) {
    INFO("inverse mass " << bad);
    RandomPair t = s;
    t.A.inv_mass = bad;
    CHECK_THROWS_AS(inverseEffectiveMass(t.A, t.B, t.p, t.n), InvalidInput);
    CHECK_THROWS_WITH(inverseEffectiveMass(t.A, t.B, t.p, t.n), Contains("body A inverse mass"));
    CHECK_THROWS_AS(impulseMagnitude(t.A, t.B, t.p, t.n, 0.5), InvalidInput);
    ContactBody A = t.A, B = t.B;
    CHECK_THROWS_WITH(applyImpulse(A, B, t.p, j * t.n), Contains("body A inverse mass"));
    CHECK(sameBody(A, t.A));
    CHECK(sameBody(B, t.B));
    t = s;
    t.B.inv_mass = bad;
    CHECK_THROWS_WITH(inverseEffectiveMass(t.A, t.B, t.p, t.n), Contains("body B inverse mass"));
    A = t.A;
    B = t.B;
    // Checked before anything changes: A untouched although only B is bad
    CHECK_THROWS_WITH(applyImpulse(A, B, t.p, j * t.n), Contains("body B inverse mass"));
    CHECK(sameBody(A, t.A));
    CHECK(sameBody(B, t.B));
  }
  // Points and impulses that are not finite
  const Vec3 bad_point(s.p.x(), kNan, s.p.z());
  CHECK_THROWS_WITH(relativeVelocity(s.A, s.B, bad_point), Contains("point p"));
  ContactBody A = s.A, B = s.B;
  CHECK_THROWS_WITH(applyImpulse(A, B, bad_point, j * s.n), Contains("point p"));
  CHECK_THROWS_WITH(applyImpulse(A, B, s.p, Vec3(0.0, 0.0, kInf)), Contains("impulse J"));
  CHECK(sameBody(A, s.A));
  CHECK(sameBody(B, s.B));
  // inverseInertiaWorld: any non-zero q is normalised, a zero or NaN one is no orientation
  const Mat3 I_inv = randomInertiaTensor().inverse();
  CHECK_NOTHROW(inverseInertiaWorld(I_inv, Quat(uniform(0.1, 3.0), 0.0, 0.0, 0.0)));
  CHECK_THROWS_WITH(inverseInertiaWorld(I_inv, Quat(0.0, 0.0, 0.0, 0.0)), Contains("orientation q"));
  CHECK_THROWS_WITH(inverseInertiaWorld(I_inv, Quat(kNan, 0.0, 0.0, 1.0)), Contains("orientation q"));
  Mat3 bad_inertia = I_inv;
  bad_inertia(1, 2) = kNan;
  CHECK_THROWS_WITH(inverseInertiaWorld(bad_inertia, Quat::Identity()), Contains("I_body_inv"));
}

TEST_CASE("friction: a normal that is not unit and a negative or NaN j_max are refused; j_max = 0 and +infinity are allowed", "[lab05][pts=1][sec=4]") {
  const RandomPair s = randomPair();
  INFO("n = " << s.n.transpose() << ", p = " << s.p.transpose());
  // +infinity is "no bound" (the solvers pass it), 0 is "no friction": both valid
  CHECK_NOTHROW(frictionImpulse(s.A, s.B, s.p, s.n, kInf));
  CHECK_NOTHROW(frictionImpulse(s.A, s.B, s.p, s.n, 0.0));
  const Vec3 unbounded = frictionImpulse(s.A, s.B, s.p, s.n, kInf);
  CHECK(std::isfinite(unbounded.norm()));
  CHECK(frictionImpulse(s.A, s.B, s.p, s.n, 0.0) == Vec3::Zero());
  CHECK_NOTHROW(frictionImpulse(s.A, s.B, s.p, Vec3(s.n * (1.0 + 1e-12)), 1.0));
  for (const double bad : {-1e-12, -uniform(0.1, 1.0), -kInf, kNan}) {
    INFO("j_max " << bad);
    CHECK_THROWS_AS(frictionImpulse(s.A, s.B, s.p, s.n, bad), InvalidInput);
    CHECK_THROWS_WITH(frictionImpulse(s.A, s.B, s.p, s.n, bad), Contains("j_max"));
  }
  for (const Vec3& bad : {Vec3(1.1 * s.n), Vec3(s.n * (1.0 + 1e-8)), Vec3(kNan, kNan, kNan)}) {
    INFO("n " << bad.transpose());
    CHECK_THROWS_AS(frictionImpulse(s.A, s.B, s.p, bad, 1.0), InvalidInput);
    CHECK_THROWS_WITH(frictionImpulse(s.A, s.B, s.p, bad, 1.0), Contains("normal n"));
  }
}

TEST_CASE("penalty: a negative depth, stiffness or damping, a NaN velocity and a normal that is not unit are refused", "[lab05][pts=1][sec=7]") {
  const double k = std::pow(10.0, uniform(3.0, 5.0)), d = uniform(1.0, 100.0), depth = uniform(1e-4, 1e-2);
  const Vec3 n = randomVec3(1.0).normalized();
  // The ends: just touching (depth 0), no damper (d = 0), a normal off by round-off
  CHECK(penaltyForce(0.0, 0.0, n, k, 0.0) == Vec3::Zero());
  CHECK_NOTHROW(penaltyForce(depth, -1.0, Vec3(n * (1.0 + 1e-12)), k, d));
  for (const double bad : {-1e-12, -depth, kNan, kInf}) {
    INFO("depth " << bad);
    CHECK_THROWS_AS(penaltyForce(bad, -1.0, n, k, d), InvalidInput);
    CHECK_THROWS_WITH(penaltyForce(bad, -1.0, n, k, d), Contains("depth"));
  }
  CHECK_THROWS_WITH(penaltyForce(depth, kNan, n, k, d), Contains("v_rel"));
  CHECK_THROWS_WITH(penaltyForce(depth, -1.0, Vec3(2.0 * n), k, d), Contains("normal n"));
  CHECK_THROWS_WITH(penaltyForce(depth, -1.0, Vec3(kNan, 0.0, 1.0), k, d), Contains("normal n"));
  for (const double bad : {0.0, -k, kNan, kInf}) {
    INFO("k " << bad);
    CHECK_THROWS_WITH(penaltyForce(depth, -1.0, n, bad, d), Contains("stiffness k"));
  }
  for (const double bad : {-1e-12, -d, kNan, kInf}) {
    INFO("d " << bad);
    CHECK_THROWS_WITH(penaltyForce(depth, -1.0, n, k, bad), Contains("damping d"));
  }
}
