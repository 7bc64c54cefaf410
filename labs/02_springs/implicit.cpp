// Lab 2, section 3: implicit Euler for spring networks (Baraff & Witkin 1998).
#include <string>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"
#include "physlab/springs.hpp"

namespace physlab {

ImplicitStats implicitEulerUpdate(const SpringSystem& sys, VecX& X, double h,
                                  const ImplicitSettings& settings, ImplicitWorkspace& ws) {
  // Assemble A = M - h df/dv - h^2 df/dx and the product (df/dx) v, spring by spring
  // TODO(student): ws.A.setZero(), ws.Kv.setZero(); per spring k, springJacobian(..., JacobianForm::Definite).
  // +block on (a, a) and (b, b), -block on (a, b); pinned rows and columns become the identity
  // TODO(student): ws.A.addDiagonal(a, block) if a is free (same for b); ws.A.addSpring(k, -block) if both are.
  // Add the masses and the drag on the diagonal; a pinned particle gets the identity
  // TODO(student): ws.A.addDiagonal(i, (m_i + h drag) * identity) if i is free, the identity if pinned.
  // Form b = h (f + h (df/dx) v), zero for pinned particles
  // TODO(student): sys.forces(X, ws.b) gives f, in place.
  // Solve A dv = b with the chosen solver
  // TODO(student): ws.A.solveCG(ws.b, ws.dv, ...) (from the last step's dv) or solveLDLT(); throw NumericalFailure on failure.
  // Update the velocities, then move with the new velocities
  // TODO(student): v += dv, then x += h v; return the iterations and |A dv - b| / |b| (ws.A.multiply()).
  notImplemented("implicitEulerUpdate", "Lab 2 handout, section 3", sys, X, h, settings, ws);
}

}  // namespace physlab
