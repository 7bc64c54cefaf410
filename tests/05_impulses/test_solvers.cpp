// Lab 5 graded tests of the many-contact solvers on a box hitting the ground on up to four
// points (Lab 4's reference narrow phase makes the manifold): what each solver guarantees; one
// sweep on one random two-body point and the first sweeps on a box against oracles written here
// from world.hpp; the restitution threshold; and the bookkeeping of accumulated impulses.
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "impulse_support.hpp"
#include "physlab/error.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

namespace {

// A box tilted by up to `tilt` [rad] about x and y, a millimetre into the ground, moving down
// with random velocities (a tilt of 5e-4 keeps all four corners in the ground).
struct BoxOnGround {
  std::vector<ContactBody> bodies;  // box, ground
  std::vector<Contact> contacts;
  double m = 1.0;
  Mat3 I = Mat3::Identity();  // world inertia
};

BoxOnGround boxOnGround(double epsilon, double mu, double tilt = 0.05) {
  BoxOnGround s;
  const Vec3 half(uniform(0.1, 0.5), uniform(0.1, 0.5), uniform(0.1, 0.5));
  s.m = uniform(0.5, 5.0);
  Pose pose;
  pose.q = Quat(Eigen::AngleAxisd(uniform(-tilt, tilt), Vec3::UnitX()) * Eigen::AngleAxisd(uniform(-tilt, tilt), Vec3::UnitY()));
  pose.x = Vec3(0.0, 0.0, half.z() - 1e-3);
  const Mat3 R = pose.q.toRotationMatrix();
  const Mat3 I_body = Vec3(half.y() * half.y() + half.z() * half.z(), half.x() * half.x() + half.z() * half.z(),
                           half.x() * half.x() + half.y() * half.y()).asDiagonal() * (s.m / 3.0);
  s.I = R * I_body * R.transpose();
  ContactBody box, ground;
  box.x = pose.x;
  box.v = Vec3(uniform(-2, 2), uniform(-2, 2), uniform(-3, -1));
  box.omega = randomVec3(1.0);
  box.inv_mass = 1.0 / s.m;
  box.I_inv_world = s.I.inverse();
  s.bodies = {box, ground};
  const Manifold manifold = collide(Box(half), pose, Plane(Vec3::UnitZ(), 0.0), Pose{});
  for (int k = 0; k < manifold.count; ++k) {
    Contact c;
    c.a = 0;
    c.b = 1;
    c.p = manifold.points[k].position;
    c.n = manifold.normal;
    c.depth = manifold.points[k].depth;
    c.id = manifold.points[k].id;
    c.epsilon = epsilon;
    c.mu = mu;
    c.v_rel_minus = c.n.dot(box.v + box.omega.cross(c.p - box.x));
    c.kind = c.v_rel_minus < 0 ? ContactKind::Colliding : ContactKind::Separating;
    s.contacts.push_back(c);
  }
  return s;
}

double kinetic(const BoxOnGround& s) {
  const ContactBody& box = s.bodies[0];
  return 0.5 * (s.m * box.v.squaredNorm() + box.omega.dot(s.I * box.omega));
}

double vRelAt(const BoxOnGround& s, const Contact& c) {
  const ContactBody& box = s.bodies[0];
  return c.n.dot(box.v + box.omega.cross(c.p - box.x));
}

}  // namespace

TEST_CASE("sequential impulses: frictionless, afterwards no point approaches and no energy is gained", "[lab05][pts=1][sec=5]") {
  const double epsilon = uniform(0.0, 1.0);
  BoxOnGround s = boxOnGround(epsilon, 0.0);
  REQUIRE(s.contacts.size() >= 1);
  Settings settings;
  settings.iterations = 10000;
  const double E0 = kinetic(s);
  const int sweeps = solveSequential(s.bodies, s.contacts, settings);
  INFO("epsilon " << epsilon << ", " << s.contacts.size() << " points, " << sweeps << " sweeps");
  CHECK(sweeps < settings.iterations);
  for (const Contact& c : s.contacts) {
    // Each point ends its last (quiet) sweep at its target >= 0 or with j = 0 and v_rel above it;
    // the other three points then change its velocity by at most the tolerance each: 4e-9 m/s.
    CHECK(vRelAt(s, c) >= -4.0 * settings.tolerance);
    CHECK(c.j >= 0.0);
  }
  // Every impulse with epsilon <= 1 removes energy; round-off of the sums.
  CHECK(kinetic(s) <= E0 * (1.0 + 1e-12));
  CHECK(s.bodies[1].v == Vec3::Zero());  // the ground stays put: zero inverses (exactly)
}

TEST_CASE("sequential impulses: with friction, impulses stay in the cone and remove energy", "[lab05][pts=1][sec=5]") {
  // Plastic (epsilon = 0): each normal update moves a point's v_n towards 0 and so takes energy
  // out. With epsilon > 0 a point pushed to -epsilon v- after its neighbours' impulses already
  // turned it round gains energy: sequential restitution is not dissipative (seeds found it).
  const double epsilon = 0.0, mu = uniform(0.1, 1.0);
  BoxOnGround s = boxOnGround(epsilon, mu);
  REQUIRE(s.contacts.size() >= 1);
  Settings settings;
  settings.iterations = static_cast<int>(uniform(1, 60));  // clamped after any number of sweeps
  const double E0 = kinetic(s);
  INFO("a box sliding on the ground: " << s.contacts.size() << " contacts, epsilon 0, mu " << mu << ", "
       << settings.iterations << " sweeps, kinetic energy before " << E0 << " J");
  solveSequential(s.bodies, s.contacts, settings);
  bool any_friction = false;
  for (const Contact& c : s.contacts) {
    CHECK(c.j >= 0.0);
    // Clamped to the cone: the length is scaled to mu j, round-off only.
    CHECK(c.j_t.norm() <= c.mu * c.j * (1.0 + 1e-12));
    CHECK(std::abs(c.j_t.dot(c.n)) <= 1e-12 * (1.0 + c.j_t.norm()));  // in the tangent plane
    any_friction = any_friction || c.j_t.norm() > 0.0;
  }
  CHECK(any_friction);  // the box slides at up to 2 m/s: friction must act somewhere
  // Plastic impulses and friction opposing the sliding remove energy; round-off.
  CHECK(kinetic(s) <= E0 * (1.0 + 1e-12));
}

TEST_CASE("simultaneous impulses: frictionless, they converge to v_rel >= 0 and warm starting reaches the same answer", "[lab05][pts=1][sec=6]") {
  BoxOnGround s = boxOnGround(0.0, 0.0);
  REQUIRE(s.contacts.size() >= 1);
  Settings settings;
  settings.method = ResponseMethod::Simultaneous;
  settings.iterations = 100000;
  settings.tolerance = 1e-10;
  BoxOnGround warm = s;
  const int sweeps = solveSimultaneous(s.bodies, s.contacts, settings);
  INFO(s.contacts.size() << " points, " << sweeps << " sweeps");
  CHECK(sweeps < settings.iterations);
  for (const Contact& c : s.contacts) {
    // epsilon = 0: every point ends at v_rel >= 0 (the tolerance is on velocity changes; Jacobi
    // converges linearly, so what is left is a small multiple of it).
    CHECK(vRelAt(s, c) >= -1e-8);
    CHECK(c.j >= 0.0);
  }
  // Start again from the answer's impulses: the warm start alone nearly solves it
  for (std::size_t k = 0; k < s.contacts.size(); ++k) warm.contacts[k].j = s.contacts[k].j;
  const int warm_sweeps = solveSimultaneous(warm.bodies, warm.contacts, settings);
  CHECK(warm_sweeps <= 2);
  // The same final velocities: both stop within the tolerance of the same fixed point (a box
  // on up to 4 points is well conditioned: a margin of 1e-6 m/s).
  CHECK((warm.bodies[0].v - s.bodies[0].v).norm() <= 1e-6);
}

TEST_CASE("simultaneous impulses: accumulated impulses stay clamped, j >= 0 and |j_t| <= mu j", "[lab05][pts=1][sec=6]") {
  const double mu = uniform(0.1, 1.0);
  BoxOnGround s = boxOnGround(uniform(0.0, 1.0), mu);
  REQUIRE(s.contacts.size() >= 1);
  Settings settings;
  settings.method = ResponseMethod::Simultaneous;
  settings.iterations = static_cast<int>(uniform(1, 60));  // clamped after any number of sweeps
  solveSimultaneous(s.bodies, s.contacts, settings);
  bool any_friction = false;
  for (const Contact& c : s.contacts) {
    CHECK(c.j >= 0.0);
    // Clamped to the cone: the length is scaled to mu j, round-off only.
    CHECK(c.j_t.norm() <= c.mu * c.j * (1.0 + 1e-12));
    CHECK(std::abs(c.j_t.dot(c.n)) <= 1e-12 * (1.0 + c.j_t.norm()));  // in the tangent plane
    any_friction = any_friction || c.j_t.norm() > 0.0;
  }
  CHECK(any_friction);  // the box slides at up to 2 m/s: friction must act somewhere
}

