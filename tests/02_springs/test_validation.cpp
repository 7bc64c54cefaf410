// Framework tests for Lab 2: bad networks and bad steps are refused with a message naming them.
#include "physlab/error.hpp"
#include "physlab/springs.hpp"
#include "support.hpp"

using namespace physlab;
using Catch::Matchers::Contains;

namespace {
SpringNetwork twoParticles(Spring s) {
  SpringNetwork net;
  net.masses = VecX::Ones(2);
  net.rest_positions = Mat3X::Zero(3, 2);
  net.springs.push_back(s);
  return net;
}
}  // namespace

TEST_CASE("springs validation: bad springs are refused", "[common]") {
  CHECK_THROWS_WITH(validate(twoParticles({0, 1, 1.0, -3.0, 0.0})), Contains("spring 0 stiffness ks"));
  CHECK_THROWS_WITH(validate(twoParticles({0, 1, -1.0, 3.0, 0.0})), Contains("spring 0 rest length"));
  CHECK_THROWS_WITH(validate(twoParticles({1, 1, 1.0, 3.0, 0.0})), Contains("joins particle 1 to itself"));
  CHECK_THROWS_WITH(validate(twoParticles({0, 7, 1.0, 3.0, 0.0})), Contains("names particle 7"));
  CHECK_THROWS_WITH(SpringSystem(twoParticles({0, 1, 1.0, 3.0, -1.0})), Contains("spring 0 damping kd"));
  SpringNetwork bad_mass = twoParticles({0, 1, 1.0, 3.0, 0.0});
  bad_mass.masses[1] = 0.0;
  CHECK_THROWS_WITH(validate(bad_mass), Contains("mass of particle 1"));
}

TEST_CASE("springs validation: a bad step or state is refused", "[common]") {
  const SpringSystem sys(makeRope(4, 1.0, 1.0, 100.0, 0.0));
  VecX X = sys.restState();
  CHECK_THROWS_WITH(implicitEulerStep(sys, X, 0.0), Contains("step size h"));
  VecX short_state = VecX::Zero(5);
  CHECK_THROWS_WITH(implicitEulerStep(sys, short_state, 0.01), Contains("has size 5, expected 24"));
  X[2] = std::nan("");
  CHECK_THROWS_WITH(implicitEulerStep(sys, X, 0.01), Contains("non-finite entry"));
  CHECK_THROWS_WITH(makeCloth(1, 5, 1.0, 0.0, 1.0, 1.0, 0.0), Contains("at least 2 x 2"));
}
