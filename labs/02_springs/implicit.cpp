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
  // TODO(student): springJacobian(..., JacobianForm::Definite); Eigen::Triplet entries for the four 3x3 blocks, skipping pinned rows/columns.
  // Add the masses and the drag on the diagonal; a pinned particle gets the identity
  // TODO(student): diagonal m_i + h drag for free particles, 1 for pinned; then A.setFromTriplets().
  // Form b = h (f + h (df/dx) v), zero for pinned particles
  // TODO(student): sys.forces(X) gives f.
  // Solve A dv = b with the chosen solver
  // TODO(student): Eigen::ConjugateGradient<..., Eigen::Lower | Eigen::Upper> or Eigen::SimplicialLDLT; check info().
  // Update the velocities, then move with the new velocities
  // TODO(student): v += dv, then x += h v; return the solver statistics.
  notImplemented("implicitEulerUpdate", "Lab 2 handout, section 3", sys, X, h, settings);
}

}  // namespace physlab