namespace {

// One contact between the two moving bodies of a random pair, as classify leaves it.
Contact oneContact(const RandomPair& s, double epsilon, double mu) {
  Contact c;
  c.a = 0;
  c.b = 1;
  c.p = s.p;
  c.n = s.n;
  c.epsilon = epsilon;
  c.mu = mu;
  c.v_rel_minus = vRel(s);
  c.kind = ContactKind::Colliding;
  return c;
}

// Changes of momentum of the box since `box0`, against the accumulated impulses of the
// contacts: m dv = sum (j n + j_t), I domega = sum r x (j n + j_t).
void checkImpulseBalance(const ContactBody& box0, const ContactBody& box, double m, const Mat3& I,
                         const std::vector<Contact>& contacts) {
  Vec3 P = Vec3::Zero(), L = Vec3::Zero();
  double size = 0.0;
  for (const Contact& c : contacts) {
    const Vec3 J = c.j * c.n + c.j_t;
    P += J;
    L += (c.p - box.x).cross(J);
    size += J.norm();
  }
  INFO("sum of impulses " << P.transpose() << ", their moment " << L.transpose());
  // Sums of a few hundred impulses at most: round-off relative to their total size.
  CHECK((m * (box.v - box0.v) - P).norm() <= 1e-10 * (1.0 + size));
  CHECK((I * (box.omega - box0.omega) - L).norm() <= 1e-10 * (1.0 + size));
}

}  // namespace

namespace {

// One sweep of `method` on one approaching point against a hand oracle: the warm start (when
// `warm`), the correction towards -epsilon v_rel-, then friction clamped to mu times the j just
// found, with mu set so that the bound is `fraction` of the impulse that would stop the sliding
// (below 1 sliding, above sticking). One point is the same for Gauss-Seidel and Jacobi.
void checkOneSweepOnOnePoint(ResponseMethod method, double fraction, bool warm) {
  const RandomPair s = approachingPair();
  const double epsilon = uniform(0.1, 1.0);
  Contact c = oneContact(s, epsilon, 0.0);
  // Warm: impulses carried over from the last step, a part of the answer (so friction clamped
  // with them instead of the j just found would be bounded too tightly)
  ContactBody A = s.A, B = s.B;
  const double K = oracleK(A, B, s.p, s.n);
  const double j0 = warm ? uniform(0.2, 0.8) * -(1.0 + epsilon) * c.v_rel_minus / K : 0.0;
  const Vec3 j_t0 = uniform(0.05, 0.2) * j0 * s.n.cross(randomVec3(1.0)).normalized();
  // The oracle: the warm start, then the target -epsilon v_rel- reached from there
  oracleApply(A, B, s.p, j0 * s.n + j_t0);
  const double v_rel = s.n.dot(oracleRelativeVelocity(A, B, s.p));
  const double j = std::max(0.0, j0 + (-epsilon * c.v_rel_minus - v_rel) / K);
  // Friction sees this point's normal correction
  oracleApply(A, B, s.p, (j - j0) * s.n);
  const Vec3 j_t_free = j_t0 + oracleFriction(A, B, s.p, s.n, std::numeric_limits<double>::infinity());
  c.mu = fraction * j_t_free.norm() / j;
  const Vec3 j_t = oracleClamp(j_t_free, c.mu * j);
  oracleApply(A, B, s.p, j_t - j_t0);
  // The solver, allowed one sweep
  c.j = j0;
  c.j_t = j_t0;
  std::vector<ContactBody> bodies = {s.A, s.B};
  std::vector<Contact> contacts = {c};
  Settings settings;
  settings.method = method;
  settings.iterations = 1;
  INFO(responseMethodName(method) << ", " << (warm ? "warm" : "cold") << ", fraction of the stopping impulse "
                                  << fraction << ", v_rel " << c.v_rel_minus << ", j " << j);
  const int sweeps = method == ResponseMethod::Sequential ? solveSequential(bodies, contacts, settings)
                                                           : solveSimultaneous(bodies, contacts, settings);
  CHECK(sweeps == 1);
  // The same formulas evaluated in another order: round-off relative to the impulses
  // (~10 N s) and the speeds (~10 m/s).
  CHECK(contacts[0].j == Approx(j).epsilon(1e-10));
  CHECK((contacts[0].j_t - j_t).norm() <= 1e-10 * j);
  CHECK(velocityDistance(bodies[0], A) <= 1e-10 * (1.0 + j));
  CHECK(velocityDistance(bodies[1], B) <= 1e-10 * (1.0 + j));
}

}  // namespace

TEST_CASE("sequential impulses: one sweep on one point is its warm start, its correction, then friction clamped to mu j", "[lab05][pts=2][sec=5]") {
  // Sliding (the bound is part of the stopping impulse) and sticking (it is more), cold and warm
  for (const double fraction : {uniform(0.2, 0.8), uniform(1.2, 3.0)}) {
    for (const bool warm : {false, true}) checkOneSweepOnOnePoint(ResponseMethod::Sequential, fraction, warm);
  }
}

TEST_CASE("sequential impulses: a point approaching slower than the restitution threshold does not bounce", "[lab05][pts=1][sec=5]") {
  Settings settings;
  const double epsilon = uniform(0.5, 1.0);
  // Slower than the threshold: epsilon = 0, the point ends at v_rel = 0
  RandomPair slow = approachingPair();
  scaleToApproach(slow, -uniform(0.2, 0.8) * settings.restitution_threshold);
  std::vector<ContactBody> bodies = {slow.A, slow.B};
  std::vector<Contact> contacts = {oneContact(slow, epsilon, 0.0)};
  solveSequential(bodies, contacts, settings);
  slow.A = bodies[0];
  slow.B = bodies[1];
  // v_rel is linear in j: round-off relative to the speeds (~0.1 m/s).
  CHECK(std::abs(vRel(slow)) <= 1e-12);
  // Faster than the threshold: it bounces with -epsilon v_rel
  RandomPair fast = approachingPair();
  const double before = -uniform(2.0, 20.0) * settings.restitution_threshold;
  scaleToApproach(fast, before);
  bodies = {fast.A, fast.B};
  contacts = {oneContact(fast, epsilon, 0.0)};
  solveSequential(bodies, contacts, settings);
  fast.A = bodies[0];
  fast.B = bodies[1];
  CHECK(vRel(fast) == Approx(-epsilon * before).epsilon(1e-10));  // round-off only
}

TEST_CASE("sequential impulses: the warm start and the accumulated j, j_t account for every change of momentum", "[lab05][pts=1][sec=5]") {
  const double mu = uniform(0.1, 1.0);
  BoxOnGround s = boxOnGround(uniform(0.0, 1.0), mu);
  REQUIRE(s.contacts.size() >= 1);
  // Impulses carried over from the last step, inside the cone: applied first, then accumulated
  for (Contact& c : s.contacts) {
    c.j = uniform(0.0, 0.5) * s.m;
    c.j_t = uniform(0.0, 1.0) * mu * c.j * c.n.cross(randomVec3(1.0)).normalized();
  }
  const BoxOnGround start = s;
  const int iterations = static_cast<int>(uniform(1, 60));  // (friction may keep it sweeping)
  // The solver applies the impulses the contacts arrive with whatever Settings::warm_start says
  // (world.hpp: the World, not the solver, clears them when it is off): the same answer both ways
  for (const bool warm_start : {true, false}) {
    s = start;
    Settings settings;
    settings.iterations = iterations;
    settings.warm_start = warm_start;
    const int sweeps = solveSequential(s.bodies, s.contacts, settings);
    INFO(s.contacts.size() << " points, " << sweeps << " sweeps, warm_start " << warm_start);
    CHECK(sweeps >= 1);
    CHECK(sweeps <= settings.iterations);
    // Random warm impulses are not the answer: the sweeps changed them (a solver applying only the
    // warm start would balance trivially)
    double changed = 0.0;
    for (std::size_t k = 0; k < start.contacts.size(); ++k) changed += std::abs(s.contacts[k].j - start.contacts[k].j);
    CHECK(changed > 0.0);
    checkImpulseBalance(start.bodies[0], s.bodies[0], s.m, s.I, s.contacts);
  }
}

TEST_CASE("simultaneous impulses: one sweep on one point is its warm start, its correction, then its friction", "[lab05][pts=2][sec=6]") {
  // Sliding and sticking, cold and warm, as in the sequential test
  for (const double fraction : {uniform(0.2, 0.8), uniform(1.2, 3.0)}) {
    for (const bool warm : {false, true}) checkOneSweepOnOnePoint(ResponseMethod::Simultaneous, fraction, warm);
  }
}

TEST_CASE("simultaneous impulses: a point approaching slower than the restitution threshold does not bounce", "[lab05][pts=1][sec=6]") {
  Settings settings;
  settings.method = ResponseMethod::Simultaneous;
  const double epsilon = uniform(0.5, 1.0);
  // Slower than the threshold: the target is v_rel = 0
  RandomPair slow = approachingPair();
  scaleToApproach(slow, -uniform(0.2, 0.8) * settings.restitution_threshold);
  std::vector<ContactBody> bodies = {slow.A, slow.B};
  std::vector<Contact> contacts = {oneContact(slow, epsilon, 0.0)};
  solveSimultaneous(bodies, contacts, settings);
  slow.A = bodies[0];
  slow.B = bodies[1];
  // One point, no friction: the first correction is exact, up to round-off of ~0.1 m/s.
  CHECK(std::abs(vRel(slow)) <= 1e-12);
  // Faster than the threshold: it bounces with -epsilon v_rel_minus
  RandomPair fast = approachingPair();
  const double before = -uniform(2.0, 20.0) * settings.restitution_threshold;
  scaleToApproach(fast, before);
  bodies = {fast.A, fast.B};
  contacts = {oneContact(fast, epsilon, 0.0)};
  solveSimultaneous(bodies, contacts, settings);
  fast.A = bodies[0];
  fast.B = bodies[1];
  CHECK(vRel(fast) == Approx(-epsilon * before).epsilon(1e-10));  // round-off only
}

