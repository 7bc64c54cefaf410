// Lab 6 hidden tests (instructor only, shown after grades are published).
#include <cmath>
#include <memory>

#include "physlab/resting.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

constexpr double kG = 9.81;
constexpr double kH = 1.0 / 60.0;

}  // namespace

TEST_CASE("hidden: a box at rest on the ground, velocity level with friction, carries Mg and stays put", "[lab06][pts=1][hidden][sec=1][sec=2][sec=5][sec=6][sec=7][sec=8]") {
  for (const LcpMethod method : {LcpMethod::Lemke, LcpMethod::Pgs}) {
    RestingSettings resting;
    resting.method = method;
    resting.lcp.max_iterations = 200;
    Scene scene = restingBox(uniform(-M_PI, M_PI));
    scene.bodies[0].mu = scene.bodies[1].mu = 0.5;
    World world(scene, restingWorldSettings(), std::make_shared<LcpContactSolver>(resting));
    const Vec3 start = world.states()[1].x;
    for (int step = 0; step < 60; ++step) world.step(kH);
    double impulse = 0.0;
    for (const Contact& c : world.contacts()) impulse += c.j * c.n.z();
    CAPTURE(lcpMethodName(method));
    // The normal impulses of a step cancel gravity's; PGS's 200 sweeps converge to 1e-6 here.
    CHECK(impulse == Approx(world.bodies()[1].mass * kG * kH).epsilon(1e-6));
    // Nothing pushes sideways: friction stays zero and the box does not move.
    CHECK((world.states()[1].x - start).norm() < 1e-6);
  }
}

TEST_CASE("hidden: Baraff's b with a fixed body as A and a spinning B", "[lab06][pts=1][hidden][sec=2]") {
  // B spins and moves, A is fixed: only B's terms and n_dot = omega_b x n remain. At p on B's
  // surface, d(t) = n(t) . (p - p_b(t)) with B's motion to second order; its central difference.
  ContactBody A, B;
  A.x = randomVec3(1.0);
  const Mat3 R = randomRotation();
  const Mat3 I = R * Vec3(uniform(0.2, 2.0), uniform(0.2, 2.0), uniform(0.2, 2.0)).asDiagonal() * R.transpose();
  B.x = randomVec3(1.0);
  B.v = randomVec3(2.0);
  B.omega = randomVec3(2.0);
  B.inv_mass = 1.0 / uniform(0.2, 5.0);
  B.I_inv_world = I.inverse();
  std::vector<AppliedLoads> loads(2);
  loads[1].F = randomVec3(5.0);
  loads[1].tau = randomVec3(2.0);
  loads[1].L = I * B.omega;
  const Vec3 p = randomVec3(1.0), n = randomVec3(1.0).normalized();
  auto skew = [](const Vec3& v) {
    Mat3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
  };
  const Vec3 omega_dot = B.I_inv_world * (loads[1].tau + loads[1].L.cross(B.omega));
  const Mat3 W = skew(B.omega);
  auto turn = [&](double t) -> Mat3 { return Mat3::Identity() + t * W + 0.5 * t * t * (skew(omega_dot) + W * W); };
  auto d = [&](double t) {
    const Vec3 p_b = B.x + t * B.v + 0.5 * t * t * B.inv_mass * loads[1].F + turn(t) * (p - B.x);
    return (turn(t) * n).dot(p - p_b);
  };
  // As in the graded test: d is a polynomial of degree 4, and Richardson's combination of two
  // central differences is exact for it up to round-off, eps |d| / delta^2.
  auto central = [&](double delta) { return (d(delta) - 2.0 * d(0.0) + d(-delta)) / (delta * delta); };
  const double d_ddot = (4.0 * central(0.005) - central(0.01)) / 3.0;
  const VecX b = accelerationBias({A, B}, loads, {{0, 1, p, n}});
  CHECK(b(0) == Approx(d_ddot).epsilon(1e-8).margin(1e-7));
}
