// Lab 1 graded tests of section 6: the boids force on hand-built neighbourhoods (one neighbour,
// a symmetric ring, none, one exactly at the radius) and on a seeded flock against the formula
// summed over all pairs here.
#include "physlab/neighbours.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;

namespace {

// The boids force of every particle, by the header's formula over all pairs (O(N^2)), written here.
Mat3X boidOracle(const Mat3X& x, const Mat3X& v, double R, double ws, double wa, double wc) {
  const Index n = x.cols();
  Mat3X F = Mat3X::Zero(3, n);
  for (Index i = 0; i < n; ++i) {
    Vec3 push = Vec3::Zero(), vsum = Vec3::Zero(), xsum = Vec3::Zero();
    int count = 0;
    for (Index j = 0; j < n; ++j) {
      const Vec3 d = x.col(i) - x.col(j);
      if (j == i || d.squaredNorm() > R * R) continue;
      ++count;
      if (d.squaredNorm() > 0.0) push += d / d.squaredNorm();
      vsum += v.col(j);
      xsum += x.col(j);
    }
    if (count > 0) F.col(i) = ws * push + wa * (vsum / count - v.col(i)) + wc * (xsum / count - x.col(i));
  }
  return F;
}

// The student's boids force, added to a buffer that holds `start`.
Mat3X boidForce(const Boids& boids, const Mat3X& x, const Mat3X& v, const Mat3X& start) {
  const VecX m = VecX::Ones(x.cols());
  Mat3X F = start;
  boids.accumulate({ConstPoints(x.data(), 3, x.cols()), ConstPoints(v.data(), 3, v.cols()), m},
                   Points(F.data(), 3, F.cols()));
  return F;
}

Mat3X boidForce(const Boids& boids, const Mat3X& x, const Mat3X& v) {
  return boidForce(boids, x, v, Mat3X::Zero(3, x.cols()));
}

}  // namespace

TEST_CASE("boids: one neighbour: separation, alignment and cohesion by hand, each weight alone, and the weights add linearly", "[lab01][pts=2][sec=6]") {
  // Particles 0 and 1 are neighbours (distance < R); particle 2 is far from both.
  const double R = uniform(0.8, 1.2);
  Mat3X x(3, 3), v = randomPoints(3, 1.0);
  x.col(0) = randomVec3(1.0);
  const Vec3 d = uniform(0.2, 0.7) * R * randomRotation().col(0);  // x_0 - x_1
  x.col(1) = x.col(0) - d;
  x.col(2) = x.col(0) + Vec3(5.0, 5.0, 5.0);
  const double ws = uniform(0.5, 2.0), wa = uniform(0.5, 2.0), wc = uniform(0.5, 2.0);
  // Each rule alone: on 0, w_s d / |d|^2, w_a (v_1 - v_0), w_c (x_1 - x_0); on 1 mirrored.
  const std::vector<std::pair<Vec3, Vec3>> by_hand{
      {ws * d / d.squaredNorm(), -ws * d / d.squaredNorm()},
      {wa * (v.col(1) - v.col(0)), wa * (v.col(0) - v.col(1))},
      {wc * (x.col(1) - x.col(0)), wc * (x.col(0) - x.col(1))}};
  const std::vector<Boids> alone{Boids(R, ws, 0, 0), Boids(R, 0, wa, 0), Boids(R, 0, 0, wc)};
  Mat3X sum = Mat3X::Zero(3, 3);
  for (std::size_t k = 0; k < 3; ++k) {
    CAPTURE(k);
    const Mat3X F = boidForce(alone[k], x, v);
    // The same few operations: round-off of O(1) numbers.
    CHECK((F.col(0) - by_hand[k].first).norm() < 1e-12 * (1.0 + by_hand[k].first.norm()));
    CHECK((F.col(1) - by_hand[k].second).norm() < 1e-12 * (1.0 + by_hand[k].second.norm()));
    CHECK(F.col(2).norm() == 0.0);  // no neighbour: exactly nothing
    sum += F;
  }
  // All three weights at once is the sum of the three alone; doubling every weight doubles it.
  const Mat3X all = boidForce(Boids(R, ws, wa, wc), x, v);
  CHECK((all - sum).norm() < 1e-12 * (1.0 + sum.norm()));
  CHECK((boidForce(Boids(R, 2 * ws, 2 * wa, 2 * wc), x, v) - 2.0 * all).norm() < 1e-12 * (1.0 + all.norm()));
}