TEST_CASE("simultaneous impulses: the warm start and the accumulated j, j_t account for every change of momentum", "[lab05][pts=1][sec=6]") {
  const double mu = uniform(0.1, 1.0);
  BoxOnGround s = boxOnGround(uniform(0.0, 1.0), mu);
  REQUIRE(s.contacts.size() >= 1);
  // Impulses carried over from the last step, inside the cone: applied first, then accumulated
  for (Contact& c : s.contacts) {
    c.j = uniform(0.0, 0.5) * s.m;
    c.j_t = uniform(0.0, 1.0) * mu * c.j * c.n.cross(randomVec3(1.0)).normalized();
  }
  const BoxOnGround start = s;
  const int iterations = static_cast<int>(uniform(1, 60));  // (friction may keep it sweeping)
  // The solver applies the impulses the contacts arrive with whatever Settings::warm_start says
  // (world.hpp: the World, not the solver, clears them when it is off): the same answer both ways
  for (const bool warm_start : {true, false}) {
    s = start;
    Settings settings;
    settings.method = ResponseMethod::Simultaneous;
    settings.iterations = iterations;
    settings.warm_start = warm_start;
    const int sweeps = solveSimultaneous(s.bodies, s.contacts, settings);
    INFO(s.contacts.size() << " points, " << sweeps << " sweeps, warm_start " << warm_start);
    CHECK(sweeps >= 1);
    CHECK(sweeps <= settings.iterations);
    // Random warm impulses are not the answer: the sweeps changed them (a solver applying only the
    // warm start would balance trivially)
    double changed = 0.0;
    for (std::size_t k = 0; k < start.contacts.size(); ++k) changed += std::abs(s.contacts[k].j - start.contacts[k].j);
    CHECK(changed > 0.0);
    checkImpulseBalance(start.bodies[0], s.bodies[0], s.m, s.I, s.contacts);
  }
}

TEST_CASE("simultaneous impulses: frictionless, a point that keeps an impulse ends at v_rel = 0 (complementarity)", "[lab05][pts=1][sec=6]") {
  BoxOnGround s = boxOnGround(0.0, 0.0);
  REQUIRE(s.contacts.size() >= 1);
  Settings settings;
  settings.method = ResponseMethod::Simultaneous;
  settings.iterations = 100000;
  settings.tolerance = 1e-10;
  solveSimultaneous(s.bodies, s.contacts, settings);
  double total = 0.0;
  for (const Contact& c : s.contacts) total += c.j;
  for (const Contact& c : s.contacts) {
    INFO("j " << c.j << " of " << total << ", v_rel " << vRelAt(s, c));
    // Jacobi stops within a small multiple of the 1e-10 tolerance of the fixed point, where
    // j > 0 means v_rel = 0 and v_rel > 0 means j = 0: 1e-8 m/s and 1e-6 of the total impulse.
    CHECK(vRelAt(s, c) >= -1e-8);
    if (c.j > 1e-6 * total) CHECK(vRelAt(s, c) <= 1e-8);
  }
}

namespace {

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

// The sequential solver of world.hpp (Gauss-Seidel), written here with the oracles: warm start,
// then sweeps in order, each point aiming at the target decided from v_rel_minus with the velocities
// the sweep has left so far, the accumulated total clamped to j >= 0 and friction to the cone of
// the j just found.
int oracleSequential(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  for (const Contact& c : contacts) oracleApply(bodies[c.a], bodies[c.b], c.p, c.j * c.n + c.j_t);
  int sweeps = 0;
  while (sweeps < settings.iterations) {
    ++sweeps;
    double largest = 0.0;
    for (Contact& c : contacts) {
      ContactBody &A = bodies[c.a], &B = bodies[c.b];
      const double target = c.v_rel_minus < -settings.restitution_threshold ? -c.epsilon * c.v_rel_minus : 0.0;
      const double K = oracleK(A, B, c.p, c.n);
      const double j = std::max(0.0, c.j + (target - c.n.dot(oracleRelativeVelocity(A, B, c.p))) / K);
      oracleApply(A, B, c.p, (j - c.j) * c.n);
      largest = std::max(largest, K * std::abs(j - c.j));
      c.j = j;
      if (c.mu > 0.0) {
        const Vec3 j_t = oracleClamp(c.j_t + oracleFriction(A, B, c.p, c.n, kUnbounded), c.mu * c.j);
        const Vec3 change = j_t - c.j_t;
        oracleApply(A, B, c.p, change);
        c.j_t = j_t;
        const double size = change.norm();
        if (size > 0.0) largest = std::max(largest, size * oracleK(A, B, c.p, change / size));
      }
    }
    if (largest <= settings.tolerance) break;
  }
  return sweeps;
}

// The simultaneous solver of world.hpp: warm start, then Jacobi sweeps from the start-of-sweep
// velocities with shares 1 / (most points on either body), accumulated and clamped.
int oracleSimultaneous(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const Settings& settings) {
  std::vector<int> points_on(bodies.size(), 0);
  for (const Contact& c : contacts) {
    if (bodies[c.a].inv_mass > 0.0) ++points_on[c.a];
    if (bodies[c.b].inv_mass > 0.0) ++points_on[c.b];
  }
  for (const Contact& c : contacts) oracleApply(bodies[c.a], bodies[c.b], c.p, c.j * c.n + c.j_t);
  int sweeps = 0;
  while (sweeps < settings.iterations) {
    ++sweeps;
    const std::vector<ContactBody> start = bodies;
    std::vector<Vec3> change(contacts.size());
    double largest = 0.0;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      Contact& c = contacts[k];
      ContactBody A = start[c.a], B = start[c.b];
      const double share = 1.0 / std::max({1, points_on[c.a], points_on[c.b]});
      const double target = c.v_rel_minus < -settings.restitution_threshold ? -c.epsilon * c.v_rel_minus : 0.0;
      const double K = oracleK(A, B, c.p, c.n);
      const double j = std::max(0.0, c.j + share * (target - c.n.dot(oracleRelativeVelocity(A, B, c.p))) / K);
      const double dj = j - c.j;
      c.j = j;
      Vec3 dj_t = Vec3::Zero();
      if (c.mu > 0.0) {
        oracleApply(A, B, c.p, dj * c.n);
        const Vec3 j_t = oracleClamp(c.j_t + share * oracleFriction(A, B, c.p, c.n, kUnbounded), c.mu * c.j);
        dj_t = j_t - c.j_t;
        c.j_t = j_t;
      }
      change[k] = dj * c.n + dj_t;
      largest = std::max(largest, K * (std::abs(dj) + dj_t.norm()));
    }
    for (std::size_t k = 0; k < contacts.size(); ++k) oracleApply(bodies[contacts[k].a], bodies[contacts[k].b], contacts[k].p, change[k]);
    if (largest <= settings.tolerance) break;
  }
  return sweeps;
}

// The solver's contacts and bodies against the oracle's, after the same sweeps.
void checkSameSweeps(const BoxOnGround& student, const BoxOnGround& oracle) {
  const ContactBody &box = student.bodies[0], &expected = oracle.bodies[0];
  double size = 1.0;
  for (const Contact& c : oracle.contacts) size += c.j + c.j_t.norm();
  INFO("box v " << box.v.transpose() << ", expected " << expected.v.transpose());
  // The same formulas in another order over a few sweeps: round-off relative to the impulses
  // (~10 N s) and speeds (~10 m/s) involved.
  CHECK(velocityDistance(box, expected) <= 1e-10 * size);
  for (std::size_t k = 0; k < oracle.contacts.size(); ++k) {
    INFO("point " << k << ": j " << student.contacts[k].j << ", expected " << oracle.contacts[k].j);
    CHECK(std::abs(student.contacts[k].j - oracle.contacts[k].j) <= 1e-10 * size);
    CHECK((student.contacts[k].j_t - oracle.contacts[k].j_t).norm() <= 1e-10 * size);
  }
}

}  // namespace

TEST_CASE("sequential impulses: the first sweeps on a box are the contract's, point after point", "[lab05][pts=2][sec=5]") {
  // From rest and from last step's impulses, as the simultaneous test below
  for (const bool warm : {false, true}) {
    const double mu = uniform(0.1, 1.0);
    BoxOnGround s = boxOnGround(uniform(0.0, 1.0), mu, 5e-4);  // flat: four points
    REQUIRE(s.contacts.size() == 4);
    // Warm: last step's impulses on half of the points. The first point's is far more than the
    // box needs (alone it lifts the point at > 10 m/s, against at most ~4 m/s of approach): the
    // first sweep must take some of it back, clamping the accumulated j (not the correction) at 0
    for (std::size_t k = 0; warm && k < s.contacts.size(); k += 2) {
      s.contacts[k].j = (k == 0 ? uniform(10.0, 15.0) : uniform(0.0, 0.5)) * s.m;
      s.contacts[k].j_t = uniform(0.0, 1.0) * mu * s.contacts[k].j * s.contacts[k].n.cross(randomVec3(1.0)).normalized();
    }
    const double j0 = s.contacts[0].j;
    BoxOnGround oracle = s;
    Settings settings;
    settings.iterations = static_cast<int>(uniform(2, 7));  // a few sweeps, mostly before convergence
    const int expected = oracleSequential(oracle.bodies, oracle.contacts, settings);
    INFO((warm ? "warm" : "cold") << ", " << settings.iterations << " sweeps allowed, " << expected << " expected");
    CHECK(solveSequential(s.bodies, s.contacts, settings) == expected);
    checkSameSweeps(s, oracle);
    if (warm) CHECK(s.contacts[0].j < j0);  // a sweep took impulse back
  }
}

