// Lab 6 scenes for tests and demos: a resting box, a plank on two supports, stacks, pyramids,
// a friction ramp and a heavy box on a light one.
#include <cmath>

#include "physlab/error.hpp"
#include "physlab/resting.hpp"

namespace physlab {

namespace {

constexpr double kCube = 0.1;  // half edge of the cubes [m]
// Stacked bodies overlap by a hair, so that round-off cannot open a gap and lose the contact
constexpr double kOverlap = 1e-6;

BodyState at(const Vec3& x, const Quat& q = Quat::Identity()) {
  BodyState s;
  s.x = x;
  s.q = q;
  return s;
}

Scene onGround(double mu = 0.5) {
  Scene scene;
  scene.bodies.push_back(BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.0, mu));
  scene.states.push_back(BodyState{});
  return scene;
}

void addCube(Scene& scene, double mass, const Vec3& x, double mu = 0.5) {
  scene.bodies.push_back(BodyDescription::box(mass, Vec3::Constant(kCube), 0.0, mu));
  scene.states.push_back(at(x));
}

}  // namespace

Settings restingWorldSettings() {
  Settings settings;
  // The velocity-level solver corrects positions itself (Baumgarte); the acceleration level
  // shows what happens without
  settings.position_correction = 0.0;
  return settings;
}

Scene restingBox(double yaw) {
  requireFinite(Vec3(yaw, 0.0, 0.0), "resting box yaw");
  const Vec3 half(0.3, 0.2, 0.1);
  Scene scene = onGround(0.0);
  scene.bodies.push_back(BodyDescription::box(2.0, half, 0.0, 0.0));
  scene.states.push_back(at(Vec3(0.0, 0.0, half.z() - kOverlap), Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()))));
  return scene;
}

Scene plankOnTwoSupports(double a, double b) {
  if (!(a > 0.0 && a <= 0.9 && b > 0.0 && b <= 0.9)) {
    throw InvalidInput("plank supports must be in (0, 0.9] m from the centre, got a = " + std::to_string(a) +
                       ", b = " + std::to_string(b));
  }
  const double r = 0.1;
  const Vec3 half(1.0, 0.1, 0.05);
  Scene scene;
  scene.bodies.push_back(BodyDescription::box(1.0, half, 0.0, 0.0));
  scene.states.push_back(at(Vec3(0.0, 0.0, 2.0 * r + half.z() - kOverlap)));
  for (const double x : {-a, b}) {
    BodyDescription support = BodyDescription::sphere(1.0, r, 0.0, 0.0);
    support.fixed = true;
    scene.bodies.push_back(support);
    scene.states.push_back(at(Vec3(x, 0.0, r)));
  }
  return scene;
}

Scene cubeStack(int n) {
  if (n < 1) throw InvalidInput("box stack needs at least 1 box, got " + std::to_string(n));
  Scene scene = onGround();
  for (int i = 0; i < n; ++i) addCube(scene, 1.0, Vec3(0.0, 0.0, (2 * i + 1) * (kCube - kOverlap)));
  return scene;
}

Scene cubePyramid(int rows) {
  if (rows < 1) throw InvalidInput("box pyramid needs at least 1 row, got " + std::to_string(rows));
  const double pitch = 2.0 * kCube + 0.02;
  Scene scene = onGround();
  for (int row = 0; row < rows; ++row) {
    const int count = rows - row;
    for (int i = 0; i < count; ++i) {
      const double x = (i - 0.5 * (count - 1)) * pitch;
      addCube(scene, 1.0, Vec3(x, 0.0, (2 * row + 1) * (kCube - kOverlap)));
    }
  }
  return scene;
}

Scene frictionRamp(double theta, const std::vector<double>& mu) {
  if (!(theta >= 0.0 && theta < M_PI / 2)) throw InvalidInput("friction ramp angle theta must be in [0, pi/2)");
  if (mu.empty()) throw InvalidInput("friction ramp needs at least one block");
  // The slope rises along +x: its normal leans back towards -x
  const Quat tilt(Eigen::AngleAxisd(-theta, Vec3::UnitY()));
  const Vec3 normal = tilt * Vec3::UnitZ();
  Scene scene;
  scene.bodies.push_back(BodyDescription::plane(normal, 0.0, 0.0, 1.0));
  scene.states.push_back(BodyState{});
  for (std::size_t i = 0; i < mu.size(); ++i) {
    requireNonNegative(mu[i], "friction ramp mu of block " + std::to_string(i));
    scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(kCube), 0.0, mu[i] * mu[i]));
    const Vec3 along_y(0.0, 0.5 * static_cast<double>(i), 0.0);
    scene.states.push_back(at(along_y + (kCube - kOverlap) * normal, tilt));
  }
  return scene;
}

Scene heavyOnLight(double ratio) {
  requirePositive(ratio, "heavy-on-light mass ratio");
  Scene scene = onGround();
  addCube(scene, 1.0, Vec3(0.0, 0.0, kCube - kOverlap));
  addCube(scene, ratio, Vec3(0.0, 0.0, 3.0 * (kCube - kOverlap)));
  return scene;
}

}  // namespace physlab
