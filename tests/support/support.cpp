#include "support.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>

namespace physlab::test {

std::mt19937_64& rng() {
  static std::mt19937_64 engine;
  static std::string seeded_for;
  const std::string name = Catch::getResultCapture().getCurrentTestName();
  if (name != seeded_for) {
    seeded_for = name;
    engine.seed(Catch::rngSeed() ^ std::hash<std::string>{}(name));
    // The seed sweep (tools/sweep.py) runs each test once with PHYSLAB_SEED_PROBE naming a file:
    // the tests that reach this line are the ones a seed changes, and it runs only those again
    if (const char* probe = std::getenv("PHYSLAB_SEED_PROBE")) std::ofstream(probe, std::ios::app) << name << '\n';
  }
  return engine;
}

double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng()); }

Vec3 randomVec3(double scale) {
  return Vec3(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale));
}

Mat3X randomPoints(Index n, double scale) {
  Mat3X p(3, n);
  for (Index i = 0; i < n; ++i) p.col(i) = randomVec3(scale);
  return p;
}

Mat3 randomRotation() {
  Quat q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
  q.normalize();
  return q.toRotationMatrix();
}

Quat rotationTaking(const Vec3& from, const Vec3& to) {
  const Vec3 a = from.normalized(), b = to.normalized();
  const Vec3 axis = a.cross(b);
  const double sine = axis.norm(), cosine = a.dot(b);
  if (sine > 1e-12) return Quat(Eigen::AngleAxisd(std::atan2(sine, cosine), axis / sine));
  if (cosine > 0.0) return Quat::Identity();
  // Opposite directions: any axis perpendicular to a will do
  return Quat(Eigen::AngleAxisd(M_PI, a.unitOrthogonal()));
}

void run(Method method, const System& sys, VecX& X, double h, long steps,
         const std::function<void(long, const VecX&)>& observe) {
  Integrator integrator(method);
  for (long n = 1; n <= steps; ++n) {
    integrator.step(sys, X, h);
    if (observe) observe(n, X);
  }
}

void oracleRK4(const System& sys, VecX& X, double h, long steps) {
  VecX a(sys.size()), b(sys.size()), c(sys.size()), d(sys.size());
  for (long n = 0; n < steps; ++n) {
    sys.derivative(X, a);
    sys.derivative(VecX(X + 0.5 * h * a), b);
    sys.derivative(VecX(X + 0.5 * h * b), c);
    sys.derivative(VecX(X + h * c), d);
    X += h / 6.0 * (a + 2.0 * (b + c) + d);
  }
}

OracleParticles::OracleParticles(VecX masses, std::vector<std::shared_ptr<const Force>> forces)
    : masses_(std::move(masses)), forces_(std::move(forces)) {}

Mat3X OracleParticles::force(const VecX& X) const {
  Mat3X F = Mat3X::Zero(3, masses_.size());
  const ParticleView s{positions(X), velocities(X), masses_};
  for (const auto& f : forces_) f->accumulate(s, Points(F.data(), 3, F.cols()));
  return F;
}

Vec3 OracleParticles::momentum(const VecX& X) const {
  return velocities(X) * masses_;
}

void OracleParticles::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  qdot = X.tail(velocitySize());
}

void OracleParticles::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  const Mat3X F = force(X);
  for (Index i = 0; i < masses_.size(); ++i) pdot.segment<3>(3 * i) = F.col(i) / masses_[i];
}

double relativeError(double a, double b) {
  const double scale = std::max({std::abs(a), std::abs(b), 1e-300});
  return std::abs(a - b) / scale;
}

}  // namespace physlab::test
