// Lab 6 framework answer (common/answers/, see cmake/PhysLab.cmake): RestingSettings::matrix_free
// with the friction cone's projected Gauss-Seidel written over per-body velocity changes. It
// computes what the students' solveLcpPgsCone() computes, so it is not in a student's copy until
// Lab 6 is released (released/06_resting_contact/framework/); until then
// common/unreleased/06_resting_contact/cone_matrix_free.cpp stands in for it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "physlab/error.hpp"
#include "physlab/resting.hpp"

namespace physlab {

const char* LcpContactSolver::matrixFreeSource() { return "framework answer"; }

// solveLcpPgsCone() on the rows (n, t, o) of every resting point, with w = b + J dv kept through
// per-body velocity changes instead of A f: a row's update touches only its two bodies.
int LcpContactSolver::solveConeMatrixFree(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts,
                                          const std::vector<int>& resting, double h) {
  const double beta_h = settings_.baumgarte / h;
  points_.resize(resting.size());
  dv_.assign(bodies.size(), Vec3::Zero());
  dw_.assign(bodies.size(), Vec3::Zero());
  // Rows, their Jacobians, diagonals and biases; the warm start inside the cone, applied
  for (std::size_t k = 0; k < resting.size(); ++k) {
    const Contact& c = contacts[static_cast<std::size_t>(resting[k])];
    PointRows& pt = points_[k];
    const ContactBody& A = bodies[static_cast<std::size_t>(c.a)];
    const ContactBody& B = bodies[static_cast<std::size_t>(c.b)];
    pt.a = static_cast<std::size_t>(c.a);
    pt.b = static_cast<std::size_t>(c.b);
    pt.inv_ma = A.inv_mass;
    pt.inv_mb = B.inv_mass;
    pt.mu = c.mu;
    // The rows n, t, o of the dense cone path
    pt.d[0] = c.n;
    std::tie(pt.d[1], pt.d[2]) = tangentPair(c.n);
    const Vec3 r_a = c.p - A.x, r_b = c.p - B.x;
    const Vec3 v_rel = A.v + A.omega.cross(r_a) - B.v - B.omega.cross(r_b);
    for (int i = 0; i < 3; ++i) {
      pt.ang_a[i] = r_a.cross(pt.d[i]);
      pt.ang_b[i] = r_b.cross(pt.d[i]);
      pt.turn_a[i] = A.I_inv_world * pt.ang_a[i];
      pt.turn_b[i] = B.I_inv_world * pt.ang_b[i];
      pt.diag[i] = A.inv_mass + B.inv_mass + pt.ang_a[i].dot(pt.turn_a[i]) + pt.ang_b[i].dot(pt.turn_b[i]);
      if (!(pt.diag[i] > settings_.lcp.pivot_tolerance)) {
        throw LcpFailure("matrix-free cone PGS: diagonal entry of row " + std::to_string(3 * k + i) + " = " +
                         std::to_string(pt.diag[i]) + " is not positive");
      }
      pt.bias[i] = pt.d[i].dot(v_rel);
    }
    pt.bias[0] = bounceBias(pt.bias[0] - beta_h * std::max(0.0, c.depth - settings_.slop), bodies, c);
    const double a_to = (A.inv_mass + B.inv_mass) * pt.d[1].dot(pt.d[2]) + pt.ang_a[1].dot(pt.turn_a[2]) +
                        pt.ang_b[1].dot(pt.turn_b[2]);
    pt.inv_diag_n = 1.0 / pt.diag[0];
    pt.inv_lambda_T = 1.0 / (0.5 * (pt.diag[1] + pt.diag[2]) + std::hypot(0.5 * (pt.diag[1] - pt.diag[2]), a_to));
    pt.f = Vec3(std::max(0.0, c.j), c.j_t.dot(pt.d[1]), c.j_t.dot(pt.d[2]));
    const double radius = pt.mu * pt.f(0), length = pt.f.tail<2>().norm();
    if (length > radius) pt.f.tail<2>() *= length > 0.0 ? radius / length : 0.0;
    for (int i = 0; i < 3; ++i) {
      dv_[pt.a] += pt.inv_ma * pt.f(i) * pt.d[i];
      dw_[pt.a] += pt.f(i) * pt.turn_a[i];
      dv_[pt.b] -= pt.inv_mb * pt.f(i) * pt.d[i];
      dw_[pt.b] -= pt.f(i) * pt.turn_b[i];
    }
  }
  // The sweeps of solveLcpPgsCone(): w_i = b_i + J_i (dv, dw), and an impulse change moves only
  // the point's two bodies
  int sweeps = 0;
  last_residual_ = std::numeric_limits<double>::infinity();
  while (sweeps < settings_.lcp.max_iterations) {
    double largest = 0.0;
    for (PointRows& pt : points_) {
      Vec3 &va = dv_[pt.a], &wa = dw_[pt.a], &vb = dv_[pt.b], &wb = dw_[pt.b];
      // The normal row, projected onto f_n >= 0
      const double w_n = pt.bias[0] + pt.d[0].dot(va - vb) + pt.ang_a[0].dot(wa) - pt.ang_b[0].dot(wb);
      const double f_n = std::max(0.0, pt.f(0) - w_n * pt.inv_diag_n);
      const double dn = f_n - pt.f(0);
      va += (pt.inv_ma * dn) * pt.d[0];
      wa += dn * pt.turn_a[0];
      vb -= (pt.inv_mb * dn) * pt.d[0];
      wb -= dn * pt.turn_b[0];
      pt.f(0) = f_n;
      // The tangential pair, one step of 1/lambda_T, projected onto the disc of radius mu f_n
      const Vec3 relative = va - vb;
      const Eigen::Vector2d w_T(pt.bias[1] + pt.d[1].dot(relative) + pt.ang_a[1].dot(wa) - pt.ang_b[1].dot(wb),
                                pt.bias[2] + pt.d[2].dot(relative) + pt.ang_a[2].dot(wa) - pt.ang_b[2].dot(wb));
      Eigen::Vector2d f_T = pt.f.tail<2>() - w_T * pt.inv_lambda_T;
      const double radius = pt.mu * f_n, length2 = f_T.squaredNorm();
      if (length2 > radius * radius) f_T *= radius / std::sqrt(length2);
      const double dt = f_T(0) - pt.f(1), d_o = f_T(1) - pt.f(2);
      const Vec3 push = dt * pt.d[1] + d_o * pt.d[2];
      va += pt.inv_ma * push;
      wa += dt * pt.turn_a[1] + d_o * pt.turn_a[2];
      vb -= pt.inv_mb * push;
      wb -= dt * pt.turn_b[1] + d_o * pt.turn_b[2];
      pt.f(1) = f_T(0);
      pt.f(2) = f_T(1);
      largest = std::max({largest, std::abs(dn) * pt.diag[0], std::abs(dt) * pt.diag[1], std::abs(d_o) * pt.diag[2]});
    }
    ++sweeps;
    last_residual_ = largest;
    if (largest <= settings_.lcp.tolerance) break;
  }
  // Apply the impulses found; store them for next step's warm start
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies[i].v += dv_[i];
    bodies[i].omega += dw_[i];
  }
  for (std::size_t k = 0; k < resting.size(); ++k) {
    Contact& c = contacts[static_cast<std::size_t>(resting[k])];
    const PointRows& pt = points_[k];
    c.j = pt.f(0);
    c.j_t = pt.f(1) * pt.d[1] + pt.f(2) * pt.d[2];
  }
  return sweeps;
}

}  // namespace physlab
