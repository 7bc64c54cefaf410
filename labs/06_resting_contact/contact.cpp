// Lab 6, sections 1, 2, 7 and 8: the contact matrix A, Baraff's b, the velocity-level b and the
// friction pyramid's LCP.
#include <cmath>
#include <string>

#include "physlab/error.hpp"
#include "physlab/resting.hpp"

namespace physlab {

MatX contactMatrix(const std::vector<ContactBody>& bodies, const std::vector<ContactRow>& rows) {
  // Push A of row j by +d_j and B by -d_j; see how the touching points of row i move apart
  // TODO(student): InvalidInput when a row names a body outside bodies, a row's d is not a finite unit vector (length
  // TODO(student): off 1 by more than 1e-9) or its p not finite, or a body's inv_mass < 0 or not finite or I_inv_world
  // TODO(student): not finite. For each pair of rows i, j: the unit impulse
  // TODO(student): d_j at p_j changes a body's point velocity at p_i by m^-1 d_j + (I^-1 (r_j x d_j)) x r_i, with
  // TODO(student): r = point - x of that body; add it for row i's A and subtract it for row i's B, with the sign of
  // TODO(student): the body's role in row j (+ for its A, - for its B); a_ij = d_i . (sum).
  // A is symmetric: fill both halves from one evaluation
  // TODO(student): compute j >= i only and set A(i, j) = A(j, i).
  notImplemented("contactMatrix", "Lab 6 handout, section 1", bodies, rows);
}

VecX accelerationBias(const std::vector<ContactBody>& bodies, const std::vector<AppliedLoads>& loads,
                      const std::vector<ContactRow>& normals) {
  // Acceleration of each touching point with no contact force: linear, angular, centripetal
  // TODO(student): InvalidInput unless loads.size() == bodies.size() and the rows and bodies pass contactMatrix's checks.
  // TODO(student): p_ddot0 = F / m + (I^-1 (tau + L x omega)) x r + omega x (omega x r), r = p - x.
  // The normal turns with body B: n_dot = omega_b x n
  // TODO(student): b_i = n . (p_ddot0_a - p_ddot0_b) + 2 n_dot . (pdot_a - pdot_b), pdot = v + omega x r.
  notImplemented("accelerationBias", "Lab 6 handout, section 2", bodies, loads, normals);
}

VecX velocityBias(const std::vector<ContactBody>& bodies, const std::vector<ContactRow>& rows, const VecX& depths,
                  double h, double baumgarte, double slop) {
  // Relative velocity along the row now, less the speed that removes a fraction of the overlap
  // TODO(student): InvalidInput on depths of the wrong size or not finite, h <= 0, baumgarte outside [0, 1], slop < 0,
  // TODO(student): rows naming bodies that do not exist, with a d that is not a finite unit vector or a p not finite.
  // TODO(student): b_i = d_i . relativeVelocity(A, B, p_i) - baumgarte / h * max(0, depth_i - slop).
  notImplemented("velocityBias", "Lab 6 handout, section 7", bodies, rows, depths, h, baumgarte, slop);
}

LcpProblem frictionPyramid(const MatX& A, const VecX& b, const VecX& mu, int k) {
  // Normal and direction rows keep A and b; the sliding speeds gamma join them
  // TODO(student): InvalidInput when k < 3, A is not (m + m k) square, b has another size, some mu < 0 or not finite,
  // TODO(student): or A or b has a non-finite entry.
  // TODO(student): the result is (m + m k + m) square: A and b top left, zeros elsewhere to start with.
  // w_d = ... + gamma: a direction opposite the sliding gets beta > 0 only when it moves at -gamma
  // TODO(student): a 1 in column gamma_i of each of contact i's k direction rows.
  // w_gamma = mu lambda_n - sum beta: the friction stays inside the pyramid
  // TODO(student): row gamma_i: mu_i in column i (its normal), -1 in the columns of its k directions.
  notImplemented("frictionPyramid", "Lab 6 handout, section 8", A, b, mu, k);
}

}  // namespace physlab
