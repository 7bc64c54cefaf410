// Lab 6, sections 1, 2, 7 and 8: the contact matrix A, Baraff's b, the velocity-level b and the
// friction pyramid's LCP.
#include <cmath>
#include <string>

#include "physlab/error.hpp"
#include "physlab/resting.hpp"

namespace physlab {

namespace {

void requireBody(const std::vector<ContactBody>& bodies, int index, std::size_t row) {
  if (index < 0 || index >= static_cast<int>(bodies.size())) {
    throw InvalidInput("contact row " + std::to_string(row) + " names body " + std::to_string(index) + " of " +
                       std::to_string(bodies.size()));
  }
}

// InvalidInput naming row i's field, built only on failure.
[[noreturn, gnu::cold, gnu::noinline]] void refuseRow(std::size_t row, const char* what) {
  throw InvalidInput("contact row " + std::to_string(row) + " " + what);
}

// Row i names two existing bodies, at a finite point, along a finite unit direction.
void requireRow(const std::vector<ContactBody>& bodies, const ContactRow& row, std::size_t i) {
  requireBody(bodies, row.a, i);
  requireBody(bodies, row.b, i);
  if (!(std::abs(row.d.norm() - 1.0) <= 1e-9)) refuseRow(i, "direction d must be a finite unit vector");
  if (firstNonFinite(row.p) >= 0) refuseRow(i, "point p must be finite");
}

// Every body's inverse mass is >= 0 and finite (0: fixed) and its inverse inertia finite.
void requireInverses(const std::vector<ContactBody>& bodies) {
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    if (!(bodies[k].inv_mass >= 0.0 && std::isfinite(bodies[k].inv_mass)) || firstNonFinite(bodies[k].I_inv_world) >= 0) {
      throw InvalidInput("body " + std::to_string(k) + " inverse mass inv_mass must be non-negative and finite, " +
                         "and its inverse inertia I_inv_world finite");
    }
  }
}

// The velocity change at p of `body` caused by the impulse J at q on it.
Vec3 velocityChange(const ContactBody& body, const Vec3& J, const Vec3& q, const Vec3& p) {
  return body.inv_mass * J + (body.I_inv_world * (q - body.x).cross(J)).cross(p - body.x);
}

}  // namespace

MatX contactMatrix(const std::vector<ContactBody>& bodies, const std::vector<ContactRow>& rows) {
  requireInverses(bodies);
  for (std::size_t i = 0; i < rows.size(); ++i) requireRow(bodies, rows[i], i);
  const Index n = static_cast<Index>(rows.size());
  MatX A = MatX::Zero(n, n);
  for (Index i = 0; i < n; ++i) {
    const ContactRow& ri = rows[i];
    for (Index j = i; j < n; ++j) {
      const ContactRow& rj = rows[j];
      // Push A of row j by +d_j and B by -d_j; see how the touching points of row i move apart
      Vec3 dv = Vec3::Zero();
      if (rj.a == ri.a) dv += velocityChange(bodies[ri.a], rj.d, rj.p, ri.p);
      if (rj.b == ri.a) dv -= velocityChange(bodies[ri.a], rj.d, rj.p, ri.p);
      if (rj.a == ri.b) dv -= velocityChange(bodies[ri.b], rj.d, rj.p, ri.p);
      if (rj.b == ri.b) dv += velocityChange(bodies[ri.b], rj.d, rj.p, ri.p);
      // A is symmetric: fill both halves from one evaluation
      A(i, j) = A(j, i) = ri.d.dot(dv);
    }
  }
  return A;
}