TEST_CASE("simultaneous impulses: the first sweeps on a box are Jacobi's, with shares and clamps", "[lab05][pts=2][sec=6]") {
  // From rest (every point's correction positive at first) and from last step's impulses
  for (const bool warm : {false, true}) {
    const double mu = uniform(0.1, 1.0);
    BoxOnGround s = boxOnGround(uniform(0.0, 1.0), mu, 5e-4);  // flat: four points, shares of 1/4
    REQUIRE(s.contacts.size() == 4);
    // Warm: last step's impulses on half of the points. The first point's is far more than the
    // box needs (alone it lifts the point at > 10 m/s, against at most ~4 m/s of approach): its
    // correction must be negative, and the accumulated j (not the correction) is what stays >= 0
    for (std::size_t k = 0; warm && k < s.contacts.size(); k += 2) {
      s.contacts[k].j = (k == 0 ? uniform(10.0, 15.0) : uniform(0.0, 0.5)) * s.m;
      s.contacts[k].j_t = uniform(0.0, 1.0) * mu * s.contacts[k].j * s.contacts[k].n.cross(randomVec3(1.0)).normalized();
    }
    BoxOnGround oracle = s;
    Settings settings;
    settings.method = ResponseMethod::Simultaneous;
    settings.iterations = static_cast<int>(uniform(2, 7));  // a few sweeps, mostly before convergence
    const int expected = oracleSimultaneous(oracle.bodies, oracle.contacts, settings);
    INFO((warm ? "warm" : "cold") << ", " << settings.iterations << " sweeps allowed, " << expected << " expected");
    CHECK(solveSimultaneous(s.bodies, s.contacts, settings) == expected);
    checkSameSweeps(s, oracle);
  }
}

// ---------------------------------------------------------------------------------------------
// Sweep counts and stopping rules, worked out by hand on scenes where one sweep is exact, and the
// shares on a scene where the ground and a box carry several points.

namespace {

// A solid sphere (mass m, radius r, isotropic inertia 2/5 m r^2) touching the fixed ground at its
// lowest point, moving down and sliding: K along any direction at that point is 1/m along n and
// 7/(2m) in the tangent plane, and the normal and tangential parts do not couple.
struct SphereOnGround {
  std::vector<ContactBody> bodies;  // sphere, ground
  Contact contact;
  double m = 1.0, r = 0.1;
};

SphereOnGround sphereOnGround(double epsilon, double mu) {
  SphereOnGround s;
  s.m = uniform(0.5, 5.0);
  s.r = uniform(0.05, 0.5);
  ContactBody sphere, ground;
  sphere.x = Vec3(uniform(-1, 1), uniform(-1, 1), s.r);
  sphere.v = Vec3(uniform(-2, 2), uniform(-2, 2), uniform(-3, -1));
  sphere.omega = randomVec3(2.0);
  sphere.inv_mass = 1.0 / s.m;
  sphere.I_inv_world = Mat3::Identity() / (0.4 * s.m * s.r * s.r);
  s.bodies = {sphere, ground};
  Contact& c = s.contact;
  c.a = 0;
  c.b = 1;
  c.p = Vec3(sphere.x.x(), sphere.x.y(), 0.0);
  c.n = Vec3::UnitZ();
  c.epsilon = epsilon;
  c.mu = mu;
  c.v_rel_minus = sphere.v.z();
  c.kind = ContactKind::Colliding;
  return s;
}

// The sliding velocity of the sphere's lowest point, v + omega x (p - x) in the ground's plane.
Vec3 sphereSlip(const SphereOnGround& s) {
  const ContactBody& sphere = s.bodies[0];
  const Vec3 v = sphere.v + sphere.omega.cross(s.contact.p - sphere.x);
  return Vec3(v.x(), v.y(), 0.0);
}

// Multiplies both bodies' masses and inertias by `factor` (velocities kept).
void makeHeavier(RandomPair& s, double factor) {
  s.A.inv_mass /= factor;
  s.A.I_inv_world /= factor;
  s.B.inv_mass /= factor;
  s.B.I_inv_world /= factor;
  s.m_a *= factor;
  s.m_b *= factor;
  s.I_a *= factor;
  s.I_b *= factor;
}

}  // namespace

TEST_CASE("sequential and simultaneous impulses: one frictionless point takes one sweep and one quiet sweep", "[lab05][pts=1][sec=5][sec=6]") {
  const RandomPair s = approachingPair();  // |v_rel| >= 0.3 m/s: above the restitution threshold
  const double epsilon = uniform(0.0, 1.0);
  INFO("v_rel " << vRel(s) << ", epsilon " << epsilon);
  // Sequential: the first sweep gives the point its full impulse, so v_rel = -epsilon v_rel-; the
  // second's correction is round-off, below the tolerance, and it stops. Returned: 2 sweeps.
  std::vector<ContactBody> bodies = {s.A, s.B};
  std::vector<Contact> contacts = {oneContact(s, epsilon, 0.0)};
  Settings settings;
  CHECK(solveSequential(bodies, contacts, settings) == 2);
  // Simultaneous, cold: one point has a share of 1, so the first correction reaches the target
  // exactly; the second sweep's correction is round-off, below the tolerance. 2 sweeps.
  bodies = {s.A, s.B};
  contacts = {oneContact(s, epsilon, 0.0)};
  settings.method = ResponseMethod::Simultaneous;
  CHECK(solveSimultaneous(bodies, contacts, settings) == 2);
  // Warm-started from the answer j = -(1 + epsilon) v_rel / K: the first sweep of either already
  // finds nothing to correct. 1 sweep.
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    bodies = {s.A, s.B};
    contacts = {oneContact(s, epsilon, 0.0)};
    contacts[0].j = -(1.0 + epsilon) * vRel(s) / oracleK(s.A, s.B, s.p, s.n);
    settings.method = method;
    INFO(responseMethodName(method) << ", warm-started from the answer");
    CHECK((method == ResponseMethod::Sequential ? solveSequential(bodies, contacts, settings)
                                                : solveSimultaneous(bodies, contacts, settings)) == 1);
  }
}

TEST_CASE("sequential and simultaneous impulses: a fixed body's own velocity counts: a ball landing on a moving, turning belt leaves with the belt", "[lab05][pts=1][sec=5][sec=6]") {
  // A fixed body (inv_mass 0, I_inv 0) takes no impulse but may move, as a conveyor belt or a
  // turntable driven from outside: the relative velocity is that of the touching points, the
  // belt's v + omega x (p - x) included. A ball lands on it with mu = 10 (the cone never cuts);
  // after the solve the ball's lowest point moves as the belt's point does plus the bounce
  // -epsilon v_rel- along n, and the belt is unchanged. Checked with the belt as B (n up, towards
  // the ball) and as A (n down, towards the belt), and one fixed case beside the random one.
  struct Case {
    Vec3 belt_v, belt_omega, ball_v, ball_omega;
    double epsilon;
  };
  const std::vector<Case> cases = {
      {Vec3(1.0, 0.0, 0.0), Vec3(0.0, 0.0, 0.5), Vec3(0.0, 0.0, -2.0), Vec3::Zero(), 0.5},
      {Vec3(uniform(-2, 2), uniform(-2, 2), 0.0), Vec3(0.0, 0.0, uniform(-1, 1)),
       Vec3(uniform(-2, 2), uniform(-2, 2), uniform(-3, -1)), randomVec3(2.0), uniform(0.0, 1.0)}};
  for (const Case& k : cases) {
    for (const bool belt_is_a : {false, true}) {
      for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
        const double m = 2.0, r = 0.2;
        ContactBody ball, belt;
        ball.x = Vec3(0.3, -0.4, r);
        ball.v = k.ball_v;
        ball.omega = k.ball_omega;
        ball.inv_mass = 1.0 / m;
        ball.I_inv_world = Mat3::Identity() / (0.4 * m * r * r);
        belt.x = Vec3(-0.5, 0.2, -0.1);  // off the point, so that its turn moves the point
        belt.v = k.belt_v;
        belt.omega = k.belt_omega;
        Contact c;
        c.a = belt_is_a ? 1 : 0;
        c.b = belt_is_a ? 0 : 1;
        c.p = Vec3(ball.x.x(), ball.x.y(), 0.0);
        c.n = belt_is_a ? Vec3(-Vec3::UnitZ()) : Vec3(Vec3::UnitZ());
        c.epsilon = k.epsilon;
        c.mu = 10.0;
        const Vec3 belt_point = belt.v + belt.omega.cross(c.p - belt.x);
        const double approach = k.ball_v.z() - belt_point.z();  // the ball's point along +z, relative
        c.v_rel_minus = approach;                                // along n either way: n . (A - B)
        c.kind = ContactKind::Colliding;
        std::vector<ContactBody> bodies = {ball, belt};  // the ball is body 0, the belt body 1, as A or B
        std::vector<Contact> contacts = {c};
        Settings settings;
        settings.method = method;
        INFO(responseMethodName(method) << (belt_is_a ? ", belt as A" : ", belt as B") << ", epsilon " << k.epsilon
                                        << ", v_rel- " << approach << " m/s");
        if (method == ResponseMethod::Sequential) {
          solveSequential(bodies, contacts, settings);
        } else {
          solveSimultaneous(bodies, contacts, settings);
        }
        // The belt takes nothing, whatever its velocity
        CHECK(bodies[1].v == belt.v);
        CHECK(bodies[1].omega == belt.omega);
        // The ball's point: the belt's point in the plane (sticking), and -epsilon v_rel- apart along
        // +z. One point converges in its first sweep (a sphere's friction does not move its normal
        // velocity): what is left is round-off of speeds of ~5 m/s, far below 1e-9 m/s.
        const Vec3 ball_point = bodies[0].v + bodies[0].omega.cross(c.p - bodies[0].x);
        const Vec3 expected = belt_point + Vec3(0.0, 0.0, -k.epsilon * approach);
        CHECK((ball_point - expected).norm() <= 1e-9);
      }
    }
  }
}

