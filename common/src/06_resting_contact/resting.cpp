// Lab 6 framework: the resting-contact solver World steps with. It builds the rows of the
// resting points, asks the students' functions for the LCP of the chosen formulation, solves it
// with the chosen method and applies the forces (or impulses) it finds (solve(), in
// resting_solve.cpp, which a grade runs in the worker). The matrix-free path
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
  return settings_.toString() + (settings_.matrix_free ? std::string(" (") + matrixFreeSource() + ")" : "") +
         (frictionless ? " (friction ignored)" : "");
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

}  // namespace physlab
