// Lab 6, sections 3-6: the LCP solvers (pivoting, Lemke, projected Gauss-Seidel and its cone variant).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SparseCore>

#include "physlab/lcp.hpp"

namespace physlab {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The pivot limit both pivoting methods share: each contact needs a few pivots, so 10 n is
// plenty for a solver that does not cycle.
int pivotLimit(const LcpOptions& options, Index n) {
  return std::max(options.max_iterations, static_cast<int>(10 * n));
}

void validateOptions(const LcpOptions& options, const std::string& what) {
  requireNonNegative(options.tolerance, what + " options.tolerance");
  requireNonNegative(options.pivot_tolerance, what + " options.pivot_tolerance");
  requireFinite(options.initial, what + " options.initial");
}

// An exact method whose round-off wrecked its answer says so rather than return a wrong f.
// The largest error an exact method may leave: half the digits of pivot_tolerance, on b's scale.
double accuracyBound(const VecX& b, const LcpOptions& options) {
  // (lpNorm<Infinity> is max |b_i|, and 0 for an empty LCP, where maxCoeff() reads past the end)
  return std::sqrt(options.pivot_tolerance) * std::max(1.0, b.lpNorm<Eigen::Infinity>());
}

// The LcpFailure of an answer that lost accuracy to round-off (Lemke runs again on it).
class LostAccuracy : public LcpFailure {
 public:
  using LcpFailure::LcpFailure;
};

void requireAccurate(const LcpSolution& s, const VecX& b, const LcpOptions& options, const std::string& what) {
  if (!(s.residual <= accuracyBound(b, options))) {
    throw LostAccuracy(what + ": lost accuracy after " + std::to_string(s.iterations) + " pivots (residual " +
                     std::to_string(s.residual) + ")");
  }
}

// PGS's first f: the warm start with negative entries raised to 0 when it has n entries, else 0.
// (The cone's tangential entries may be negative; it projects them itself.)
VecX startingForces(const LcpOptions& options, Index n, bool cone = false) {
  if (options.initial.size() != n) return VecX::Zero(n);
  VecX f = options.initial;
  for (Index i = 0; i < n; ++i) {
    if (!cone || i % 3 == 0) f(i) = std::max(0.0, f(i));
  }
  return f;
}

// Solves A_CC x = g for the clamped contacts C as they join and leave. For symmetric A it keeps
// a Cholesky factor A_CC = L L^T up to date, O(k^2) per change (k = |C|), where factoring A_CC
// afresh at each pivot costs O(k^3): a contact joining adds a row to L, one leaving removes its
// row and Givens rotations make L triangular again. L's rows follow the order of contacts().
// Other A (a P-matrix) gets an LU factorization of A_CC at each solve.
class ClampedSolver {
 public:
  ClampedSolver(const MatX& A, double pivot_tolerance, double scale)
      : A_(A), pivot_tolerance_(pivot_tolerance), scale_(scale), position_(static_cast<std::size_t>(A.rows()), -1) {
    const Index n = A.rows();
    contacts_.reserve(static_cast<std::size_t>(n));
    // Symmetric to round-off: a product such as J M^-1 J^T may differ from its transpose there
    symmetric_ = n == 0 || (A - A.transpose()).cwiseAbs().maxCoeff() <= pivot_tolerance * scale;
    if (symmetric_) {
      L_.resize(n, n);
      x_.resize(n);
    }
  }

  const std::vector<Index>& contacts() const { return contacts_; }
  bool contains(Index i) const { return position_[static_cast<std::size_t>(i)] >= 0; }

  // Direction of Dantzig's step: df_d = 1 and df_C solves A_CC df_C = -A_Cd, so that every
  // clamped contact keeps w = 0. Entries of df outside C and d are left as they are.
  void direction(Index d, VecX& df) {
    const Index k = size();
    df(d) = 1.0;
    if (k == 0) return;
    if (symmetric_) {
      x_.head(k) = -A_(contacts_, d);
      const auto L = L_.topLeftCorner(k, k);
      L.triangularView<Eigen::Lower>().solveInPlace(x_.head(k));
      L.transpose().triangularView<Eigen::Upper>().solveInPlace(x_.head(k));
      for (Index p = 0; p < k; ++p) df(contacts_[static_cast<std::size_t>(p)]) = x_(p);
      return;
    }
    const MatX A_CC = A_(contacts_, contacts_);
    const Eigen::PartialPivLU<MatX> lu(A_CC);
    // A tiny pivot (relative to the block's entries) means the clamped contacts cannot hold w = 0
    // on their own: two of them are the same constraint
    if (lu.matrixLU().diagonal().cwiseAbs().minCoeff() <= pivot_tolerance_ * A_CC.cwiseAbs().maxCoeff()) {
      throw LcpFailure("solveLcpPivoting: singular pivot in the clamped contacts' block A_CC while driving contact " +
                       std::to_string(d));
    }
    const VecX df_clamped = lu.solve(-A_(contacts_, d));
    for (Index p = 0; p < k; ++p) df(contacts_[static_cast<std::size_t>(p)]) = df_clamped(p);
  }