VecX accelerationBias(const std::vector<ContactBody>& bodies, const std::vector<AppliedLoads>& loads,
                      const std::vector<ContactRow>& normals) {
  requireSize(static_cast<Index>(loads.size()), static_cast<Index>(bodies.size()), "accelerationBias loads");
  requireInverses(bodies);
  VecX b(static_cast<Index>(normals.size()));
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const ContactRow& row = normals[i];
    requireRow(bodies, row, i);
    // Acceleration of each touching point with no contact force: linear, angular, centripetal
    auto pointAcceleration = [&](int k) -> Vec3 {
      const ContactBody& body = bodies[k];
      const Vec3 r = row.p - body.x;
      const Vec3 omega_dot = body.I_inv_world * (loads[k].tau + loads[k].L.cross(body.omega));
      return body.inv_mass * loads[k].F + omega_dot.cross(r) + body.omega.cross(body.omega.cross(r));
    };
    const Vec3 pdot_a = bodies[row.a].v + bodies[row.a].omega.cross(row.p - bodies[row.a].x);
    const Vec3 pdot_b = bodies[row.b].v + bodies[row.b].omega.cross(row.p - bodies[row.b].x);
    // The normal turns with body B: n_dot = omega_b x n
    const Vec3 n_dot = bodies[row.b].omega.cross(row.d);
    b(static_cast<Index>(i)) =
        row.d.dot(pointAcceleration(row.a) - pointAcceleration(row.b)) + 2.0 * n_dot.dot(pdot_a - pdot_b);
  }
  return b;
}

VecX velocityBias(const std::vector<ContactBody>& bodies, const std::vector<ContactRow>& rows, const VecX& depths,
                  double h, double baumgarte, double slop) {
  requireSize(depths.size(), static_cast<Index>(rows.size()), "velocityBias depths");
  requirePositive(h, "velocityBias step size h");
  if (!(baumgarte >= 0.0 && baumgarte <= 1.0)) throw InvalidInput("velocityBias Baumgarte factor must be in [0, 1]");
  requireNonNegative(slop, "velocityBias slop");
  requireFinite(depths, "velocityBias depths");
  VecX b(depths.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ContactRow& row = rows[i];
    requireRow(bodies, row, i);
    // Relative velocity along the row now, less the speed that removes a fraction of the overlap
    const double v_rel = row.d.dot(relativeVelocity(bodies[row.a], bodies[row.b], row.p));
    const double overlap = std::max(0.0, depths(static_cast<Index>(i)) - slop);
    b(static_cast<Index>(i)) = v_rel - baumgarte / h * overlap;
  }
  return b;
}

LcpProblem frictionPyramid(const MatX& A, const VecX& b, const VecX& mu, int k) {
  if (k < 3) throw InvalidInput("friction pyramid needs k >= 3 directions, got " + std::to_string(k));
  const Index m = mu.size(), rows = m + m * k;
  if (A.rows() != rows || A.cols() != rows) {
    throw InvalidInput("friction pyramid: A must be " + std::to_string(rows) + " x " + std::to_string(rows) +
                       " for " + std::to_string(m) + " contacts and k = " + std::to_string(k));
  }
  requireSize(b.size(), rows, "friction pyramid b");
  requireFinite(A, "friction pyramid A");
  requireFinite(b, "friction pyramid b");
  for (Index i = 0; i < m; ++i) requireNonNegative(mu(i), "friction pyramid mu of contact " + std::to_string(i));
  // Normal and direction rows keep A and b; the sliding speeds gamma join them
  LcpProblem lcp;
  lcp.A = MatX::Zero(rows + m, rows + m);
  lcp.b = VecX::Zero(rows + m);
  lcp.A.topLeftCorner(rows, rows) = A;
  lcp.b.head(rows) = b;
  for (Index i = 0; i < m; ++i) {
    for (Index l = 0; l < k; ++l) {
      const Index direction = m + i * k + l, gamma = rows + i;
      // w_d = ... + gamma: a direction opposite the sliding gets beta > 0 only when it moves at -gamma
      lcp.A(direction, gamma) = 1.0;
      // w_gamma = mu lambda_n - sum beta: the friction stays inside the pyramid
      lcp.A(gamma, direction) = -1.0;
    }
    lcp.A(rows + i, i) = mu(i);
  }
  return lcp;
}

}  // namespace physlab
