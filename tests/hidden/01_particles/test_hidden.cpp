// Lab 1 hidden tests (instructor only, shown after grades are published).
#include <complex>

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