  // C gains contact j: L's new row is (l^T, sqrt(s)) with L l = A_Cj and s = a_jj - l^T l, the
  // Schur complement of A_CC. An s at round-off of A's entries means j repeats clamped contacts.
  void add(Index j) {
    const Index k = size();
    if (symmetric_) {
      x_.head(k) = A_(contacts_, j);
      L_.topLeftCorner(k, k).triangularView<Eigen::Lower>().solveInPlace(x_.head(k));
      const double s = A_(j, j) - x_.head(k).squaredNorm();
      if (!(s > pivot_tolerance_ * scale_)) {
        throw LcpFailure("solveLcpPivoting: singular pivot in the clamped contacts' block A_CC when contact " +
                         std::to_string(j) + " joins it");
      }
      L_.row(k).head(k) = x_.head(k).transpose();
      L_(k, k) = std::sqrt(s);
    }
    position_[static_cast<std::size_t>(j)] = k;
    contacts_.push_back(j);
  }

  // C loses contact j: delete its row of L; each row below then has one entry right of the
  // diagonal, which a rotation of two neighbouring columns zeroes (L Q Q^T L^T = L L^T).
  void remove(Index j) {
    const Index k = size(), p = position_[static_cast<std::size_t>(j)];
    if (symmetric_) {
      for (Index i = p; i + 1 < k; ++i) L_.row(i).head(k) = L_.row(i + 1).head(k);
      for (Index r = p; r + 1 < k; ++r) {
        const double a = L_(r, r), c = L_(r, r + 1), rho = std::hypot(a, c);
        const double cosine = a / rho, sine = c / rho;
        for (Index i = r; i + 1 < k; ++i) {
          const double x = L_(i, r), y = L_(i, r + 1);
          L_(i, r) = cosine * x + sine * y;
          L_(i, r + 1) = cosine * y - sine * x;
        }
      }
    }
    contacts_.erase(contacts_.begin() + p);
    for (Index q = p; q + 1 < k; ++q) position_[static_cast<std::size_t>(contacts_[static_cast<std::size_t>(q)])] = q;
    position_[static_cast<std::size_t>(j)] = -1;
  }

 private:
  Index size() const { return static_cast<Index>(contacts_.size()); }

  const MatX& A_;
  double pivot_tolerance_, scale_;
  bool symmetric_ = false;
  MatX L_;                       // symmetric A: top-left k x k, the Cholesky factor of A_CC
  VecX x_;                       // work vector
  std::vector<Index> contacts_;  // C, in L's order
  std::vector<Index> position_;  // position in contacts_, -1 when not clamped
};

}  // namespace