TEST_CASE("boids: a symmetric ring: separation and cohesion cancel at its centre, alignment pulls toward the ring's mean velocity, ring members are pushed outward", "[lab01][pts=1][sec=6]") {
  // Particle 0 at c, k particles evenly on a circle of radius rho around it (in a random plane);
  // neighbours of the centre (rho < R), and each ring member is a neighbour of the centre and of
  // its two ring neighbours only (chord 2 rho sin(pi/k) <= R < the next chord).
  const int k = 8;
  const double rho = 1.0, R = 1.2;  // chords: 0.765 (neighbours), 1.414 and more (not)
  const Mat3 rot = randomRotation();
  const Vec3 c = randomVec3(2.0);
  Mat3X x(3, k + 1), v(3, k + 1);
  x.col(0) = c;
  v.col(0) = randomVec3(1.0);
  Vec3 mean_v = Vec3::Zero();
  for (int j = 1; j <= k; ++j) {
    const double a = 2.0 * M_PI * (j - 1) / k;
    x.col(j) = c + rho * rot * Vec3(std::cos(a), std::sin(a), 0.0);
    v.col(j) = randomVec3(1.0);
    mean_v += v.col(j) / k;
  }
  const double ws = uniform(0.5, 2.0), wa = uniform(0.5, 2.0), wc = uniform(0.5, 2.0);
  const Mat3X F = boidForce(Boids(R, ws, wa, wc), x, v);
  // At the centre only alignment remains: w_a (mean ring velocity - v_0).
  CHECK((F.col(0) - wa * (mean_v - v.col(0))).norm() < 1e-12);  // cancellation of O(1) terms
  // With equal velocities alignment vanishes too; then a ring member's separation from the centre
  // and its two neighbours, and its cohesion toward their centroid, all lie along its radius:
  // the force is radial. Separation from the centre is w_s / rho outward, cohesion toward the
  // centroid of {c, both neighbours} pulls inward.
  const Mat3X same_v = Mat3X::Constant(3, k + 1, 0.3);
  const Mat3X G = boidForce(Boids(R, ws, wa, wc), x, same_v);
  CHECK(G.col(0).norm() < 1e-12);
  for (int j = 1; j <= k; ++j) {
    CAPTURE(j);
    const Vec3 out = (x.col(j) - c).normalized();
    // The exact radial value: the formula for this geometry, written here.
    const double half = M_PI / k, chord = 2.0 * rho * std::sin(half);
    // Separation from each ring neighbour: (x_j - x_n) / chord^2, radial part sin(half) / chord each.
    const double separation = ws * (1.0 / rho + 2.0 * std::sin(half) / chord);
    // Cohesion: centroid of {c, x_{j-1}, x_{j+1}} minus x_j, radial part (2 rho cos(2 half) - 3 rho) / 3.
    const double cohesion = wc * (2.0 * rho * std::cos(2.0 * half) - 3.0 * rho) / 3.0;
    CHECK((G.col(j) - (separation + cohesion) * out).norm() < 1e-12 * (1.0 + G.col(j).norm()));
  }
}

TEST_CASE("boids: an empty neighbourhood gives no force, a neighbour exactly at R counts, one just beyond does not; no potential", "[lab01][pts=1][sec=6]") {
  const double R = 0.5;  // exact in binary, so the positions below are exactly R apart
  const Boids boids(R, 1.5, 0.75, 2.0);
  Mat3X x(3, 2);
  const Mat3X v = randomPoints(2, 1.0);
  const Mat3X start = randomPoints(2, 1.0);  // forces accumulate onto what the buffer holds
  x.col(0) = Vec3(0.25, -1.0, 2.0);
  x.col(1) = x.col(0) + Vec3(0.0, R, 0.0);
  const Mat3X at_R = boidForce(boids, x, v, start) - start;
  const Mat3X expected = boidOracle(x, v, R, 1.5, 0.75, 2.0);
  CHECK(expected.norm() > 0.1);  // exactly at R they are neighbours
  CHECK((at_R - expected).norm() < 1e-12);
  x.col(1) = x.col(0) + Vec3(0.0, R * (1.0 + 1e-12), 0.0);
  CHECK((boidForce(boids, x, v, start) - start).norm() == 0.0);  // an empty neighbourhood: nothing added
  CHECK(boids.potential({ConstPoints(x.data(), 3, 2), ConstPoints(v.data(), 3, 2), VecX::Ones(2)}) == 0.0);
}

TEST_CASE("boids: a seeded flock with coincident members against the formula summed over all pairs", "[lab01][pts=2][sec=6]") {
  const Index n = 300;
  Mat3X x = randomPoints(n, 1.0), v = randomPoints(n, 1.0);
  x.col(7) = x.col(3);  // coincident: a neighbour for the means, no separation
  x.col(11) = x.col(3);
  const double R = uniform(0.2, 0.4), ws = uniform(0.0, 0.1), wa = uniform(0.0, 2.0), wc = uniform(0.0, 2.0);
  const Mat3X expected = boidOracle(x, v, R, ws, wa, wc);
  const Mat3X F = boidForce(Boids(R, ws, wa, wc), x, v);
  CHECK(std::isfinite(F.sum()));
  // The same sums in another order: round-off relative to the forces' size.
  CHECK((F - expected).norm() < 1e-12 * expected.norm());
}
