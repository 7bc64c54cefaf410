// Lab 5 graded tests of the many-contact solvers on a box hitting the ground on up to four
// points (Lab 4's reference narrow phase makes the manifold): what each solver guarantees.
#include <cmath>

#include "impulse_support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// A box slightly tilted, a millimetre into the ground, moving down with random velocities.
struct BoxOnGround {
  std::vector<ContactBody> bodies;  // box, ground
  std::vector<Contact> contacts;
  double m = 1.0;
  Mat3 I = Mat3::Identity();  // world inertia
};

BoxOnGround boxOnGround(double epsilon, double mu) {
  BoxOnGround s;
  const Vec3 half(uniform(0.1, 0.5), uniform(0.1, 0.5), uniform(0.1, 0.5));
  s.m = uniform(0.5, 5.0);
  Pose pose;
  pose.q = Quat(Eigen::AngleAxisd(uniform(-0.05, 0.05), Vec3::UnitX()) * Eigen::AngleAxisd(uniform(-0.05, 0.05), Vec3::UnitY()));
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

TEST_CASE("sequential impulses: frictionless, afterwards no point approaches and no energy is gained", "[lab05][pts=1]") {
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
    // The loop stops only when a sweep finds no point approaching faster than the tolerance.
    CHECK(vRelAt(s, c) >= -settings.tolerance);
    CHECK(c.j >= 0.0);
  }
  // Every impulse with epsilon <= 1 removes energy; round-off of the sums.
  CHECK(kinetic(s) <= E0 * (1.0 + 1e-12));
  CHECK(s.bodies[1].v == Vec3::Zero());  // the ground stays put: zero inverses (exactly)
}

TEST_CASE("sequential impulses: with friction, impulses stay in the cone and remove energy", "[lab05][pts=1]") {
  const double epsilon = uniform(0.0, 1.0), mu = uniform(0.1, 1.0);
  BoxOnGround s = boxOnGround(epsilon, mu);
  REQUIRE(s.contacts.size() >= 1);
  Settings settings;
  settings.iterations = static_cast<int>(uniform(1, 60));  // clamped after any number of sweeps
  const double E0 = kinetic(s);
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
  // Impulses with epsilon <= 1 and friction opposing the sliding remove energy; round-off.
  CHECK(kinetic(s) <= E0 * (1.0 + 1e-12));
}

TEST_CASE("simultaneous impulses: frictionless, they converge to v_rel >= 0 and warm starting reaches the same answer", "[lab05][pts=1]") {
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

TEST_CASE("simultaneous impulses: accumulated impulses stay clamped, j >= 0 and |j_t| <= mu j", "[lab05][pts=1]") {
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
