// Lab 1, section 6: Reynolds' boids (separation, alignment, cohesion) as a force.
#include "physlab/error.hpp"
#include "physlab/neighbours.hpp"

namespace physlab {

// ---- boids ----------------------------------------------------------------------------------

void Boids::accumulate(const ParticleView& s, Points F) const {
  // Find the neighbour pairs within R
  // TODO(student): neighbourPairs(s.x, radius, pairs_, grid_, stats); each pair is a neighbour of both.
  // Sum over each particle's neighbours: separation push, velocities, positions and the count
  // TODO(student): push_, velocity_sum_, position_sum_ (3 x n) and count_ (n) are yours to size and zero;
  // TODO(student): a neighbour at the same position adds to the count and sums but no push.
  // Steer each particle that has neighbours: apart, toward their mean velocity and their centroid
  // TODO(student): F_i += w_s push_i + w_a (mean v - v_i) + w_c (centroid - x_i); nothing when count is 0.
  notImplemented("Boids::accumulate", "Lab 1 handout, section 6", s, F);
}

double Boids::potential(const ParticleView& s) const {
  // Steering is not conservative: no potential
  // TODO(student): return 0.
  notImplemented("Boids::potential", "Lab 1 handout, section 6", s);
}

}  // namespace physlab
