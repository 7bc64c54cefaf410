// Framework tests for Lab 6: the resting-contact solver's settings, the tangent directions and
// the scenes refuse bad input with a message naming it. They grade nothing (the code lives in
// common/), so they carry [common].
#include <cmath>
#include <memory>

#include "physlab/resting.hpp"
#include "support.hpp"

using namespace physlab;
using Catch::Matchers::Contains;

TEST_CASE("resting settings: bad values are refused, every value is printed", "[common]") {
  RestingSettings settings;
  settings.lcp.max_iterations = 0;
  CHECK_THROWS_WITH(LcpContactSolver(settings), Contains("max_iterations"));
  settings = RestingSettings{};
  settings.baumgarte = 1.5;
  CHECK_THROWS_WITH(LcpContactSolver(settings), Contains("baumgarte"));
  settings = RestingSettings{};
  settings.pyramid_directions = 2;
  CHECK_THROWS_WITH(LcpContactSolver(settings), Contains("pyramid_directions"));
  settings = RestingSettings{};
  settings.slop = -1e-3;
  CHECK_THROWS_WITH(LcpContactSolver(settings), Contains("slop"));
  settings = RestingSettings{};
  settings.regularization = std::nan("");
  CHECK_THROWS_WITH(LcpContactSolver(settings), Contains("regularization"));
  settings = RestingSettings{};
  settings.method = LcpMethod::Pivoting;
  settings.matrix_free = true;  // pivoting has no matrix-free path
  CHECK_THROWS_WITH(LcpContactSolver(settings), Contains("matrix_free"));
  settings.method = LcpMethod::Pgs;
  settings.formulation = Formulation::Acceleration;
  CHECK_THROWS_WITH(LcpContactSolver(settings), Contains("matrix_free"));
  settings.formulation = Formulation::Velocity;
  CHECK_THAT(LcpContactSolver(settings).describe(), Contains("matrix_free=yes"));
  settings = RestingSettings{};
  settings.method = LcpMethod::Lemke;
  settings.formulation = Formulation::Acceleration;
  const std::string line = LcpContactSolver(settings).describe();
  CHECK_THAT(line, Contains("formulation=acceleration") && Contains("lcp=Lemke") && Contains("baumgarte=0.2") &&
                       Contains("slop=0.001") && Contains("pyramid_directions=4") && Contains("matrix_free=no"));
  // Friction is the one thing the acceleration level and pivoting leave out: the line says so
  CHECK_THAT(line, Contains("friction ignored"));
  const World world(restingBox(0.0), restingWorldSettings(), std::make_shared<LcpContactSolver>(settings));
  CHECK_THAT(world.describe(), Contains("restitution_threshold=0.05") && Contains("colliding points: impulses, resting: formulation=acceleration"));
  CHECK_FALSE(LcpContactSolver(settings).bounces());
  // The defaults model friction (PGS on the cone) and bounces, and say nothing is ignored
  const LcpContactSolver defaults{RestingSettings{}};
  CHECK_THAT(defaults.describe(), Contains("lcp=PGS") && !Contains("ignored"));
  CHECK(defaults.bounces());
  const World bouncing(restingBox(0.0), restingWorldSettings(), std::make_shared<LcpContactSolver>(RestingSettings{}));
  CHECK_THAT(bouncing.describe(), Contains("every point (bounces too): formulation=velocity lcp=PGS"));
  settings.formulation = Formulation::Velocity;
  settings.method = LcpMethod::Pivoting;
  CHECK_THAT(LcpContactSolver(settings).describe(), Contains("friction ignored"));
}

TEST_CASE("tangent directions: k unit vectors in the tangent plane, evenly spaced, refused for a bad n", "[common]") {
  const Vec3 n = test::randomVec3(1.0).normalized();
  const std::vector<Vec3> d = tangentDirections(n, 6);
  REQUIRE(d.size() == 6);
  for (std::size_t l = 0; l < d.size(); ++l) {
    // A few products of unit vectors: round-off.
    CHECK(std::abs(d[l].norm() - 1.0) <= 1e-14);
    CHECK(std::abs(d[l].dot(n)) <= 1e-14);
    CHECK(d[l].dot(d[(l + 1) % d.size()]) == Approx(std::cos(2.0 * M_PI / 6)).margin(1e-14));
  }
  CHECK(tangentDirections(n, 6)[0] == d[0]);  // the same n, the same directions
  CHECK_THROWS_WITH(tangentDirections(2.0 * n, 4), Contains("unit"));
  CHECK_THROWS_AS(tangentDirections(n, 0), InvalidInput);
}

TEST_CASE("resting scenes: bad sizes and angles are refused", "[common]") {
  CHECK_THROWS_WITH(plankOnTwoSupports(0.0, 0.5), Contains("plank supports"));
  CHECK_THROWS_WITH(plankOnTwoSupports(0.5, 1.0), Contains("plank supports"));
  CHECK_THROWS_AS(cubeStack(0), InvalidInput);
  CHECK_THROWS_AS(cubePyramid(0), InvalidInput);
  CHECK_THROWS_WITH(frictionRamp(2.0, {0.5}), Contains("theta"));
  CHECK_THROWS_WITH(frictionRamp(0.3, {}), Contains("at least one block"));
  CHECK_THROWS_WITH(frictionRamp(0.3, {-0.5}), Contains("mu of block 0"));
  CHECK_THROWS_AS(heavyOnLight(0.0), InvalidInput);
  CHECK_THROWS_AS(restingBox(std::nan("")), InvalidInput);
  CHECK(cubePyramid(4).bodies.size() == 1 + 10);
}
