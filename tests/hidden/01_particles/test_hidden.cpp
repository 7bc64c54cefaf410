// Lab 1 hidden tests (instructor only, shown after grades are published).
#include <algorithm>
#include <complex>

#include "physlab/curl_noise.hpp"
#include "physlab/neighbours.hpp"
#include "physlab/scenes.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

TEST_CASE("hidden: RK4 on the oscillator equals its stability polynomial applied N times", "[lab01][pts=2][hidden][sec=3]") {
  const HarmonicOscillator osc(uniform(0.5, 2.0));
  const double z = uniform(0.05, 0.5);  // h omega
  const long steps = 1 + static_cast<long>(uniform(10.0, 200.0));
  VecX X = Eigen::Vector2d(uniform(-1.0, 1.0), uniform(-1.0, 1.0));
  // With u = x + i v / omega the oscillator is u' = -i omega u, and one RK4 step multiplies u by
  // R(w) = 1 + w + w^2/2 + w^3/6 + w^4/24 at w = -i h omega: exactly, not approximately.
  const std::complex<double> w(0.0, -z);
  const std::complex<double> R = 1.0 + w + w * w / 2.0 + w * w * w / 6.0 + w * w * w * w / 24.0;
  const std::complex<double> u = std::pow(R, static_cast<int>(steps)) *
                                 std::complex<double>(X[0], X[1] / osc.omega);
  run(Method::RK4, osc, X, z / osc.omega, steps);
  // Round-off only: about 1e-16 per step over at most 200 steps.
  CHECK(X[0] == Approx(u.real()).margin(1e-12));
  CHECK(X[1] / osc.omega == Approx(u.imag()).margin(1e-12));
}

TEST_CASE("hidden: a damped spring dissipates power kd (l_dot . u)^2", "[lab01][pts=2][hidden][sec=1]") {
  Mat3X x(3, 2), v(3, 2);
  x.col(0) = randomVec3(1.0);
  x.col(1) = x.col(0) + Vec3(0.5, 0.0, 0.0) + randomVec3(0.3);
  v.col(0) = randomVec3(1.0);
  v.col(1) = randomVec3(1.0);
  const VecX m = VecX::Ones(2);
  const double kd = uniform(0.5, 3.0);
  const DampedSpring spring(0, 1, uniform(0.2, 0.8), uniform(5.0, 50.0), kd);
  const ParticleView s{ConstPoints(x.data(), 3, 2), ConstPoints(v.data(), 3, 2), m};
  Mat3X F = Mat3X::Zero(3, 2);
  spring.accumulate(s, Points(F.data(), 3, 2));
  const double power = F.col(0).dot(v.col(0)) + F.col(1).dot(v.col(1));
  // dU/dt along the motion by a central difference in time (error O(dt^2) ~ 1e-10).
  const double dt = 1e-5;
  const Mat3X xp = x + dt * v, xm = x - dt * v;
  const double dU_dt =
      (spring.potential({ConstPoints(xp.data(), 3, 2), ConstPoints(v.data(), 3, 2), m}) -
       spring.potential({ConstPoints(xm.data(), 3, 2), ConstPoints(v.data(), 3, 2), m})) / (2 * dt);
  const Vec3 u = (x.col(0) - x.col(1)).normalized();
  const double l_dot_u = (v.col(0) - v.col(1)).dot(u);
  // The elastic part exchanges energy with U; only the damping part removes it. The elastic
  // power and dU/dt cancel, so the difference quotient's error scales with them, not with the
  // (possibly tiny) dissipation: 1e-8 of their size, far below a wrong damping's O(kd |v|^2).
  CHECK(power + dU_dt ==
        Approx(-kd * l_dot_u * l_dot_u).epsilon(1e-6).margin(1e-8 * (std::abs(power) + std::abs(dU_dt))));
}

