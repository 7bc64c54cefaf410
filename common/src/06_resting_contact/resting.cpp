// Lab 6 framework: the resting-contact solver World steps with. It builds the rows of the
// resting points, asks the students' functions for the LCP of the chosen formulation, solves it
// with the chosen method and applies the forces (or impulses) it finds.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>

#include "physlab/error.hpp"
#include "physlab/resting.hpp"

namespace physlab {

const char* formulationName(Formulation formulation) {
  switch (formulation) {
    case Formulation::Acceleration: return "acceleration";
    case Formulation::Velocity: return "velocity";
  }
  return "unknown";
}

const char* lcpMethodName(LcpMethod method) {
  switch (method) {
    case LcpMethod::Pivoting: return "pivoting";
    case LcpMethod::Lemke: return "Lemke";
    case LcpMethod::Pgs: return "PGS";
  }
  return "unknown";
}

std::string RestingSettings::toString() const {
  std::ostringstream out;
  out << "formulation=" << formulationName(formulation) << " lcp=" << lcpMethodName(method)
      << " max_iterations=" << lcp.max_iterations << " tolerance=" << lcp.tolerance
      << " pivot_tolerance=" << lcp.pivot_tolerance << " pyramid_directions=" << pyramid_directions
      << " baumgarte=" << baumgarte << " slop=" << slop << " regularization=" << regularization
      << " matrix_free=" << (matrix_free ? "yes" : "no");
  return out.str();
}

// n crossed with the world axis it is least aligned with, so the tangent is never short
std::pair<Vec3, Vec3> tangentPair(const Vec3& n) {
  Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  const Vec3 t1 = n.cross(Vec3::Unit(axis)).normalized();
  return {t1, n.cross(t1)};
}

std::vector<Vec3> tangentDirections(const Vec3& n, int k) {
  if (k < 1) throw InvalidInput("tangentDirections needs k >= 1, got " + std::to_string(k));
  requireFinite(n, "tangentDirections normal n");
  if (std::abs(n.norm() - 1.0) > 1e-9) throw InvalidInput("tangentDirections normal n must be a unit vector");
  const auto [t1, t2] = tangentPair(n);
  std::vector<Vec3> directions(static_cast<std::size_t>(k));
  for (int l = 0; l < k; ++l) {
    const double angle = 2.0 * M_PI * l / k;
    directions[static_cast<std::size_t>(l)] = std::cos(angle) * t1 + std::sin(angle) * t2;
  }
  return directions;
}

LcpContactSolver::LcpContactSolver(RestingSettings settings) : settings_(settings) {
  if (settings_.lcp.max_iterations < 1) throw InvalidInput("resting settings lcp max_iterations must be at least 1");
  requireNonNegative(settings_.lcp.tolerance, "resting settings lcp tolerance");
  requireNonNegative(settings_.lcp.pivot_tolerance, "resting settings lcp pivot_tolerance");
  if (settings_.pyramid_directions < 3) throw InvalidInput("resting settings pyramid_directions must be at least 3");
  if (!(settings_.baumgarte >= 0.0 && settings_.baumgarte <= 1.0)) {
    throw InvalidInput("resting settings baumgarte must be in [0, 1]");
  }
  requireNonNegative(settings_.slop, "resting settings slop");
  if (!(settings_.regularization >= 0.0 && settings_.regularization < 1.0)) {
    throw InvalidInput("resting settings regularization must be in [0, 1)");
  }
  if (settings_.matrix_free && (settings_.method != LcpMethod::Pgs || settings_.formulation != Formulation::Velocity)) {
    throw InvalidInput("resting settings matrix_free needs method PGS at the velocity level");
  }
}

std::string LcpContactSolver::describe() const {
  const bool frictionless = settings_.method == LcpMethod::Pivoting || settings_.formulation == Formulation::Acceleration;
  return settings_.toString() + (frictionless ? " (friction ignored)" : "");
}

bool LcpContactSolver::bounces() const { return settings_.formulation == Formulation::Velocity; }

namespace {

// The relative normal velocity of contact c's points now [m/s].
double normalVelocity(const std::vector<ContactBody>& bodies, const Contact& c) {
  const ContactBody &A = bodies[static_cast<std::size_t>(c.a)], &B = bodies[static_cast<std::size_t>(c.b)];
  return c.n.dot(A.v + A.omega.cross(c.p - A.x) - B.v - B.omega.cross(c.p - B.x));
}

// A colliding point's normal bias aims at its bounce when that is faster than the push apart
double bounceBias(double bias, const std::vector<ContactBody>& bodies, const Contact& c) {
  if (c.kind != ContactKind::Colliding) return bias;
  return std::min(bias, normalVelocity(bodies, c) + c.epsilon * c.v_rel_minus);
}

}  // namespace

int LcpContactSolver::solve(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts,
                            const std::vector<int>& resting, const std::vector<BodyDescription>& descriptions,
                            const std::vector<BodyState>& states, const Vec3& gravity, double h) {
  if (settings_.matrix_free) return solveConeMatrixFree(bodies, contacts, resting, h);
  const bool velocity_level = settings_.formulation == Formulation::Velocity;
  const Index m = static_cast<Index>(resting.size());
  VecX mu(m);
  for (Index i = 0; i < m; ++i) mu(i) = contacts[resting[i]].mu;
  // Friction needs the velocity level and a solver that takes a non-symmetric problem or a cone
  const bool friction = velocity_level && settings_.method != LcpMethod::Pivoting && mu.maxCoeff() > 0.0;
  const bool cone = friction && settings_.method == LcpMethod::Pgs;
  const int k = settings_.pyramid_directions;

  // Rows: normals, then k directions per contact (pyramid); or (n, t, o) per contact (cone)
  rows_.clear();
  std::vector<double> depths;
  auto addRow = [&](const Contact& c, const Vec3& d, double depth) {
    rows_.push_back({c.a, c.b, c.p, d});
    depths.push_back(depth);
  };
  for (const int index : resting) {
    const Contact& c = contacts[index];
    if (cone) {
      const auto [t1, t2] = tangentPair(c.n);
      addRow(c, c.n, c.depth);
      addRow(c, t1, 0.0);
      addRow(c, t2, 0.0);
    } else {
      addRow(c, c.n, c.depth);
    }
  }
  if (friction && !cone) {
    for (const int index : resting) {
      for (const Vec3& d : tangentDirections(contacts[index].n, k)) addRow(contacts[index], d, 0.0);
    }
  }

  // The LCP of the formulation
  MatX A = contactMatrix(bodies, rows_);
  // Dantzig's clamped blocks must stay invertible; Lemke and PGS take A as it is
  if (settings_.method == LcpMethod::Pivoting && A.size() > 0) {
    A.diagonal().array() += settings_.regularization * A.diagonal().maxCoeff();
  }
  VecX b;
  if (velocity_level) {
    b = velocityBias(bodies, rows_, Eigen::Map<const VecX>(depths.data(), static_cast<Index>(depths.size())), h,
                     settings_.baumgarte, settings_.slop);
    for (Index i = 0; i < m; ++i) {
      const Index row = cone ? 3 * i : i;
      b(row) = bounceBias(b(row), bodies, contacts[resting[static_cast<std::size_t>(i)]]);
    }
  } else {
    loads_.assign(bodies.size(), AppliedLoads{});
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (descriptions[i].fixed) continue;
      loads_[i].F = descriptions[i].mass * gravity;
      loads_[i].L = states[i].L;
    }
    b = accelerationBias(bodies, loads_, rows_);
  }