TEST_CASE("sequential and simultaneous impulses: a body pinned at its centre (inverse mass 0, inverse inertia not) turns, as A or as B", "[lab05][pts=1][sec=5][sec=6]") {
  // Fixed means both inverses zero (world.hpp); a wheel on an axle through its centre has m^-1 = 0
  // but turns, and the solvers must give it its impulse. By hand: I^-1 = 2 1, spinning at
  // omega = (0, 3, 0), its point p = (1, 0, 0) hitting the fixed ground at 3 m/s (n = z from the
  // ground to the wheel); K = 2, epsilon = 1/2: j = 1.5 x 3 / 2 = 2.25 and omega = (0, -1.5, 0),
  // the point leaving at 1.5 m/s; exact in binary. Seeded: a pinned body of random inertia and
  // spin hit by a moving ball at a random point, frictionless.
  ContactBody wheel;
  wheel.I_inv_world = 2.0 * Mat3::Identity();
  wheel.omega = Vec3(0.0, 3.0, 0.0);
  for (const bool wheel_is_a : {true, false}) {
    for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
      std::vector<ContactBody> bodies = {wheel, ContactBody{}};  // the wheel, the ground
      Contact c;
      c.a = wheel_is_a ? 0 : 1;
      c.b = wheel_is_a ? 1 : 0;
      c.p = Vec3(1.0, 0.0, 0.0);
      c.n = wheel_is_a ? Vec3(Vec3::UnitZ()) : Vec3(-Vec3::UnitZ());
      c.epsilon = 0.5;
      c.v_rel_minus = -3.0;
      c.kind = ContactKind::Colliding;
      std::vector<Contact> contacts = {c};
      Settings settings;
      settings.method = method;
      INFO(responseMethodName(method) << (wheel_is_a ? ", wheel as A" : ", wheel as B"));
      const int sweeps = method == ResponseMethod::Sequential ? solveSequential(bodies, contacts, settings)
                                                              : solveSimultaneous(bodies, contacts, settings);
      CHECK(sweeps == 2);  // the answer, then a quiet sweep
      CHECK(contacts[0].j == 2.25);
      CHECK(bodies[0].omega == Vec3(0.0, -1.5, 0.0));
      CHECK(bodies[0].v == Vec3::Zero());  // pinned: the centre stays
      CHECK(bodies[1].v == Vec3::Zero());
      CHECK(bodies[1].omega == Vec3::Zero());
    }
  }
  ContactBody pinned;
  pinned.x = randomVec3(0.5);
  pinned.omega = randomVec3(3.0);
  pinned.I_inv_world = randomInertiaTensor().inverse();
  const double m = uniform(0.5, 5.0), r = uniform(0.1, 0.5);
  const Vec3 n = randomVec3(1.0).normalized();
  const Vec3 p = pinned.x + uniform(0.3, 1.0) * randomVec3(1.0).cross(n).normalized();  // off the centre, across n
  ContactBody ball;
  ball.x = p - r * n;  // below the point along n: n points from the ball (B) to the pinned body (A)
  ball.inv_mass = 1.0 / m;
  ball.I_inv_world = Mat3::Identity() / (0.4 * m * r * r);
  ball.omega = randomVec3(2.0);
  ball.v = randomVec3(1.0);
  const double approach = n.dot(oracleRelativeVelocity(pinned, ball, p));
  ball.v += (approach + uniform(0.5, 3.0)) * n;  // the points now approach at 0.5 to 3 m/s
  const double before = n.dot(oracleRelativeVelocity(pinned, ball, p)), epsilon = uniform(0.0, 1.0);
  for (const bool pinned_is_a : {true, false}) {
    for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
      std::vector<ContactBody> bodies = {pinned, ball};
      Contact c;
      c.a = pinned_is_a ? 0 : 1;
      c.b = pinned_is_a ? 1 : 0;
      c.p = p;
      c.n = pinned_is_a ? n : Vec3(-n);
      c.epsilon = epsilon;
      c.v_rel_minus = before;
      c.kind = ContactKind::Colliding;
      std::vector<Contact> contacts = {c};
      Settings settings;
      settings.method = method;
      INFO(responseMethodName(method) << (pinned_is_a ? ", pinned body as A" : ", pinned body as B") << ", v_rel- " << before
                                      << ", epsilon " << epsilon);
      if (method == ResponseMethod::Sequential) {
        solveSequential(bodies, contacts, settings);
      } else {
        solveSimultaneous(bodies, contacts, settings);
      }
      CHECK(bodies[0].v == Vec3::Zero());
      CHECK((bodies[0].omega - pinned.omega).norm() > 0.0);  // it turned
      // One frictionless point: the first sweep's correction is the answer, the second round-off.
      // Round-off relative to the impulse and to speeds of ~5 m/s.
      const double j = -(1.0 + epsilon) * before / oracleK(pinned, ball, p, n);
      CHECK(contacts[0].j == Approx(j).epsilon(1e-10));
      CHECK(n.dot(oracleRelativeVelocity(bodies[0], bodies[1], p)) == Approx(-epsilon * before).margin(1e-10 * (1.0 + std::abs(before))));
    }
  }
}

TEST_CASE("sequential and simultaneous impulses: a sweep that only stops a slip is quiet when the slip is at most the tolerance, in m/s either side of 1", "[lab05][pts=1][sec=5][sec=6]") {
  // A point mass (m^-1 = 1/2, no inertia: K = 1/2 along any direction) resting on the ground with
  // its weight's impulse j = 1 warm-started, so that its normal velocity -1/2 becomes exactly 0,
  // and sliding at s along x with mu = 10 (the cone never cuts). The first sweep changes no normal
  // velocity and stops the slip with j_t = -2 s: the sweep changed a velocity by s. It is quiet
  // (1 sweep) when s <= tolerance, else a second, quiet, sweep follows (2). Comparing s^2 instead
  // moves the threshold to sqrt(tolerance): wrong between the two, below 1 m/s and above.
  // Powers of two and small integers: every velocity is exact.
  struct Case {
    double tolerance, s;
    int sweeps;
  };
  for (const Case& k : {Case{1.0 / 1024, 1.0 / 64, 2},   // s^2 = 1/4096 would be below the tolerance
                        Case{1.0 / 1024, 1.0 / 1024, 1},  // exactly the tolerance: quiet
                        Case{1.0 / 1024, 0.5, 2},
                        Case{4.0, 3.0, 1},                // s^2 = 9 would be above it
                        Case{4.0, 4.0, 1},
                        Case{4.0, 4.5, 2}}) {
    for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
      ContactBody puck;
      puck.inv_mass = 0.5;
      puck.v = Vec3(k.s, 0.0, -0.5);
      std::vector<ContactBody> bodies = {puck, ContactBody{}};
      Contact c;
      c.p = Vec3::Zero();
      c.mu = 10.0;
      c.j = 1.0;
      c.v_rel_minus = -0.5;
      c.kind = ContactKind::Colliding;
      c.a = 0;
      c.b = 1;
      std::vector<Contact> contacts = {c};
      Settings settings;
      settings.method = method;
      settings.tolerance = k.tolerance;
      INFO(responseMethodName(method) << ", tolerance " << k.tolerance << " m/s, slip " << k.s << " m/s");
      const int sweeps = method == ResponseMethod::Sequential ? solveSequential(bodies, contacts, settings)
                                                              : solveSimultaneous(bodies, contacts, settings);
      CHECK(sweeps == k.sweeps);
      CHECK(contacts[0].j == 1.0);
      CHECK(contacts[0].j_t == Vec3(-2.0 * k.s, 0.0, 0.0));
      CHECK(bodies[0].v == Vec3::Zero());
    }
  }
}