TEST_CASE("hidden: a cubic lattice of spacing r, every point on cell borders: exactly the 3 n^2 (n - 1) axis pairs", "[lab01][pts=2][hidden][sec=5]") {
  // n^3 points at integer multiples of r = 1/4 (exact), shuffled: each point's neighbours are the
  // axis neighbours exactly r away; the diagonal ones, sqrt(2) r away, are not.
  const int n = 8;
  const double r = 0.25;
  std::vector<Vec3> lattice;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      for (int c = 0; c < n; ++c) lattice.push_back(r * Vec3(a, b, c) + Vec3(1.0, -2.0, 0.5));
    }
  }
  std::shuffle(lattice.begin(), lattice.end(), rng());
  Mat3X x(3, n * n * n);
  for (Index i = 0; i < x.cols(); ++i) x.col(i) = lattice[static_cast<std::size_t>(i)];
  std::vector<NeighbourPair> pairs;
  NeighbourGrid grid;
  NeighbourStats stats;
  neighbourPairs(ConstPoints(x.data(), 3, x.cols()), r, pairs, grid, stats);
  CHECK(pairs.size() == static_cast<std::size_t>(3 * n * n * (n - 1)));
  bool ordered = true, exact = true;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    exact &= pairs[k].i < pairs[k].j && (x.col(pairs[k].i) - x.col(pairs[k].j)).squaredNorm() == r * r;
    if (k > 0) ordered &= pairs[k - 1].i < pairs[k].i || (pairs[k - 1].i == pairs[k].i && pairs[k - 1].j < pairs[k].j);
  }
  CHECK(exact);
  CHECK(ordered);
}

TEST_CASE("hidden: boids are Galilean invariant: a common shift of every position and every velocity changes no force", "[lab01][pts=2][hidden][sec=6]") {
  const Index n = 120;
  const Mat3X x = randomPoints(n, 1.0), v = randomPoints(n, 1.0);
  const Boids boids(uniform(0.3, 0.5), uniform(0.01, 0.1), uniform(0.5, 2.0), uniform(0.5, 2.0));
  const VecX m = VecX::Ones(n);
  // The shifted coordinates round by an ulp of 8 (2e-15): only a pair that close to R could change
  // neighbourhood, which a seeded cloud essentially never has.
  const Mat3X y = x.colwise() + Vec3(4.0, -8.0, 2.0), w = v.colwise() + randomVec3(3.0);
  Mat3X F = Mat3X::Zero(3, n), G = Mat3X::Zero(3, n);
  boids.accumulate({ConstPoints(x.data(), 3, n), ConstPoints(v.data(), 3, n), m}, Points(F.data(), 3, n));
  boids.accumulate({ConstPoints(y.data(), 3, n), ConstPoints(w.data(), 3, n), m}, Points(G.data(), 3, n));
  REQUIRE(F.norm() > 0.1);
  // Only the rounding of the shifted coordinates differs: 1e-15 relative, magnified by the sums.
  CHECK((F - G).norm() < 1e-9 * F.norm());
}

TEST_CASE("hidden: a curl-noise tracer keeps its stream function: psi along an RK4 path stays at its start", "[lab01][pts=2][hidden][sec=7]") {
  std::vector<NoiseWave> waves;
  for (int k = 0; k < 3; ++k) {
    const double angle = uniform(0.0, 2.0 * M_PI);
    waves.push_back({uniform(0.05, 0.2), uniform(1.0, 3.0) * Eigen::Vector2d(std::cos(angle), std::sin(angle)), uniform(0.0, 6.0)});
  }
  const CurlNoise field(waves, Vec3::Zero(), 0.5, 0.4, 1e-4);
  Vec3 p(uniform(0.7, 1.0), uniform(-1.0, 1.0), 0.0);
  const double psi0 = streamFunction(field, p);
  double worst = 0.0;
  const double h = 0.005;
  for (int n = 0; n < 2000; ++n) {
    const Vec3 k1 = curlNoiseVelocity(field, p);
    const Vec3 k2 = curlNoiseVelocity(field, p + 0.5 * h * k1);
    const Vec3 k3 = curlNoiseVelocity(field, p + 0.5 * h * k2);
    const Vec3 k4 = curlNoiseVelocity(field, p + h * k3);
    p += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    worst = std::max(worst, std::abs(streamFunction(field, p) - psi0));
  }
  // psi is constant along the exact flow; RK4's O(h^4) error and the O(e^2) differences leave
  // ~1e-8 over the path, far below psi's own variation (~0.1 across the domain).
  CHECK(worst < 1e-6);
}
