// Lab 1, section 6: Reynolds' boids (separation, alignment, cohesion) as a force.
#include "physlab/error.hpp"
#include "physlab/neighbours.hpp"

namespace physlab {

// ---- boids ----------------------------------------------------------------------------------

void Boids::accumulate(const ParticleView& s, Points F) const {
  // Find the neighbour pairs within R
  NeighbourStats stats;
  neighbourPairs(s.x, radius, pairs_, grid_, stats);
  // Sum over each particle's neighbours: separation push, velocities, positions and the count
  const Index n = s.x.cols();
  push_.setZero(3, n);
  velocity_sum_.setZero(3, n);
  position_sum_.setZero(3, n);
  count_.setZero(n);
  for (const NeighbourPair& p : pairs_) {
    const Vec3 d = s.x.col(p.i) - s.x.col(p.j);
    const double d2 = d.squaredNorm();
    if (d2 > 0.0) {
      push_.col(p.i) += d / d2;
      push_.col(p.j) -= d / d2;
    }
    velocity_sum_.col(p.i) += s.v.col(p.j);
    velocity_sum_.col(p.j) += s.v.col(p.i);
    position_sum_.col(p.i) += s.x.col(p.j);
    position_sum_.col(p.j) += s.x.col(p.i);
    count_[p.i] += 1.0;
    count_[p.j] += 1.0;
  }
  // Steer each particle that has neighbours: apart, toward their mean velocity and their centroid
  for (Index i = 0; i < n; ++i) {
    if (count_[i] == 0.0) continue;
    F.col(i) += separation * push_.col(i) + alignment * (velocity_sum_.col(i) / count_[i] - s.v.col(i)) +
                cohesion * (position_sum_.col(i) / count_[i] - s.x.col(i));
  }
}

double Boids::potential(const ParticleView& /*s*/) const {
  // Steering is not conservative: no potential
  return 0.0;
}

}  // namespace physlab
