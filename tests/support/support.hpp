// Helpers shared by the graded tests: seeded random inputs and oracles that do not depend on
// any student code.
#pragma once

#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "physlab/integrators.hpp"
#include "physlab/particles.hpp"

namespace physlab::test {

/// Random engine for the running test case, seeded from Catch's --rng-seed and the test's
/// name: the grader draws a fresh seed per run (printed in the report), so expected values
/// cannot be memorised, while a given seed reproduces a failure exactly.
std::mt19937_64& rng();
/// Uniform number in [lo, hi).
double uniform(double lo, double hi);
/// Vector with entries uniform in [-scale, scale).
Vec3 randomVec3(double scale);
/// n points (3 x n) with entries uniform in [-scale, scale).
Mat3X randomPoints(Index n, double scale);
/// A random rotation matrix (uniform enough for test inputs).
Mat3 randomRotation();
/// The shortest rotation taking the direction of `from` to that of `to` (a half turn about a
/// perpendicular axis when they are opposite). Eigen's Quaternion::FromTwoVectors does the same
/// through an SVD whose templates cost 9 s of compile time in every file that calls it.
Quat rotationTaking(const Vec3& from, const Vec3& to);

/// Runs `steps` steps of `method` on `X` in place, calling `observe(n, X)` after each step.
void run(Method method, const System& sys, VecX& X, double h, long steps,
         const std::function<void(long, const VecX&)>& observe = {});

/// Classical RK4 written apart from the student's code: the oracle for trajectories.
void oracleRK4(const System& sys, VecX& X, double h, long steps);

/// A particle system whose derivative is computed here from the forces, independently of the
/// student's ParticleSystem::computeVelocityRate: force tests depend on the force alone.
class OracleParticles final : public System {
 public:
  OracleParticles(VecX masses, std::vector<std::shared_ptr<const Force>> forces);
  Index positionSize() const override { return 3 * masses_.size(); }
  Index velocitySize() const override { return 3 * masses_.size(); }
  std::string name() const override { return "oracle particles"; }
  /// Total force on each particle, 3 x n.
  Mat3X force(const VecX& X) const;
  /// Linear momentum sum m v.
  Vec3 momentum(const VecX& X) const;

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override;
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override;

 private:
  VecX masses_;
  std::vector<std::shared_ptr<const Force>> forces_;
};

/// Relative difference |a - b| / max(|a|, |b|, tiny).
double relativeError(double a, double b);

}  // namespace physlab::test
