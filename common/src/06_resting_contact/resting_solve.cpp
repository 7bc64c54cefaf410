// Lab 6 framework: a step of the resting-contact solver: the rows of the resting points, the LCP
// of the chosen formulation from the students' contactMatrix() and velocityBias() (or
// accelerationBias()), its solution by the chosen method, and the impulses (or forces) applied.
//
// In a grade this file runs in the worker, beside the submitted functions it calls (IN_WORKER in
// CMakeLists.txt; docs/grading.md, "Where submitted code runs"): a step's matrix A is dense, one
// row per constraint, so a pyramid's A would cross the wire three times a step (hundreds of
// kilobytes each way); here only the step's bodies and contacts cross.
#include <vector>

#include "physlab/resting.hpp"

namespace physlab {

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
