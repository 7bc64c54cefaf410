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
  const SpringNetwork& net = sys.network();
  const Index n3 = sys.positionSize();
  const VecX& inv_m = sys.inverseMasses();
  const ConstPoints x = positions(X), v = velocities(X);
  auto free = [&](Index i) { return inv_m[i] != 0.0; };

  // Assemble A = M - h df/dv - h^2 df/dx and the product (df/dx) v, spring by spring
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(4 * 9 * net.springs.size() + n3);
  VecX Kv = VecX::Zero(n3);
  for (const Spring& s : net.springs) {
    const SpringJacobian J = springJacobian(s, x.col(s.a), x.col(s.b), v.col(s.a), v.col(s.b),
                                            JacobianForm::Definite);
    const Mat3 block = -h * J.dfa_dva - h * h * J.dfa_dxa;
    const Vec3 K_dv = J.dfa_dxa * (v.col(s.a) - v.col(s.b));
    Kv.segment<3>(3 * s.a) += K_dv;
    Kv.segment<3>(3 * s.b) -= K_dv;
    for (const auto& [row, row_sign] : {std::pair{s.a, 1.0}, std::pair{s.b, -1.0}}) {
      for (const auto& [col, col_sign] : {std::pair{s.a, 1.0}, std::pair{s.b, -1.0}}) {
        if (!free(row) || !free(col)) continue;  // pinned rows and columns become the identity
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) {
            triplets.emplace_back(3 * row + r, 3 * col + c, row_sign * col_sign * block(r, c));
          }
        }
      }
    }
  }
  // Add the masses and the drag on the diagonal; a pinned particle gets the identity
  for (Index i = 0; i < n3; ++i) {
    const bool is_free = free(i / 3);
    triplets.emplace_back(i, i, is_free ? net.masses[i / 3] + h * net.drag : 1.0);
  }
  Eigen::SparseMatrix<double> A(n3, n3);
  A.setFromTriplets(triplets.begin(), triplets.end());

  // Form b = h (f + h (df/dx) v), zero for pinned particles
  VecX b = h * (sys.forces(X) + h * Kv);
  for (Index i = 0; i < n3; ++i) {
    if (!free(i / 3)) b[i] = 0.0;
  }

  // Solve A dv = b with the chosen solver
  ImplicitStats stats;
  VecX dv;
  if (settings.solver == LinearSolver::ConjugateGradient) {
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(settings.cg_tolerance);
    cg.setMaxIterations(settings.cg_max_iterations);
    cg.compute(A);
    dv = cg.solve(b);
    if (cg.info() != Eigen::Success) {
      throw NumericalFailure("implicit Euler: CG did not converge in " +
                             std::to_string(settings.cg_max_iterations) + " iterations");
    }
    stats.iterations = static_cast<int>(cg.iterations());
  } else {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
    if (ldlt.info() != Eigen::Success) {
      throw NumericalFailure("implicit Euler: LDLT factorisation failed");
    }
    dv = ldlt.solve(b);
  }
  stats.residual = b.norm() > 0.0 ? (A * dv - b).norm() / b.norm() : 0.0;

  // Update the velocities, then move with the new velocities
  X.tail(n3) += dv;
  X.head(n3) += h * X.tail(n3);
  return stats;
}

}  // namespace physlab