TEST_CASE("sequential and simultaneous impulses: the stopping rule measures velocity changes, friction included", "[lab05][pts=2][sec=5][sec=6]") {
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    INFO(responseMethodName(method));
    auto solve = [method](std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, Settings settings) {
      settings.method = method;
      return method == ResponseMethod::Sequential ? solveSequential(bodies, contacts, settings)
                                                  : solveSimultaneous(bodies, contacts, settings);
    };
    // Heavy bodies (x1000): a correction of velocity dv is an impulse of dv / K, about 1000 dv.
    // With the tolerance at twice the first correction's velocity change, the first sweep (exact,
    // one point) is already within it: the solver stops after 1 sweep.
    RandomPair heavy = approachingPair();
    makeHeavier(heavy, 1e3);
    const double epsilon = uniform(0.0, 1.0);
    std::vector<ContactBody> bodies = {heavy.A, heavy.B};
    std::vector<Contact> contacts = {oneContact(heavy, epsilon, 0.0)};
    Settings settings;
    settings.tolerance = 2.0 * (1.0 + epsilon) * std::abs(vRel(heavy));
    INFO("K " << oracleK(heavy.A, heavy.B, heavy.p, heavy.n) << " 1/kg, tolerance " << settings.tolerance << " m/s");
    CHECK(solve(bodies, contacts, settings) == 1);
    // Stopping does not drop the last sweep's correction: the bodies received the reported j and the
    // point leaves at -epsilon v_rel- (v_rel is linear in j: round-off of the speeds, ~10 m/s).
    const double before = vRel(heavy);
    CHECK(contacts[0].j == Approx(-(1.0 + epsilon) * before / oracleK(heavy.A, heavy.B, heavy.p, heavy.n)).epsilon(1e-10));
    heavy.A = bodies[0];
    heavy.B = bodies[1];
    CHECK(vRel(heavy) == Approx(-epsilon * before).margin(1e-10 * (1.0 + std::abs(before))));

    // A sphere sliding on the ground, warm-started with exactly its normal impulse and no friction:
    // the first sweep's normal correction is zero, its friction correction stops the slip (mu = 10
    // keeps it inside the cone). That is a velocity change of |v_t|, so a second sweep is needed,
    // which finds nothing left: 2 sweeps.
    SphereOnGround s = sphereOnGround(epsilon, 10.0);
    const double target = -epsilon * s.contact.v_rel_minus;  // v_rel- <= -1 m/s: above the threshold
    s.contact.j = s.m * (target - s.contact.v_rel_minus);    // K along n is 1/m: no coupling
    const Vec3 slip = sphereSlip(s);
    INFO("slip " << slip.transpose() << " m/s, j " << s.contact.j << " N s");
    std::vector<Contact> sphere_contacts = {s.contact};
    CHECK(solve(s.bodies, sphere_contacts, Settings{}) == 2);
    // The normal velocity reached the target and the slip stopped; the friction impulse that stops a
    // slip v_t at the lowest point of a sphere is 2 m |v_t| / 7. Round-off of ~10 m/s, ~10 N s.
    CHECK(s.bodies[0].v.z() == Approx(target).margin(1e-12 * (1.0 + std::abs(target))));
    CHECK(sphereSlip(s).norm() <= 1e-12 * (1.0 + slip.norm()));
    CHECK(sphere_contacts[0].j_t.norm() == Approx(2.0 * s.m * slip.norm() / 7.0).epsilon(1e-10));
  }
}

TEST_CASE("sequential impulses: on a heavy box the sweeps stop when friction changes no sliding speed by more than the tolerance", "[lab05][pts=1][sec=5]") {
  // The box is 1000 times heavier: friction's impulses (N s) are ~1000 times the sliding-speed
  // changes (m/s) they make, and only the latter is compared with the tolerance.
  BoxOnGround s = boxOnGround(uniform(0.0, 1.0), uniform(0.1, 1.0), 5e-4);  // flat: four points
  REQUIRE(s.contacts.size() == 4);
  s.m *= 1e3;
  s.I *= 1e3;
  s.bodies[0].inv_mass /= 1e3;
  s.bodies[0].I_inv_world /= 1e3;
  BoxOnGround oracle = s;
  Settings settings;
  settings.iterations = 1000;
  settings.tolerance = std::pow(10.0, uniform(-3.0, -2.0));  // coarse: the stopping rule decides
  const int expected = oracleSequential(oracle.bodies, oracle.contacts, settings);
  INFO(expected << " sweeps expected, tolerance " << settings.tolerance << " m/s");
  CHECK(solveSequential(s.bodies, s.contacts, settings) == expected);
  checkSameSweeps(s, oracle);
}

TEST_CASE("simultaneous impulses: the share counts each moving body's points, as A or as B, and none on the fixed ground", "[lab05][pts=1][sec=6]") {
  // Bodies: 0 the fixed ground, 1 a flat box on it (A, four corners), 2 a sphere on the box (A,
  // with the box as B), 3 a sphere on the ground elsewhere (A). The box carries 5 points, each
  // sphere 1, the ground none that count (a fixed body takes no correction). Shares: 1/5 at the
  // box's corners and under the sphere on it, 1 under the lone sphere.
  const Vec3 half(uniform(0.1, 0.5), uniform(0.1, 0.5), uniform(0.1, 0.5));
  const double m_box = uniform(0.5, 5.0), m_top = uniform(0.5, 5.0), m_lone = uniform(0.5, 5.0), r = 0.1;
  std::vector<ContactBody> bodies(4);
  ContactBody &box = bodies[1], &top = bodies[2], &lone = bodies[3];
  box.x = Vec3(0.0, 0.0, half.z());
  box.v = Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-3, -1));
  box.omega = randomVec3(0.3);  // corners move at most ~0.3 m/s from the rotation: all approach
  box.inv_mass = 1.0 / m_box;
  box.I_inv_world = Vec3(half.y() * half.y() + half.z() * half.z(), half.x() * half.x() + half.z() * half.z(),
                         half.x() * half.x() + half.y() * half.y()).asDiagonal().inverse();
  box.I_inv_world *= 3.0 / m_box;
  top.x = Vec3(uniform(-0.5, 0.5) * half.x(), uniform(-0.5, 0.5) * half.y(), 2.0 * half.z() + r);
  top.v = box.v + Vec3(0.0, 0.0, uniform(-2.0, -1.0));  // faster down than the box under it
  top.inv_mass = 1.0 / m_top;
  top.I_inv_world = Mat3::Identity() / (0.4 * m_top * r * r);
  lone.x = Vec3(3.0, 0.0, r);
  lone.v = Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-3, -1));
  lone.inv_mass = 1.0 / m_lone;
  lone.I_inv_world = Mat3::Identity() / (0.4 * m_lone * r * r);
  std::vector<Contact> contacts;
  auto add = [&](int a, int b, const Vec3& p) {
    Contact c;
    c.a = a;
    c.b = b;
    c.p = p;
    c.n = Vec3::UnitZ();
    c.epsilon = uniform(0.0, 1.0);
    c.v_rel_minus = c.n.dot(oracleRelativeVelocity(bodies[a], bodies[b], p));
    c.kind = ContactKind::Colliding;
    contacts.push_back(c);
  };
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0}) add(1, 0, Vec3(sx * half.x(), sy * half.y(), 0.0));
  add(2, 1, Vec3(top.x.x(), top.x.y(), 2.0 * half.z()));
  add(3, 0, Vec3(lone.x.x(), lone.x.y(), 0.0));
  // One sweep by hand: every correction from the starting velocities, share (target - v_rel) / K
  const double shares[] = {0.2, 0.2, 0.2, 0.2, 0.2, 1.0};
  std::vector<double> expected;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    REQUIRE(c.v_rel_minus < -Settings{}.restitution_threshold);  // all approach: target -epsilon v_rel-
    const double K = oracleK(bodies[c.a], bodies[c.b], c.p, c.n);
    expected.push_back(std::max(0.0, shares[k] * (-c.epsilon * c.v_rel_minus - c.v_rel_minus) / K));
  }
  const ContactBody lone0 = lone;
  Settings settings;
  settings.method = ResponseMethod::Simultaneous;
  settings.iterations = 1;
  CHECK(solveSimultaneous(bodies, contacts, settings) == 1);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    INFO("point " << k << " (bodies " << contacts[k].a << ", " << contacts[k].b << "): j " << contacts[k].j << ", expected "
                  << expected[k]);
    // The same formula evaluated in another order: round-off relative to the impulse (~10 N s).
    CHECK(contacts[k].j == Approx(expected[k]).epsilon(1e-10));
  }
  // The lone sphere alone on its point got its whole correction: it leaves at -epsilon v_rel-
  // (a sphere touching at its lowest point: K = 1/m, no rotation), round-off of ~10 m/s.
  CHECK(lone.v.z() == Approx(-contacts[5].epsilon * lone0.v.z()).margin(1e-12 * (1.0 + std::abs(lone0.v.z()))));
  CHECK(bodies[0].v == Vec3::Zero());  // the ground stays put (exactly)
}

// ---------------------------------------------------------------------------------------------
// Fixed configurations beside the random ones, on every run: the documented ends of the settings'
// ranges, points with nothing to do, and a sliding sphere worked out by hand with the moving body
// as A and as B.

