// Lab 1, section 3: one-step integrators. Each works on any System through its small interface.
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "physlab/error.hpp"
#include "physlab/integrators.hpp"

namespace physlab {

void explicitEuler(const System& sys, double h, VecX& X, Workspace& ws) {
  // Evaluate the slope at the start of the step
  sys.derivative(X, ws.k1);
  // Follow it for the whole step
  X += h * ws.k1;
}

void symplecticEuler(const System& sys, double h, VecX& X, Workspace& ws) {
  const Index nq = sys.positionSize();
  const Index np = sys.velocitySize();
  // Kick: update the velocities with the forces at the old positions
  sys.velocityRate(X, ws.k1.head(np));
  X.tail(np) += h * ws.k1.head(np);
  // Drift: move the positions with the new velocities
  X.head(nq) += h * sys.positionRateView(X, ws.k2.head(nq));
}

void midpoint(const System& sys, double h, VecX& X, Workspace& ws) {
  // Take half an Euler step to the midpoint
  sys.derivative(X, ws.k1);
  ws.X_tmp = X + (0.5 * h) * ws.k1;
  // Take the full step with the slope at the midpoint
  sys.derivative(ws.X_tmp, ws.k2);
  X += h * ws.k2;
}

void trapezoid(const System& sys, double h, VecX& X, Workspace& ws) {
  // Take a full Euler step to predict the end of the step
  sys.derivative(X, ws.k1);
  ws.X_tmp = X + h * ws.k1;
  // Average the slopes at both ends
  sys.derivative(ws.X_tmp, ws.k2);
  X += (0.5 * h) * (ws.k1 + ws.k2);
}

void rk4(const System& sys, double h, VecX& X, Workspace& ws) {
  // Sample the slope at the start, twice at the middle, and at the end
  sys.derivative(X, ws.k1);
  ws.X_tmp = X + (0.5 * h) * ws.k1;
  sys.derivative(ws.X_tmp, ws.k2);
  ws.X_tmp = X + (0.5 * h) * ws.k2;
  sys.derivative(ws.X_tmp, ws.k3);
  ws.X_tmp = X + h * ws.k3;
  sys.derivative(ws.X_tmp, ws.k4);
  // Combine them with weights 1/6, 2/6, 2/6, 1/6
  X += (h / 6.0) * (ws.k1 + 2.0 * ws.k2 + 2.0 * ws.k3 + ws.k4);
}

void verlet(const System& sys, double h, VecX& X, Workspace& ws) {
  const Index nq = sys.positionSize();
  const Index np = sys.velocitySize();
  // Kick the velocities by half a step
  sys.velocityRate(X, ws.k1.head(np));
  X.tail(np) += (0.5 * h) * ws.k1.head(np);
  // Drift the positions by a full step with the half-step velocities
  X.head(nq) += h * sys.positionRateView(X, ws.k2.head(nq));
  // Kick the velocities by the second half step with the forces at the new positions
  sys.velocityRate(X, ws.k1.head(np));
  X.tail(np) += (0.5 * h) * ws.k1.head(np);
}

void implicitEuler(const System& sys, double h, VecX& X, Workspace& ws,
                   const NewtonSettings& newton) {
  // Start Newton's method from an explicit Euler prediction of the end of the step
  const VecX& X_n = ws.X_tmp = X;
  const Index n = sys.size();
  sys.derivative(X_n, ws.k1);
  X += h * ws.k1;
  for (int iteration = 0; iteration < newton.max_iterations; ++iteration) {
    // Form the residual G(X) = X - X_n - h f(X)
    sys.derivative(X, ws.k1);
    ws.k2 = X - X_n - h * ws.k1;
    // Solve (1 - h df/dX) dX = -G for the Newton update
    const MatX A = MatX::Identity(n, n) - h * sys.jacobian(X);
    ws.k3 = A.partialPivLu().solve(-ws.k2);
    X += ws.k3;
    // Stop when the update is negligible next to the state
    if (!X.allFinite()) break;
    if (ws.k3.norm() <= newton.tolerance * (1.0 + X.norm())) return;
  }
  throw NumericalFailure("implicit Euler: Newton's method did not converge in " +
                         std::to_string(newton.max_iterations) + " iterations (h = " +
                         std::to_string(h) + ")");
}

}  // namespace physlab
