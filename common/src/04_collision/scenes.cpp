// Lab 4 scenes for tests, demos and benchmarks: a random soup, a stack, a pyramid, and a fast
// small body before a thin wall.
#include <random>

#include "physlab/collision.hpp"
#include "physlab/error.hpp"

namespace physlab {

std::vector<CollisionBody> shapeSoup(int count, double size, std::uint64_t seed) {
  if (count < 0) throw InvalidInput("shape soup count must not be negative");
  requirePositive(size, "shape soup box size");
  std::mt19937_64 engine(seed);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine); };
  auto vec = [&](double scale) { return Vec3(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)); };
  std::vector<CollisionBody> soup;
  soup.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double s = uniform(0.1, 0.5);
    Pose pose;
    pose.x = vec(0.5 * size);
    pose.q = Quat(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)).normalized();
    const Motion motion{vec(2.0 / std::sqrt(3.0)), vec(3.0 / std::sqrt(3.0))};
    switch (i % 4) {
      case 0:
        soup.push_back({Sphere(s), pose, motion});
        break;
      case 1:
        soup.push_back({Box(Vec3(s, uniform(0.1, 0.5), uniform(0.1, 0.5))), pose, motion});
        break;
      case 2:
        soup.push_back({Capsule(0.5 * s, uniform(0.1, 0.5)), pose, motion});
        break;
      default: {
        // A tetrahedron around its centroid, with corners at least 0.1 s from the others' plane.
        const Vec3 a(s, 0, -s / std::sqrt(2.0)), b(-s, 0, -s / std::sqrt(2.0)), c(0, s, s / std::sqrt(2.0)),
            d(0, -s, s / std::sqrt(2.0));
        soup.push_back({ConvexPolyhedron::tetrahedron(a + vec(0.2 * s), b + vec(0.2 * s), c + vec(0.2 * s), d),
                        pose, motion});
      }
    }
  }
  return soup;
}

std::vector<CollisionBody> boxStack(int count, double overlap) {
  if (count < 0) throw InvalidInput("box stack count must not be negative");
  requireNonNegative(overlap, "box stack overlap");
  std::vector<CollisionBody> stack;
  stack.push_back({Plane(Vec3::UnitZ(), 0.0), Pose{}, Motion{}});
  for (int i = 0; i < count; ++i) {
    Pose pose;
    pose.x = Vec3(0.0, 0.0, 0.5 - overlap + i * (1.0 - overlap));
    stack.push_back({Box(Vec3::Constant(0.5)), pose, Motion{}});
  }
  return stack;
}

std::vector<CollisionBody> boxPyramid(int rows) {
  if (rows < 0) throw InvalidInput("box pyramid rows must not be negative");
  std::vector<CollisionBody> pyramid;
  pyramid.push_back({Plane(Vec3::UnitZ(), 0.0), Pose{}, Motion{}});
  for (int r = 0; r < rows; ++r) {
    const int n = rows - r;
    for (int k = 0; k < n; ++k) {
      Pose pose;
      pose.x = Vec3(k - 0.5 * (n - 1), 0.0, 0.5 + r);
      pyramid.push_back({Box(Vec3::Constant(0.5)), pose, Motion{}});
    }
  }
  return pyramid;
}

std::vector<CollisionBody> bulletAndWall(double speed) {
  requirePositive(speed, "bullet speed");
  Pose bullet;
  bullet.x = Vec3(-1.0, 0.0, 0.0);
  return {{Box(Vec3(0.01, 1.0, 1.0)), Pose{}, Motion{}}, {Sphere(0.05), bullet, Motion{Vec3(speed, 0.0, 0.0), Vec3::Zero()}}};
}

}  // namespace physlab
