// Lab 2 hidden tests (instructor only, shown after grades are published).
#include "physlab/springs.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

TEST_CASE("hidden: a damped hanging rope settles where each spring carries the weight below it", "[lab02][pts=2][hidden][sec=1]") {
  const Index n = 8;
  const double k = uniform(200.0, 2000.0), m = uniform(0.05, 0.2), g = 9.81;
  SpringNetwork net = makeRope(n, 1.0, m * (n - 1), k, 2.0);
  net.drag = 0.1;
  const SpringSystem sys(net);
  VecX X = sys.restState();
  for (int step = 0; step < 3000; ++step) implicitEulerStep(sys, X, 0.01);
  double z = 0.0;
  for (Index i = 1; i < n; ++i) {
    z -= net.springs[i - 1].rest + (n - i) * m * g / k;
    // Implicit Euler's fixed points are the true equilibria; 30 s of damping leaves < 1e-9 m.
    CHECK(X[3 * i + 2] == Approx(z).margin(1e-8));
  }
}

TEST_CASE("hidden: a particle dropped on the penalty ground rests at depth m g / k", "[lab02][pts=1][hidden][sec=4]") {
  SpringNetwork net;
  net.masses = VecX::Constant(1, uniform(0.1, 1.0));
  net.rest_positions = Mat3X::Zero(3, 1);
  net.rest_positions(2, 0) = 0.3;
  net.gravity = Vec3(0, 0, -9.81);
  net.ground = {0.0, uniform(500.0, 5000.0), 5.0};
  const SpringSystem sys(net);
  VecX X = sys.restState();
  // 10 s: the damped bounce has died out (its slowest decay, c / 2m = 2.5/s, leaves 1e-11 m). At
  // h = 1e-3 RK4 is stable and accurate on the stiffest ground (h sqrt(k/m) <= 0.23), and the rest
  // depth does not depend on the path to it; a finer step only costs evaluations (each crosses
  // the wire in a grade).
  oracleRK4(sys, X, 1e-3, 10000);
  // Static balance k d = m g; RK4 at this step is exact to far below the 1e-9 m margin.
  CHECK(-X[2] == Approx(net.masses[0] * 9.81 / net.ground.stiffness).margin(1e-9));
}
