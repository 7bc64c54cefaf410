// Lab 5 scenes for tests and demos: a bouncing ball, Newton's cradle, a sliding box, a sphere
// thrown without spin, and a rain of boxes and spheres into a container.
#include <cmath>
#include <random>
#include <string>

#include "physlab/error.hpp"
#include "physlab/world.hpp"

namespace physlab {

namespace {

BodyState at(const Vec3& x, const Vec3& P = Vec3::Zero()) {
  BodyState s;
  s.x = x;
  s.P = P;
  return s;
}

}  // namespace

Scene bouncingBall(double height, double epsilon) {
  requireNonNegative(height, "bouncing ball height");
  const double r = 0.1;
  Scene scene;
  scene.bodies = {BodyDescription::plane(Vec3::UnitZ(), 0.0, 1.0, 0.0), BodyDescription::sphere(1.0, r, epsilon, 0.0)};
  scene.states = {BodyState{}, at(Vec3(0.0, 0.0, r + height))};
  return scene;
}

Scene newtonsCradle(int n, double v0) {
  if (n < 2) throw InvalidInput("Newton's cradle needs at least 2 balls, got " + std::to_string(n));
  requireFinite(Vec3(v0, 0.0, 0.0), "Newton's cradle speed v0");
  const double r = 0.1;
  // The balls overlap by a hair so that round-off in their positions cannot open a gap
  const double spacing = 2.0 * r - 1e-9;
  Scene scene;
  for (int i = 0; i < n; ++i) {
    scene.bodies.push_back(BodyDescription::sphere(1.0, r, 1.0, 0.0));
    scene.states.push_back(at(Vec3(i * spacing, 0.0, 0.0), Vec3(i == 0 ? v0 : 0.0, 0.0, 0.0)));
  }
  return scene;
}

Scene slidingBox(double v0, double mu) {
  const Vec3 half(0.2, 0.2, 0.1);
  Scene scene;
  scene.bodies = {BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.0, mu), BodyDescription::box(1.0, half, 0.0, mu)};
  scene.states = {BodyState{}, at(Vec3(0.0, 0.0, half.z()), Vec3(v0, 0.0, 0.0))};
  return scene;
}

Scene thrownSphere(double v0, double mu) {
  const double r = 0.1;
  Scene scene;
  scene.bodies = {BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.0, mu), BodyDescription::sphere(1.0, r, 0.0, mu)};
  scene.states = {BodyState{}, at(Vec3(0.0, 0.0, r), Vec3(v0, 0.0, 0.0))};
  return scene;
}

Scene boxRain(int count, std::uint64_t seed) {
  if (count < 0) throw InvalidInput("box rain count must not be negative");
  std::mt19937_64 engine(seed);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine); };
  Scene scene;
  const double eps = 0.3, mu = 0.5;
  scene.bodies.push_back(BodyDescription::plane(Vec3::UnitZ(), 0.0, eps, mu));
  scene.states.push_back(BodyState{});
  // Four walls 0.1 m thick around a 2 x 2 m floor, 1 m high
  const Vec3 wall_x(0.05, 1.1, 0.5), wall_y(1.1, 0.05, 0.5);
  const Vec3 wall_at[4] = {{1.05, 0, 0.5}, {-1.05, 0, 0.5}, {0, 1.05, 0.5}, {0, -1.05, 0.5}};
  for (int k = 0; k < 4; ++k) {
    scene.bodies.push_back(BodyDescription::fixedBox(k < 2 ? wall_x : wall_y, eps, mu));
    scene.states.push_back(at(wall_at[k]));
  }
  // Bodies on a 4 x 4 grid of cells 0.4 m apart, layer after layer upwards
  for (int i = 0; i < count; ++i) {
    const int cell = i % 16, layer = i / 16;
    const Vec3 x(-0.6 + 0.4 * (cell % 4), -0.6 + 0.4 * (cell / 4), 0.5 + 0.4 * layer);
    const double s = uniform(0.06, 0.12);
    scene.bodies.push_back(i % 2 == 0 ? BodyDescription::box(1.0, Vec3(s, uniform(0.06, 0.12), uniform(0.06, 0.12)), eps, mu)
                                      : BodyDescription::sphere(1.0, s, eps, mu));
    BodyState state = at(x, Vec3(uniform(-0.5, 0.5), uniform(-0.5, 0.5), 0.0));
    state.q = Quat(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)).normalized();
    scene.states.push_back(state);
  }
  return scene;
}

Scene shakenScene(const Scene& scene, std::uint64_t seed, double shift) {
  if (!(shift >= 0.0 && std::isfinite(shift))) {
    throw InvalidInput("shakenScene shift must be finite and >= 0, got " + std::to_string(shift));
  }
  Scene shaken = scene;
  if (seed == 0) return shaken;
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> uniform(-shift, shift);
  for (std::size_t i = 0; i < shaken.bodies.size() && i < shaken.states.size(); ++i) {
    if (shaken.bodies[i].fixed) continue;
    shaken.states[i].x.x() += uniform(engine);
    shaken.states[i].x.y() += uniform(engine);
  }
  return shaken;
}

}  // namespace physlab
