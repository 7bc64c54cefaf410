// Lab 6 framework, student copy before Lab 6 is released: RestingSettings::matrix_free built on
// the students' own functions, standing in for the framework answer
// common/answers/06_resting_contact/cone_matrix_free.cpp (see cmake/PhysLab.cmake). The sweeps are
// solveLcpPgsCone()'s, point by point: each point's 3 x 3 block of A comes from contactMatrix()
// and its b from velocityBias(), both once per solve; a sweep asks solveLcpPgsCone() for one
// sweep on the point's block, with w = b + J dv read from the bodies' velocities as they change,
// and applyImpulse() applies the change. Gauss-Seidel over the points is Gauss-Seidel over the
// rows in the same order, so the iterates are the dense cone PGS's up to round-off, at a cost
// linear in the points.
#include <algorithm>
#include <limits>
#include <vector>

#include "physlab/resting.hpp"

namespace physlab {

namespace {

// One resting point: its rows, its block of A, the part of w that is not the velocity along the
// rows, its friction coefficient and its impulses (f_n, f_t, f_o).
struct PointBlock {
  std::vector<ContactRow> rows;
  MatX A;
  Vec3 offset = Vec3::Zero();
  VecX mu = VecX::Zero(1);
  VecX f = VecX::Zero(3);
};

// The velocity of the point's A relative to its B, along each of its rows.
Vec3 rowVelocities(const std::vector<ContactBody>& bodies, const PointBlock& point) {
  const ContactRow& row = point.rows[0];
  const ContactBody &A = bodies[static_cast<std::size_t>(row.a)], &B = bodies[static_cast<std::size_t>(row.b)];
  const Vec3 v_rel = A.v + A.omega.cross(row.p - A.x) - B.v - B.omega.cross(row.p - B.x);
  return Vec3(point.rows[0].d.dot(v_rel), point.rows[1].d.dot(v_rel), point.rows[2].d.dot(v_rel));
}

// The impulse change from `before` to the point's f, applied at the point.
void applyChange(std::vector<ContactBody>& bodies, const PointBlock& point, const Vec3& before) {
  Vec3 J = Vec3::Zero();
  for (int i = 0; i < 3; ++i) J += (point.f(i) - before(i)) * point.rows[static_cast<std::size_t>(i)].d;
  const ContactRow& row = point.rows[0];
  applyImpulse(bodies[static_cast<std::size_t>(row.a)], bodies[static_cast<std::size_t>(row.b)], row.p, J);
}

}  // namespace

const char* LcpContactSolver::matrixFreeSource() { return "built on your solveLcpPgsCone"; }

int LcpContactSolver::solveConeMatrixFree(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts,
                                          const std::vector<int>& resting, double h) {
  // Each point's block of A and its b at the velocities before any impulse (the dense cone path's
  // rows n, t, o), and its warm start inside the cone
  std::vector<PointBlock> points(resting.size());
  for (std::size_t k = 0; k < resting.size(); ++k) {
    const Contact& c = contacts[static_cast<std::size_t>(resting[k])];
    PointBlock& point = points[k];
    const auto [t, o] = tangentPair(c.n);
    point.rows = {{c.a, c.b, c.p, c.n}, {c.a, c.b, c.p, t}, {c.a, c.b, c.p, o}};
    point.A = contactMatrix(bodies, point.rows);
    VecX b = velocityBias(bodies, point.rows, Vec3(c.depth, 0.0, 0.0), h, settings_.baumgarte, settings_.slop);
    b(0) = bounceBias(b(0), bodies, c);
    point.offset = Vec3(b) - rowVelocities(bodies, point);
    point.mu(0) = c.mu;
    point.f = Vec3(std::max(0.0, c.j), c.j_t.dot(t), c.j_t.dot(o));
    const double radius = c.mu * point.f(0), length = point.f.tail<2>().norm();
    if (length > radius) point.f.tail<2>() *= length > 0.0 ? radius / length : 0.0;
  }
  for (const PointBlock& point : points) applyChange(bodies, point, Vec3::Zero());
  // The sweeps: one sweep of solveLcpPgsCone() per point on w = A_kk f + (w now - A_kk f)
  LcpOptions one = settings_.lcp;
  one.max_iterations = 1;
  one.tolerance = 0.0;
  int sweeps = 0;
  last_residual_ = std::numeric_limits<double>::infinity();
  while (sweeps < settings_.lcp.max_iterations) {
    double largest = 0.0;
    for (PointBlock& point : points) {
      const Vec3 before = point.f;
      const VecX w = point.offset + rowVelocities(bodies, point);
      one.initial = point.f;
      const LcpSolution solution = solveLcpPgsCone(point.A, w - point.A * point.f, point.mu, one);
      point.f = solution.f;
      applyChange(bodies, point, before);
      largest = std::max(largest, solution.residual);
    }
    ++sweeps;
    last_residual_ = largest;
    if (largest <= settings_.lcp.tolerance) break;
  }
  // The impulses found, stored for next step's warm start
  for (std::size_t k = 0; k < resting.size(); ++k) {
    Contact& c = contacts[static_cast<std::size_t>(resting[k])];
    const PointBlock& point = points[k];
    c.j = point.f(0);
    c.j_t = point.f(1) * point.rows[1].d + point.f(2) * point.rows[2].d;
  }
  return sweeps;
}

}  // namespace physlab