namespace {

constexpr double kSphereMass = 2.0, kSphereRadius = 0.2;

// A solid sphere of 2 kg and radius 0.2 m, without spin, touching the fixed ground at its lowest
// point, the origin. The sphere is A above the ground (n = +z), or with `ground_as_a` the ground
// is A and the sphere B (n = -z). Either way v_rel = n . (pdot_A - pdot_B) is exactly v_z.
struct FixedSphere {
  std::vector<ContactBody> bodies;
  std::vector<Contact> contacts;
  int sphere = 0;  // the sphere's index in bodies
};

FixedSphere fixedSphereOnGround(const Vec3& v, double epsilon, double mu, bool ground_as_a) {
  ContactBody sphere, ground;
  sphere.x = Vec3(0.0, 0.0, kSphereRadius);
  sphere.v = v;
  sphere.inv_mass = 1.0 / kSphereMass;
  sphere.I_inv_world = Mat3::Identity() / (0.4 * kSphereMass * kSphereRadius * kSphereRadius);
  FixedSphere s;
  s.sphere = ground_as_a ? 1 : 0;
  s.bodies = ground_as_a ? std::vector<ContactBody>{ground, sphere} : std::vector<ContactBody>{sphere, ground};
  Contact c;
  c.a = 0;
  c.b = 1;
  c.p = Vec3::Zero();
  c.n = ground_as_a ? Vec3(-Vec3::UnitZ()) : Vec3(Vec3::UnitZ());
  c.epsilon = epsilon;
  c.mu = mu;
  c.v_rel_minus = v.z();
  c.kind = v.z() < -Settings{}.restitution_threshold ? ContactKind::Colliding
                                                      : (v.z() > 0.0 ? ContactKind::Separating : ContactKind::Resting);
  s.contacts = {c};
  return s;
}

int solveWith(ResponseMethod method, FixedSphere& s, Settings settings) {
  settings.method = method;
  return method == ResponseMethod::Sequential ? solveSequential(s.bodies, s.contacts, settings)
                                              : solveSimultaneous(s.bodies, s.contacts, settings);
}

const char* sideName(bool ground_as_a) { return ground_as_a ? "ground A, sphere B" : "sphere A, ground B"; }

}  // namespace

TEST_CASE("sequential and simultaneous impulses: with nothing approaching, no impulse and one quiet sweep, even at tolerance 0", "[lab05][pts=1][sec=5][sec=6]") {
  // Tolerance 0, the lower end of its range: only a point with v_rel < 0 approaches, and a solver
  // stops when nothing changes at all. At rest, leaving straight up (no slip, so friction has no
  // direction) and leaving while sliding (j stays 0, so the cone |j_t| <= mu j is a point).
  Settings settings;
  settings.tolerance = 0.0;
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    for (const bool ground_as_a : {false, true}) {
      for (const Vec3& v : {Vec3(Vec3::Zero()), Vec3(0.0, 0.0, 0.5), Vec3(1.5, -0.5, 0.5)}) {
        FixedSphere s = fixedSphereOnGround(v, 0.5, 0.8, ground_as_a);
        INFO(responseMethodName(method) << ", " << sideName(ground_as_a) << ", v " << v.transpose());
        CHECK(solveWith(method, s, settings) == 1);
        // Nothing was applied: every velocity and accumulated impulse is exactly what it was.
        CHECK(s.bodies[s.sphere].v == v);
        CHECK(s.bodies[s.sphere].omega == Vec3::Zero());
        CHECK(s.contacts[0].j == 0.0);
        CHECK(s.contacts[0].j_t == Vec3::Zero());
      }
    }
  }
  // No contacts at all: the one sweep that finds nothing (world.hpp), and no body touched.
  FixedSphere s = fixedSphereOnGround(Vec3(1.0, 0.0, -1.0), 0.5, 0.8, false);
  std::vector<Contact> none;
  CHECK(solveSequential(s.bodies, none, settings) == 1);
  settings.method = ResponseMethod::Simultaneous;
  CHECK(solveSimultaneous(s.bodies, none, settings) == 1);
  CHECK(s.bodies[0].v == Vec3(1.0, 0.0, -1.0));
}

TEST_CASE("sequential and simultaneous impulses: approaching at exactly the restitution threshold rests; a threshold of 0 bounces", "[lab05][pts=1][sec=5][sec=6]") {
  // v_rel = -0.25 m/s exactly. With the threshold at 0.25 m/s the point is resting (|v_rel| <=
  // threshold, ContactKind): epsilon = 0, it stops. With 0, the lower end of the range, every
  // approach bounces: v_z = +epsilon 0.25 = 0.125 m/s. K = 1/m exactly (r parallel to n).
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    for (const bool ground_as_a : {false, true}) {
      for (const double threshold : {0.25, 0.0}) {
        FixedSphere s = fixedSphereOnGround(Vec3(0.0, 0.0, -0.25), 0.5, 0.0, ground_as_a);
        Settings settings;
        settings.restitution_threshold = threshold;
        INFO(responseMethodName(method) << ", " << sideName(ground_as_a) << ", threshold " << threshold << " m/s");
        solveWith(method, s, settings);
        const double expected = threshold > 0.0 ? 0.0 : 0.125;
        // j = 0.25 m (1 + epsilon) and v += j / m: a few roundings of 0.25 m/s.
        CHECK(s.bodies[s.sphere].v.z() == Approx(expected).margin(1e-15));
        CHECK(s.contacts[0].j == Approx(kSphereMass * (0.25 + expected)).epsilon(1e-14));
      }
    }
  }
}

TEST_CASE("sequential impulses: each point leaves the solve with its lever arms and K matrix, whatever it arrived with", "[lab05][pts=1][sec=5]") {
  // Fixed: a sphere (m = 2 kg, r = 0.2 m, I = 2/5 m r^2) on the ground, as A and as B. Its lever
  // arm is -r n, so K = diag(1/m + r^2/I, 1/m + r^2/I, 1/m) = diag(3.5/m, 3.5/m, 1/m) by hand.
  for (const bool ground_as_a : {false, true}) {
    FixedSphere s = fixedSphereOnGround(Vec3(1.0, 0.0, -1.0), 0.5, 0.3, ground_as_a);
    INFO(sideName(ground_as_a));
    s.contacts[0].r_a = s.contacts[0].r_b = Vec3::Constant(7.0);  // stale values the solve must replace
    s.contacts[0].K_matrix = Mat3::Constant(-1.0);
    solveSequential(s.bodies, s.contacts, Settings{});
    const Contact& c = s.contacts[0];
    const Vec3 sphere_arm(0.0, 0.0, -kSphereRadius);
    CHECK(c.r_a == (ground_as_a ? Vec3::Zero() : sphere_arm));  // p - x: exact
    CHECK(c.r_b == (ground_as_a ? sphere_arm : Vec3::Zero()));
    const Mat3 K = Vec3(3.5, 3.5, 1.0).asDiagonal() * (1.0 / kSphereMass);
    CHECK((c.K_matrix - K).norm() <= 1e-14);  // a few roundings of numbers of order 1
  }
  // Random: two moving bodies with random inertia tensors; K_matrix d must be the change of
  // pdot_A - pdot_B that a unit impulse along d makes (oracleApply), for random d, and d . K d the
  // section 2 denominator (oracleK). The solve moves velocities only, so x and I^-1 are those on entry.
  for (int trial = 0; trial < 20; ++trial) {
    RandomPair pair = randomPair(trial % 4 == 3);
    std::vector<ContactBody> bodies = {pair.A, pair.B};
    Contact c;
    c.a = 0;
    c.b = 1;
    c.p = pair.p;
    c.n = pair.n;
    c.epsilon = 0.5;
    c.mu = 0.4;
    c.v_rel_minus = vRel(pair);
    c.r_a = c.r_b = randomVec3(3.0);
    c.K_matrix = Mat3::Random();
    std::vector<Contact> contacts = {c};
    solveSequential(bodies, contacts, Settings{});
    const Contact& done = contacts[0];
    CHECK(done.r_a == pair.p - pair.A.x);
    CHECK(done.r_b == pair.p - pair.B.x);
    for (int k = 0; k < 3; ++k) {
      const Vec3 d = randomVec3(1.0).normalized();
      ContactBody A = pair.A, B = pair.B;
      oracleApply(A, B, pair.p, d);
      const Vec3 change = oracleRelativeVelocity(A, B, pair.p) - oracleRelativeVelocity(pair.A, pair.B, pair.p);
      const double scale = oracleK(pair.A, pair.B, pair.p, d);
      // Sums of a few products of order-1 numbers: round-off relative to K's size.
      CHECK((done.K_matrix * d - change).norm() <= 1e-12 * (1.0 + done.K_matrix.norm()));
      CHECK(d.dot(done.K_matrix * d) == Approx(scale).epsilon(1e-12));
    }
  }
}