  // Warm start PGS from last step's impulses (World carried them over by feature id)
  LcpOptions options = settings_.lcp;
  if (settings_.method == LcpMethod::Pgs) {
    const double scale = velocity_level ? 1.0 : 1.0 / h;
    options.initial = VecX::Zero(static_cast<Index>(rows_.size()));
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      const Contact& c = contacts[resting[cone ? r / 3 : r]];
      options.initial(static_cast<Index>(r)) = scale * (cone && r % 3 != 0 ? c.j_t.dot(rows_[r].d) : c.j);
    }
  }

  LcpSolution solution;
  switch (settings_.method) {
    case LcpMethod::Pivoting:
      solution = solveLcpPivoting(A, b, options);
      break;
    case LcpMethod::Lemke:
      if (friction) {
        const LcpProblem pyramid = frictionPyramid(A, b, mu, k);
        solution = solveLcpLemke(pyramid.A, pyramid.b, options);
      } else {
        solution = solveLcpLemke(A, b, options);
      }
      break;
    case LcpMethod::Pgs:
      solution = cone ? solveLcpPgsCone(A, b, mu, options) : solveLcpPgs(A, b, options);
      break;
  }
  last_residual_ = solution.residual;

  // Apply: impulses as they are, forces over the step
  const double scale = velocity_level ? 1.0 : h;
  for (const int index : resting) {
    contacts[index].j = 0.0;
    contacts[index].j_t = Vec3::Zero();
  }
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const ContactRow& row = rows_[r];
    const double impulse = scale * solution.f(static_cast<Index>(r));
    applyImpulse(bodies[row.a], bodies[row.b], row.p, impulse * row.d);
    // Which contact the row belongs to: rows come per contact (cone) or normals first (pyramid)
    const std::size_t contact = cone ? r / 3 : (r < resting.size() ? r : (r - resting.size()) / k);
    Contact& c = contacts[resting[contact]];
    const bool normal = cone ? r % 3 == 0 : r < resting.size();
    if (normal) {
      c.j += impulse;
    } else {
      c.j_t += impulse * row.d;
    }
  }
  return solution.iterations;
}

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
