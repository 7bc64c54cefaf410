// Lab 1, section 3: one-step integrators. Each works on any System through its small interface.
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "physlab/error.hpp"
#include "physlab/integrators.hpp"

namespace physlab {

void explicitEuler(const System& sys, double h, VecX& X, Workspace& ws) {
  // Evaluate the slope at the start of the step
  // TODO(student): evaluate the slope at the start of the step.
  // Follow it for the whole step
  // TODO(student): follow it for the whole step.
  notImplemented("explicitEuler", "Lab 1 handout, section 3.1", sys, h, X, ws);
}

void symplecticEuler(const System& sys, double h, VecX& X, Workspace& ws) {
  // Kick: update the velocities with the forces at the old positions
  // TODO(student): kick: update the velocities with the forces at the old positions.
  // Drift: move the positions with the new velocities
  // TODO(student): drift: move the positions with the new velocities.
  notImplemented("symplecticEuler", "Lab 1 handout, section 3.2", sys, h, X, ws);
}

void midpoint(const System& sys, double h, VecX& X, Workspace& ws) {
  // Take half an Euler step to the midpoint
  // TODO(student): take half an Euler step to the midpoint.
  // Take the full step with the slope at the midpoint
  // TODO(student): take the full step with the slope at the midpoint.
  notImplemented("midpoint", "Lab 1 handout, section 3.3", sys, h, X, ws);
}

void trapezoid(const System& sys, double h, VecX& X, Workspace& ws) {
  // Take a full Euler step to predict the end of the step
  // TODO(student): take a full Euler step to predict the end of the step.
  // Average the slopes at both ends
  // TODO(student): average the slopes at both ends.
  notImplemented("trapezoid", "Lab 1 handout, section 3.3", sys, h, X, ws);
}

void rk4(const System& sys, double h, VecX& X, Workspace& ws) {
  // Sample the slope at the start, twice at the middle, and at the end
  // TODO(student): sample the slope at the start, twice at the middle, and at the end.
  // Combine them with weights 1/6, 2/6, 2/6, 1/6
  // TODO(student): combine them with weights 1/6, 2/6, 2/6, 1/6.
  notImplemented("rk4", "Lab 1 handout, section 3.4", sys, h, X, ws);
}

void verlet(const System& sys, double h, VecX& X, Workspace& ws) {
  // Kick the velocities by half a step
  // TODO(student): kick the velocities by half a step.
  // Drift the positions by a full step with the half-step velocities
  // TODO(student): drift the positions by a full step with the half-step velocities.
  // Kick the velocities by the second half step with the forces at the new positions
  // TODO(student): kick the velocities by the second half step with the forces at the new positions.
  notImplemented("verlet", "Lab 1 handout, section 3.5", sys, h, X, ws);
}

void implicitEuler(const System& sys, double h, VecX& X, Workspace& ws,
                   const NewtonSettings& newton) {
  // Start Newton's method from the current state
  // TODO(student): start Newton's method from the current state.
  notImplemented("implicitEuler", "Lab 1 handout, section 3.6", sys, h, X, ws, newton);
}

}  // namespace physlab
