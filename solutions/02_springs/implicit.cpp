// Lab 2, section 3: implicit Euler for spring networks (Baraff & Witkin 1998).
#include <string>

#include "physlab/error.hpp"
#include "physlab/particles.hpp"
#include "physlab/springs.hpp"

namespace physlab {

ImplicitStats implicitEulerUpdate(const SpringSystem& sys, VecX& X, double h,
                                  const ImplicitSettings& settings, ImplicitWorkspace& ws) {
  const SpringNetwork& net = sys.network();
  const Index n3 = sys.positionSize();
  const VecX& inv_m = sys.inverseMasses();
  const ConstPoints x = positions(X), v = velocities(X);
  auto free = [&](Index i) { return inv_m[i] != 0.0; };

  // Assemble A = M - h df/dv - h^2 df/dx and the product (df/dx) v, spring by spring
  SpringMatrix& A = ws.A;
  A.setZero();
  ws.Kv.setZero();
  for (std::size_t k = 0; k < net.springs.size(); ++k) {
    const Spring& s = net.springs[k];
    const SpringJacobian J = springJacobian(s, x.col(s.a), x.col(s.b), v.col(s.a), v.col(s.b),
                                            JacobianForm::Definite);
    const Mat3 block = -h * J.dfa_dva - h * h * J.dfa_dxa;
    const Vec3 K_dv = J.dfa_dxa * (v.col(s.a) - v.col(s.b));
    ws.Kv.segment<3>(3 * s.a) += K_dv;
    ws.Kv.segment<3>(3 * s.b) -= K_dv;
    // +block on (a, a) and (b, b), -block on (a, b); pinned rows and columns become the identity
    if (free(s.a)) A.addDiagonal(s.a, block);
    if (free(s.b)) A.addDiagonal(s.b, block);
    if (free(s.a) && free(s.b)) A.addSpring(k, -block);
  }
  // Add the masses and the drag on the diagonal; a pinned particle gets the identity
  for (Index i = 0; i < sys.count(); ++i) {
    A.addDiagonal(i, (free(i) ? net.masses[i] + h * net.drag : 1.0) * Mat3::Identity());
  }

  // Form b = h (f + h (df/dx) v), zero for pinned particles
  VecX& b = ws.b;
  sys.forces(X, b);
  b = h * (b + h * ws.Kv);
  for (Index i = 0; i < n3; ++i) {
    if (!free(i / 3)) b[i] = 0.0;
  }

  // Solve A dv = b with the chosen solver
  ImplicitStats stats;
  VecX& dv = ws.dv;  // CG starts from the last step's dv
  if (settings.solver == LinearSolver::ConjugateGradient) {
    const CGResult cg = A.solveCG(b, dv, settings.cg_tolerance, settings.cg_max_iterations);
    if (!cg.converged) {
      throw NumericalFailure("implicit Euler: CG did not converge in " +
                             std::to_string(settings.cg_max_iterations) + " iterations");
    }
    stats.iterations = cg.iterations;
  } else if (!A.solveLDLT(b, dv)) {
    throw NumericalFailure("implicit Euler: LDLT factorisation failed");
  }
  A.multiply(dv, ws.Adv);
  const double b_norm = b.norm();
  stats.residual = b_norm > 0.0 ? (ws.Adv - b).norm() / b_norm : 0.0;

  // Update the velocities, then move with the new velocities
  X.tail(n3) += dv;
  X.head(n3) += h * X.tail(n3);
  return stats;
}

}  // namespace physlab