LcpSolution solveLcpPivoting(const MatX& A, const VecX& b, const LcpOptions& options) {
  validateLcp(A, b, "solveLcpPivoting");
  validateOptions(options, "solveLcpPivoting");
  const Index n = b.size();
  const int limit = pivotLimit(options, n);
  // Sign tests on w and dw need A's scale: below pivot_tolerance * scale is round-off
  const MatX A_abs = A.cwiseAbs();
  const double scale = n > 0 ? A_abs.maxCoeff() : 0.0;
  // Contacts couple only through shared bodies: A is mostly zeros, and dw = A df costs its nonzeros
  const Eigen::SparseMatrix<double> A_sparse = A.sparseView(), A_abs_sparse = A_abs.sparseView();
  LcpSolution s;
  s.f = VecX::Zero(n);
  s.w = b;
  ClampedSolver clamped(A, options.pivot_tolerance, scale);  // C: w = 0, f >= 0
  std::vector<Index> free;                                   // NC: f = 0, w >= 0
  free.reserve(static_cast<std::size_t>(n));
  std::vector<bool> seen(static_cast<std::size_t>(n), false);
  VecX df(n), dw(n), dw_noise(n);
  for (Index k = 0; k < n; ++k) {
    // Take the unseen contact with the most negative w (ties: the lowest index): the one the
    // others' forces are least likely to hold up, so later drives disturb fewer clamped forces
    Index d = -1;
    for (Index i = 0; i < n; ++i) {
      if (!seen[static_cast<std::size_t>(i)] && (d < 0 || s.w(i) < s.w(d))) d = i;
    }
    seen[static_cast<std::size_t>(d)] = true;
    // Drive w_d to zero, changing one contact's set at each blocked step (steps that others
    // block may bring w_d to zero on the way: a degenerate contact). A w_d within round-off of
    // the terms it sums (b_d and a_dj f_j, each step adding its own) is zero: large opposing
    // forces on nearly dependent contacts leave w_d = -1e-11 where it is exactly 0
    const auto roundoff = [&](const VecX& f) { return options.pivot_tolerance * (scale + static_cast<double>(n) * (A_abs.row(d).dot(f.cwiseAbs()) + std::abs(b(d)))); };
    while (s.w(d) < -roundoff(s.f)) {
      if (s.iterations >= limit) {
        throw LcpFailure("solveLcpPivoting: pivot limit " + std::to_string(limit) + " reached while driving contact " +
                         std::to_string(d));
      }
      ++s.iterations;
      // Direction: raise f_d by 1, move the clamped forces so that every clamped contact keeps w = 0
      df.setZero();
      clamped.direction(d, df);
      dw.noalias() = A_sparse * df;
      // A dw_i within round-off of the terms it sums is no direction at all, nor one within the
      // round-off the direction carries: the clamped contacts' dw, zero in exact arithmetic
      dw_noise.noalias() = A_abs_sparse * df.cwiseAbs();
      dw_noise *= options.pivot_tolerance;
      double carried = 0.0;
      for (Index i : clamped.contacts()) carried = std::max(carried, std::abs(dw(i)));
      dw_noise = dw_noise.cwiseMax(carried);
      // Find the blocking contact by the ratio test
      double step = kInfinity;
      Index blocking = -1;
      for (Index i : clamped.contacts()) {
        if (df(i) < -options.pivot_tolerance && std::max(s.f(i), 0.0) / -df(i) < step) {
          step = std::max(s.f(i), 0.0) / -df(i);
          blocking = i;
        }
      }
      for (Index i : free) {
        if (dw(i) < -dw_noise(i) && std::max(s.w(i), 0.0) / -dw(i) < step) {
          step = std::max(s.w(i), 0.0) / -dw(i);
          blocking = i;
        }
      }
      // d blocks, ending the drive, also when the step the others allow leaves w_d within
      // round-off of zero (a tie, which goes to d): the contact that blocked would join C with
      // w = 0 where it is degenerate, and d, zero now too, would join C after it; when d's row
      // depends on C's and the blocking one's (A = B B^T of rank below n), that A_CC is singular
      if (dw(d) > dw_noise(d)) {
        const double own = -s.w(d) / dw(d);
        if (own <= step || s.w(d) + step * dw(d) >= -roundoff(s.f + step * df)) {
          step = std::min(step, own);
          blocking = d;
        }
      }
      // Nothing blocks: w_d does not grow with f_d (PSD: the Schur complement of A_CC is zero)
      if (blocking < 0) {
        throw LcpFailure("solveLcpPivoting: singular pivot (dw_d = " + std::to_string(dw(d)) +
                         ") and no contact blocks the step while driving contact " + std::to_string(d) +
                         " after " + std::to_string(s.iterations) + " pivots: the LCP has no solution this method finds");
      }
      s.f += step * df;
      s.w += step * dw;
      // Move the blocking contact to its other set, setting the blocked value to zero exactly
      if (blocking == d) {
        s.w(d) = 0.0;
      } else if (clamped.contains(blocking)) {
        s.f(blocking) = 0.0;
        clamped.remove(blocking);
        free.push_back(blocking);
      } else {
        s.w(blocking) = 0.0;
        free.erase(std::find(free.begin(), free.end(), blocking));
        clamped.add(blocking);
      }
    }
    // Add d to the clamped set when it pushes, else to the free set (f_d = 0, w_d >= 0)
    if (s.f(d) > 0.0) {
      clamped.add(d);
    } else {
      free.push_back(d);
    }
  }
  // Report w from f itself, not from the accumulated steps
  s.f = s.f.cwiseMax(0.0);
  s.w = A * s.f + b;
  s.residual = lcpResidual(A, b, s.f);
  requireAccurate(s, b, options, "solveLcpPivoting");
  return s;
}

