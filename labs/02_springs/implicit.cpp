// Lab 2, section 3: implicit Euler for spring networks (Baraff & Witkin 1998).
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#include <vector>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"
#include "physlab/springs.hpp"

namespace physlab {

ImplicitStats implicitEulerUpdate(const SpringSystem& sys, VecX& X, double h,
                                  const ImplicitSettings& settings) {
  // Assemble A = M - h df/dv - h^2 df/dx and the product (df/dx) v, spring by spring
  // TODO(student): assemble A = M - h df/dv - h^2 df/dx and the product (df/dx) v, spring by spring.
  // Add the masses and the drag on the diagonal; a pinned particle gets the identity
  // TODO(student): add the masses and the drag on the diagonal; a pinned particle gets the identity.
  // Form b = h (f + h (df/dx) v), zero for pinned particles
  // TODO(student): form b = h (f + h (df/dx) v), zero for pinned particles.
  // Solve A dv = b with the chosen solver
  // TODO(student): solve A dv = b with the chosen solver.
  // Update the velocities, then move with the new velocities
  // TODO(student): update the velocities, then move with the new velocities.
  notImplemented("implicitEulerUpdate", "Lab 2 handout, section 3", sys, X, h, settings);
}

}  // namespace physlab
