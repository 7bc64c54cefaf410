// Framework half of Lab 1's sections 5-7: parameters and their checks, the brute-force oracle of
// the neighbour search, the order parameter of a flock and the noise of the curl-noise flow.
// The algorithms (grid search, forces, stream function, velocity) are the student's.
#include <cmath>
#include <string>
#include <utility>

#include "physlab/curl_noise.hpp"
#include "physlab/error.hpp"
#include "physlab/neighbours.hpp"

namespace physlab {

void bruteForcePairs(ConstPoints x, double r, std::vector<NeighbourPair>& pairs, NeighbourStats& stats) {
  requirePositive(r, "bruteForcePairs radius r");
  requireFinite(x, "bruteForcePairs points x");
  pairs.clear();
  stats = NeighbourStats{};
  const double r2 = r * r;
  for (Index i = 0; i < x.cols(); ++i) {
    for (Index j = i + 1; j < x.cols(); ++j) {
      ++stats.distance_checks;
      if ((x.col(i) - x.col(j)).squaredNorm() <= r2) pairs.push_back({i, j});
    }
  }
}

double orderParameter(ConstPoints v) {
  Vec3 sum = Vec3::Zero();
  Index moving = 0;
  for (Index i = 0; i < v.cols(); ++i) {
    const double speed = v.col(i).norm();
    if (speed > 0.0) {
      sum += v.col(i) / speed;
      ++moving;
    }
  }
  return moving == 0 ? 0.0 : sum.norm() / static_cast<double>(moving);
}

CutoffLennardJones::CutoffLennardJones(double epsilon_, double sigma_, double cutoff_)
    : epsilon(epsilon_), sigma(sigma_), cutoff(cutoff_) {
  requirePositive(epsilon, "cut-off Lennard-Jones epsilon");
  requirePositive(sigma, "cut-off Lennard-Jones sigma");
  requirePositive(cutoff, "cut-off Lennard-Jones cutoff r_c");
}

Boids::Boids(double radius_, double separation_, double alignment_, double cohesion_)
    : radius(radius_), separation(separation_), alignment(alignment_), cohesion(cohesion_) {
  requirePositive(radius, "boids neighbour radius R");
  requireNonNegative(separation, "boids separation weight w_s");
  requireNonNegative(alignment, "boids alignment weight w_a");
  requireNonNegative(cohesion, "boids cohesion weight w_c");
}

CurlNoise::CurlNoise(std::vector<NoiseWave> waves_, const Vec3& centre_, double radius_, double ramp_width_,
                     double step_)
    : waves(std::move(waves_)), centre(centre_), radius(radius_), ramp_width(ramp_width_), step(step_) {
  for (std::size_t k = 0; k < waves.size(); ++k) {
    const NoiseWave& w = waves[k];
    if (!(std::isfinite(w.amplitude) && std::isfinite(w.phase) && std::isfinite(w.kappa.sum()))) {
      throw InvalidInput("curl noise wave " + std::to_string(k) + " has a non-finite amplitude, wave vector or phase");
    }
  }
  requireFinite(centre, "curl noise disc centre");
  requirePositive(radius, "curl noise disc radius R");
  requirePositive(ramp_width, "curl noise ramp width L");
  requirePositive(step, "curl noise finite-difference step e");
}

double CurlNoise::noise(const Vec3& p) const {
  double psi = 0.0;
  for (const NoiseWave& w : waves) psi += w.amplitude * std::sin(w.kappa.x() * p.x() + w.kappa.y() * p.y() + w.phase);
  return psi;
}

double CurlNoise::distance(const Vec3& p) const {
  return std::hypot(p.x() - centre.x(), p.y() - centre.y()) - radius;
}

}  // namespace physlab