namespace {

// How a run of Lemke's method picks the leaving row among rows that tie in the ratio test.
enum class TieRule {
  Lexicographic,  // the lexicographic minimum: never cycles in exact arithmetic
  LargestPivot    // the largest entry of the entering column: the least round-off (Harris)
};

// One run of Lemke's method on a checked LCP with some b_i < 0, ties in the ratio test broken by
// `ties`; `pivots` counts each pivot made. LcpFailure on a ray, at the pivot limit, and on lost accuracy.
LcpSolution lemkeRun(const MatX& A, const VecX& b, const LcpOptions& options, TieRule ties, int& pivots) {
  const Index n = b.size();
  LcpSolution s;
  s.f = VecX::Zero(n);
  // Build the tableau [I | -A | -e | b] of w - A f - e z0 = b; variables 0..n-1 are w, n..2n-1 f, 2n z0
  const Index z0 = 2 * n, rhs = 2 * n + 1;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> T(n, 2 * n + 2);
  T << MatX::Identity(n, n), -A, -VecX::Ones(n), b;
  std::vector<Index> basis(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) basis[static_cast<std::size_t>(i)] = i;
  VecX column(n);
  const auto pivot = [&](Index row, Index entering) {
    T.row(row) /= T(row, entering);
    column = T.col(entering);
    column(row) = 0.0;
    T.noalias() -= column * T.row(row);
    basis[static_cast<std::size_t>(row)] = entering;
  };
  const int limit = pivotLimit(options, n);
  // requireAccurate()'s bound on the answer, applied to the basic values along the way
  const double feasibility = accuracyBound(b, options);

  // Let z0 enter where b is most negative: z0 = -min b makes every w >= 0 (ties: the last such
  // row, the lexicographic minimum of the rows of [b | I])
  Index row = 0;
  for (Index i = 1; i < n; ++i) {
    if (b(i) <= b(row)) row = i;
  }
  Index leaving = basis[static_cast<std::size_t>(row)];
  pivot(row, z0);
  s.iterations = 1;
  ++pivots;

  // Let the complement of the leaving variable enter until z0 leaves
  while (leaving != z0) {
    const Index entering = leaving < n ? leaving + n : leaving - n;
    if (s.iterations >= limit) {
      throw LcpFailure("solveLcpLemke: pivot limit " + std::to_string(limit) + " reached");
    }
    // Find the leaving row by the minimum ratio test. Entries within round-off of zero (n
    // pivot_tolerance times max(1, the column's largest)) are no pivots, and a basic value
    // within round-off below zero counts as the zero it is in exact arithmetic
    const double eligible = options.pivot_tolerance * static_cast<double>(n) * std::max(1.0, T.col(entering).cwiseAbs().maxCoeff());
    const auto ratio = [&](Index i) { return std::max(0.0, T(i, rhs)) / T(i, entering); };
    // A basic value within round-off of zero (n pivot_tolerance times the largest) is zero
    const double zero_value = options.pivot_tolerance * static_cast<double>(n) * std::max(1.0, T.col(rhs).cwiseAbs().maxCoeff());
    double best = kInfinity;
    for (Index i = 0; i < n; ++i) {
      if (T(i, entering) > eligible) best = std::min(best, ratio(i));
    }
    if (best == kInfinity) {
      throw LcpFailure("solveLcpLemke: ray termination after " + std::to_string(s.iterations) + " pivots (variable " +
                       std::to_string(entering) + " can grow without bound): the LCP has no solution Lemke can find");
    }
    std::vector<Index> candidates;
    for (Index i = 0; i < n; ++i) {
      if (T(i, entering) > eligible && ratio(i) <= best + options.pivot_tolerance * std::max(1.0, best)) {
        candidates.push_back(i);
      }
    }
    // z0 leaving among the ties ends the method at once. z0 ties when the step leaves it within
    // round-off of zero: z0 and a degenerate dependent contact reach 0 together in exact
    // arithmetic, and their ratios, quotients of entries that cancelled down to 1e-4, may differ
    // by more than pivot_tolerance (relative); a w leaving instead strands z0 at 1e-16 on a ray
    row = candidates.front();
    for (Index i = 0; i < n; ++i) {
      if (basis[static_cast<std::size_t>(i)] == z0 && T(i, entering) > eligible &&
          T(i, rhs) - best * T(i, entering) <= zero_value) {
        row = i;
      }
    }
    if (basis[static_cast<std::size_t>(row)] != z0 && ties == TieRule::LargestPivot) {
      // Redundant contacts make degenerate rows (basic value 0) whose entry is zero in exact
      // arithmetic and round-off here: the largest entry among the ties is a true pivot
      for (Index i : candidates) {
        if (T(i, entering) > T(row, entering)) row = i;
      }
    }
    // Ties broken lexicographically by the rows of B^-1 (the tableau's first n columns)
    for (Index k = 0; k < n && ties == TieRule::Lexicographic && candidates.size() > 1 &&
                      basis[static_cast<std::size_t>(row)] != z0; ++k) {
      double smallest = kInfinity;
      for (Index i : candidates) smallest = std::min(smallest, T(i, k) / T(i, entering));
      std::vector<Index> kept;
      for (Index i : candidates) {
        if (T(i, k) / T(i, entering) <= smallest + options.pivot_tolerance) kept.push_back(i);
      }
      candidates.swap(kept);
      row = candidates.front();
    }
    leaving = basis[static_cast<std::size_t>(row)];
    pivot(row, entering);
    ++s.iterations;
    ++pivots;
    // The basic values stay >= 0 in exact arithmetic; one far below 0 is round-off that has
    // already wrecked the tableau: stop now rather than pivot on to the limit
    if (T.col(rhs).minCoeff() < -feasibility) {
      throw LostAccuracy("solveLcpLemke: lost accuracy after " + std::to_string(s.iterations) +
                       " pivots (a basic variable fell to " + std::to_string(T.col(rhs).minCoeff()) + ")");
    }
  }

  // Read f from the basic variables (round-off may leave -1e-17: clamp to the contract's f >= 0)
  for (Index i = 0; i < n; ++i) {
    const Index variable = basis[static_cast<std::size_t>(i)];
    if (variable >= n && variable < 2 * n) s.f(variable - n) = std::max(0.0, T(i, rhs));
  }
  s.w = A * s.f + b;
  s.residual = lcpResidual(A, b, s.f);
  requireAccurate(s, b, options, "solveLcpLemke");
  return s;
}

}  // namespace

