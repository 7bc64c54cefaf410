// Lab 6 framework: the resting-contact solver World steps with. It builds the rows of the
// resting points, asks the students' functions for the LCP of the chosen formulation, solves it
// with the chosen method and applies the forces (or impulses) it finds. The matrix-free path
// (solveConeMatrixFree()) is in common/answers/06_resting_contact/, or in a student's copy before
// Lab 6 is released its stand-in in common/unreleased/06_resting_contact/ (cmake/PhysLab.cmake).
#include <algorithm>
#include <cmath>
#include <sstream>
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

double LcpContactSolver::normalVelocity(const std::vector<ContactBody>& bodies, const Contact& c) {
  const ContactBody &A = bodies[static_cast<std::size_t>(c.a)], &B = bodies[static_cast<std::size_t>(c.b)];
  return c.n.dot(A.v + A.omega.cross(c.p - A.x) - B.v - B.omega.cross(c.p - B.x));
}

double LcpContactSolver::bounceBias(double bias, const std::vector<ContactBody>& bodies, const Contact& c) {
  if (c.kind != ContactKind::Colliding) return bias;
  return std::min(bias, normalVelocity(bodies, c) + c.epsilon * c.v_rel_minus);
}

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

}  // namespace physlab
