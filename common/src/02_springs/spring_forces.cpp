// Lab 2 framework: a spring network's total force, summed from the students' springForce() and
// groundForce().
//
// In a grade this file runs in the worker, beside the submitted functions it calls (IN_WORKER in
// CMakeLists.txt; docs/grading.md, "Where submitted code runs"): one evaluation calls
// springForce() once per spring, some 10^5 times a second of a cloth, which across the wire would
// cost a pipe round trip each.
#include "physlab/error.hpp"
#include "physlab/particles.hpp"
#include "physlab/springs.hpp"

namespace physlab {

void SpringSystem::forces(const VecX& X, VecX& f) const {
  requireSize(X.size(), size(), "spring network state");
  const ConstPoints x = positions(X), v = velocities(X);
  f.setZero(positionSize());
  Points F(f.data(), 3, count());
  for (const Spring& s : network_.springs) {
    const Vec3 fa = springForce(s, x.col(s.a), x.col(s.b), v.col(s.a), v.col(s.b));
    F.col(s.a) += fa;
    F.col(s.b) -= fa;
  }
  const bool ground_on = network_.ground.stiffness > 0.0;
  for (Index i = 0; i < count(); ++i) {
    if (inverse_masses_[i] == 0.0) continue;  // pinned: held in place whatever acts on it
    F.col(i) += network_.masses[i] * network_.gravity - network_.drag * v.col(i);
    if (ground_on) F.col(i) += groundForce(network_.ground, x.col(i), v.col(i));
  }
}

}  // namespace physlab