LcpSolution solveLcpLemke(const MatX& A, const VecX& b, const LcpOptions& options) {
  validateLcp(A, b, "solveLcpLemke");
  validateOptions(options, "solveLcpLemke");
  const Index n = b.size();
  // f = 0 already solves it when b >= 0
  if (n == 0 || b.minCoeff() >= 0.0) {
    LcpSolution s;
    s.f = VecX::Zero(n);
    s.w = b;
    return s;
  }
  // First run: ties broken lexicographically, the rule that never cycles. Redundant contacts (a
  // pyramid's four corners per face) make degenerate rows whose entry in the entering column is
  // zero in exact arithmetic and round-off here; when a tie goes to such a row, dividing by it
  // wrecks the tableau and the run loses accuracy. Then run again from the start with ties going
  // to the largest entry. Either way, iterations counts every pivot made
  int pivots = 0;
  try {
    LcpSolution s = lemkeRun(A, b, options, TieRule::Lexicographic, pivots);
    s.iterations = pivots;
    return s;
  } catch (const LostAccuracy&) {
    LcpSolution s = lemkeRun(A, b, options, TieRule::LargestPivot, pivots);
    s.iterations = pivots;
    return s;
  }
}

LcpSolution solveLcpPgs(const MatX& A, const VecX& b, const LcpOptions& options, std::vector<double>* residuals) {
  validateLcp(A, b, "solveLcpPgs");
  validateOptions(options, "solveLcpPgs");
  const Index n = b.size();
  // Check the diagonal: each update divides by a_ii
  for (Index i = 0; i < n; ++i) {
    if (!(A(i, i) > options.pivot_tolerance)) {
      throw LcpFailure("solveLcpPgs: diagonal entry a_" + std::to_string(i) + std::to_string(i) + " = " +
                       std::to_string(A(i, i)) + " is not positive");
    }
  }
  LcpSolution s;
  // Start from the warm start when there is one, else from zero
  s.f = startingForces(options, n);
  s.residual = lcpResidual(A, b, s.f);
  // Rows of A as contiguous columns: Eigen stores A by columns
  const MatX At = A.transpose();
  while (s.iterations < options.max_iterations) {
    // Sweep: solve row i for f_i with the others fixed, then project onto f_i >= 0
    for (Index i = 0; i < n; ++i) {
      const double w_i = At.col(i).dot(s.f) + b(i);
      s.f(i) = std::max(0.0, s.f(i) - w_i / A(i, i));
    }
    ++s.iterations;
    // lcpResidual()'s value without its input checks, which validateLcp() made once already
    s.residual = (A * s.f + b).cwiseMin(s.f).lpNorm<Eigen::Infinity>();
    if (residuals != nullptr) residuals->push_back(s.residual);
    if (s.residual <= options.tolerance) break;
  }
  s.w = A * s.f + b;
  return s;
}