TEST_CASE("sequential and simultaneous impulses: a sphere sliding onto the ground takes j and mu j by hand, as A or as B", "[lab05][pts=1][sec=5][sec=6]") {
  // m = 2 kg, r = 0.2 m, I = 2/5 m r^2, arriving at v = (2, 0, -1) m/s without spin; epsilon 0.5,
  // mu 0.1. Normal: K = 1/m, j = (1 + epsilon) m 1 = 3 N s, v_z = +0.5. Friction: stopping the slip
  // of 2 m/s would take 2 / (7 / (2 m)) = 8/7 N s > mu j = 0.3 N s, so it slides: 0.3 N s against
  // the slip. v_x = 2 - 0.3 / m = 1.85, omega_y = r 0.3 / I = 1.875 rad/s, still sliding at
  // 1.85 - r 1.875 = 1.475 m/s. The stored j_t is the impulse on A: (-0.3, 0, 0) on the sphere as A,
  // (+0.3, 0, 0) on the ground as A. Two sweeps: the impulses, then a quiet sweep (the clamp holds).
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    for (const bool ground_as_a : {false, true}) {
      FixedSphere s = fixedSphereOnGround(Vec3(2.0, 0.0, -1.0), 0.5, 0.1, ground_as_a);
      INFO(responseMethodName(method) << ", " << sideName(ground_as_a));
      CHECK(solveWith(method, s, Settings{}) == 2);
      const ContactBody& sphere = s.bodies[s.sphere];
      const Contact& c = s.contacts[0];
      // A few roundings of numbers of order 1 (N s, m/s, rad/s).
      CHECK(c.j == Approx(3.0).epsilon(1e-14));
      CHECK((c.j_t - Vec3(ground_as_a ? 0.3 : -0.3, 0.0, 0.0)).norm() <= 1e-14);
      CHECK((sphere.v - Vec3(1.85, 0.0, 0.5)).norm() <= 1e-14);
      CHECK((sphere.omega - Vec3(0.0, 1.875, 0.0)).norm() <= 1e-14);
      // The ground, A or B, never moves (zero inverses, exactly).
      CHECK(s.bodies[1 - s.sphere].v == Vec3::Zero());
      CHECK(s.bodies[1 - s.sphere].omega == Vec3::Zero());
    }
  }
}

TEST_CASE("sequential and simultaneous impulses: the target comes from v_rel_minus, not from the velocity the solve starts with", "[lab05][pts=1][sec=5][sec=6]") {
  // The World classifies before gravity, so the point may approach faster (or slower) when the
  // solve starts than its v_rel_minus says. epsilon 0.5, K = 1/m = 0.5 exactly. By hand:
  //   v_rel- = -1,    v_z = -1.2: target +0.5 (not +0.6), j = 2 (0.5 + 1.2) = 3.4 N s
  //   v_rel- = -0.04, v_z = -0.5: slower than the 0.05 m/s threshold: target 0 (no bounce), j = 1
  //   v_rel- = -1,    v_z = -0.5: target +0.5 (not +0.25), j = 2 N s
  struct Case {
    double v_rel_minus, v_z, target, j;
  };
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    for (const Case& k : {Case{-1.0, -1.2, 0.5, 3.4}, Case{-0.04, -0.5, 0.0, 1.0}, Case{-1.0, -0.5, 0.5, 2.0}}) {
      FixedSphere s = fixedSphereOnGround(Vec3(0.0, 0.0, k.v_z), 0.5, 0.0, false);
      s.contacts[0].v_rel_minus = k.v_rel_minus;
      INFO(responseMethodName(method) << ", v_rel- " << k.v_rel_minus << ", v_z " << k.v_z);
      solveWith(method, s, Settings{});
      // A few roundings of numbers of order 1 (m/s, N s).
      CHECK(s.bodies[0].v.z() == Approx(k.target).margin(1e-14));
      CHECK(s.contacts[0].j == Approx(k.j).epsilon(1e-14));
    }
  }
}

TEST_CASE("sequential and simultaneous impulses: a sweep changing velocities by exactly the tolerance is quiet; iterations bound the sweeps", "[lab05][pts=1][sec=5][sec=6]") {
  // v = (0, 0, -1) m/s, epsilon 0.5, K = 1/m = 0.5 exactly: the first sweep gives j = 3 N s, a
  // velocity change of exactly K j = 1.5 m/s. A tolerance of 1.5 (its upper end: "no more than")
  // stops after that sweep; just below it a second, quiet sweep follows. With iterations = 1 and
  // tolerance 0 the solver stops after its one allowed sweep, with the impulse given.
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    for (const double tolerance : {1.5, 1.4999}) {
      FixedSphere s = fixedSphereOnGround(Vec3(0.0, 0.0, -1.0), 0.5, 0.0, false);
      Settings settings;
      settings.tolerance = tolerance;
      INFO(responseMethodName(method) << ", tolerance " << tolerance << " m/s");
      CHECK(solveWith(method, s, settings) == (tolerance == 1.5 ? 1 : 2));
      CHECK(s.contacts[0].j == 3.0);  // exact: (0.5 + 1) / 0.5 in binary
    }
    FixedSphere s = fixedSphereOnGround(Vec3(0.0, 0.0, -1.0), 0.5, 0.0, false);
    Settings settings;
    settings.tolerance = 0.0;
    settings.iterations = 1;
    INFO(responseMethodName(method) << ", 1 sweep allowed");
    CHECK(solveWith(method, s, settings) == 1);
    CHECK(s.bodies[0].v.z() == 0.5);  // exact: -1 + 3 / 2
  }
}

namespace {

// Equal, or both NaN: a refused contact may carry a NaN, and must still be exactly as it was.
bool same(double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); }
bool same(const Vec3& x, const Vec3& y) { return same(x.x(), y.x()) && same(x.y(), y.y()) && same(x.z(), y.z()); }

bool unchanged(const BoxOnGround& before, const BoxOnGround& after) {
  for (std::size_t i = 0; i < before.bodies.size(); ++i) {
    const ContactBody &X = before.bodies[i], &Y = after.bodies[i];
    if (!(same(X.v, Y.v) && same(X.omega, Y.omega) && same(X.inv_mass, Y.inv_mass))) return false;
  }
  for (std::size_t k = 0; k < before.contacts.size(); ++k) {
    if (!(same(before.contacts[k].j, after.contacts[k].j) && same(before.contacts[k].j_t, after.contacts[k].j_t))) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("sequential and simultaneous impulses: bad bodies and contacts are refused naming them, before anything changes", "[lab05][pts=2][sec=5][sec=6]") {
  // The box with friction and a warm start, the ground last: bodies 0 (box), 1 (a spare sphere
  // far away) and 2 (ground), so the contacts use the first and the last index
  BoxOnGround base = boxOnGround(0.5, 0.4);
  ContactBody spare;
  spare.x = Vec3(10.0, 0.0, 1.0);
  spare.inv_mass = 1.0;
  spare.I_inv_world = Mat3::Identity();
  base.bodies.insert(base.bodies.begin() + 1, spare);
  for (Contact& c : base.contacts) {
    c.b = 2;
    c.j = uniform(0.001, 0.01);  // a warm start that moves the box before the first sweep
  }
  const int last = static_cast<int>(base.contacts.size()) - 1;
  Settings settings;
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    INFO(responseMethodName(method));
    auto solve = [&](BoxOnGround& s) {
      return method == ResponseMethod::Sequential ? solveSequential(s.bodies, s.contacts, settings)
                                                  : solveSimultaneous(s.bodies, s.contacts, settings);
    };
    // Valid: indices 0 and size - 1, epsilon 0 and 1, mu 0, a normal off by round-off
    BoxOnGround ok = base;
    ok.contacts[0].epsilon = 1.0;
    ok.contacts[last].epsilon = 0.0;
    ok.contacts[last].mu = 0.0;
    ok.contacts[last].n *= 1.0 + 1e-12;
    CHECK(solve(ok) >= 1);
    CHECK(ok.bodies[0].v != base.bodies[0].v);
    // Each bad field on the last contact, so that a solver checking as it goes would already
    // have applied the warm start and earlier points: the message names the contact and the field
    const std::string where = "contact " + std::to_string(last);
    auto refused = [&](const std::function<void(Contact&)>& spoil, const std::string& words) {
      BoxOnGround spoilt = base;
      spoil(spoilt.contacts[static_cast<std::size_t>(last)]);
      INFO("expected: " << words);
      BoxOnGround s = spoilt;
      CHECK_THROWS_AS(solve(s), InvalidInput);
      s = spoilt;
      CHECK_THROWS_WITH(solve(s), Contains(where) && Contains(words));
      CHECK(unchanged(spoilt, s));
    };
    refused([](Contact& c) { c.a = 3; }, "body index a");
    refused([](Contact& c) { c.a = -1; }, "body index a");
    refused([](Contact& c) { c.b = 3; }, "body index b");
    refused([](Contact& c) { c.b = -1; }, "body index b");
    refused([](Contact& c) { c.n *= 1.5; }, "normal n");
    refused([](Contact& c) { c.n *= 1.0 + 1e-8; }, "normal n");
    refused([](Contact& c) { c.n.x() = std::nan(""); }, "normal n");
    refused([](Contact& c) { c.p.y() = std::numeric_limits<double>::infinity(); }, "point p");
    refused([](Contact& c) { c.epsilon = 1.5; }, "epsilon");
    refused([](Contact& c) { c.epsilon = -1e-9; }, "epsilon");
    refused([](Contact& c) { c.epsilon = std::nan(""); }, "epsilon");
    refused([](Contact& c) { c.mu = -0.1; }, "mu");
    refused([](Contact& c) { c.mu = std::nan(""); }, "mu");
    refused([](Contact& c) { c.v_rel_minus = std::nan(""); }, "v_rel_minus");
    refused([](Contact& c) { c.j = -0.1; }, "impulse j");
    refused([](Contact& c) { c.j_t.z() = std::nan(""); }, "j_t");
    // A negative or NaN inverse mass; with it restored, nothing else differs
    for (const double bad : {-1.0, std::nan("")}) {
      BoxOnGround s = base;
      s.bodies[0].inv_mass = bad;
      CHECK_THROWS_WITH(solve(s), Contains("body 0") && Contains("inverse mass"));
      s.bodies[0].inv_mass = base.bodies[0].inv_mass;
      CHECK(unchanged(base, s));
    }
  }
}