LcpSolution solveLcpPgsCone(const MatX& A, const VecX& b, const VecX& mu, const LcpOptions& options) {
  validateLcp(A, b, "solveLcpPgsCone");
  validateOptions(options, "solveLcpPgsCone");
  const Index n = b.size();
  if (n % 3 != 0) {
    throw InvalidInput("solveLcpPgsCone matrix A is " + std::to_string(n) + " x " + std::to_string(n) +
                       ", not a multiple of 3 (blocks f_n, f_t, f_o per contact)");
  }
  requireSize(mu.size(), n / 3, "solveLcpPgsCone friction coefficients mu");
  for (Index k = 0; k < mu.size(); ++k) {
    requireNonNegative(mu(k), "solveLcpPgsCone friction coefficient mu(" + std::to_string(k) + ")");
  }
  for (Index i = 0; i < n; ++i) {
    if (!(A(i, i) > options.pivot_tolerance)) {
      throw LcpFailure("solveLcpPgsCone: diagonal entry a_" + std::to_string(i) + std::to_string(i) + " = " +
                       std::to_string(A(i, i)) + " is not positive");
    }
  }
  LcpSolution s;
  // Start from the warm start when there is one, inside the cones, else from zero
  s.f = startingForces(options, n, true);
  for (Index c = 0; c < n; c += 3) {
    const double radius = mu(c / 3) * s.f(c), length = s.f.segment<2>(c + 1).norm();
    if (length > radius) s.f.segment<2>(c + 1) *= length > 0.0 ? radius / length : 0.0;
  }
  s.residual = kInfinity;
  const MatX At = A.transpose();
  while (s.iterations < options.max_iterations) {
    double largest = 0.0;
    for (Index c = 0; c < n; c += 3) {
      const Vec3 before = s.f.segment<3>(c);
      // Update the normal force as in PGS: f_n >= 0
      s.f(c) = std::max(0.0, s.f(c) - (At.col(c).dot(s.f) + b(c)) / A(c, c));
      // Update the tangential pair together, aiming at no sliding (w_t = w_o = 0): one step
      // along -w_T scaled by the largest eigenvalue of its 2 x 2 block, the same for both
      // entries, so that on the rim friction opposes the sliding w_T exactly (Coulomb)
      const double a_tt = A(c + 1, c + 1), a_oo = A(c + 2, c + 2), a_to = 0.5 * (A(c + 1, c + 2) + A(c + 2, c + 1));
      const double lambda = 0.5 * (a_tt + a_oo) + std::hypot(0.5 * (a_tt - a_oo), a_to);
      const Eigen::Vector2d w_T(At.col(c + 1).dot(s.f) + b(c + 1), At.col(c + 2).dot(s.f) + b(c + 2));
      s.f.segment<2>(c + 1) -= w_T / lambda;
      // Project the tangential force onto the disc |(f_t, f_o)| <= mu f_n
      const double radius = mu(c / 3) * s.f(c);
      const double length = s.f.segment<2>(c + 1).norm();
      if (length > radius) s.f.segment<2>(c + 1) *= radius / length;
      // Measure the change as a change of w (|df_i| a_ii), comparable across contacts
      for (Index i = 0; i < 3; ++i) largest = std::max(largest, std::abs(s.f(c + i) - before(i)) * A(c + i, c + i));
    }
    ++s.iterations;
    s.residual = largest;
    if (largest <= options.tolerance) break;
  }
  s.w = A * s.f + b;
  return s;
}

}  // namespace physlab
