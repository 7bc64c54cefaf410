/// \file lcp.hpp
/// \brief Lab 6: linear complementarity problems and the solvers that find resting-contact forces.
///
/// Resting contact asks for forces \f$f_i\f$ at the contact points such that the separation
/// distances \f$d_i\f$ neither accelerate into each other nor are held together by glue (lecture
/// 002): with \f$\ddot d = A f + b\f$,
/// \f[ \ddot d_i \ge 0, \qquad f_i \ge 0, \qquad f_i\, \ddot d_i = 0. \f]
/// Written with \f$w = \ddot d\f$ this is the linear complementarity problem LCP(A, b):
/// find \f$f\f$ with \f$w = A f + b \ge 0,\ f \ge 0,\ f^T w = 0\f$. For symmetric positive
/// semidefinite \f$A\f$ it is also the quadratic program \f$\min_f \tfrac12 f^T A f + b^T f\f$
/// subject to \f$f \ge 0\f$ (lecture 003), whose optimality conditions are exactly the three above.
///
/// Three solvers, each returning f, w, the work it did and its residual:
/// - pivoting (Dantzig, as Baraff uses it): adds one contact at a time, keeping every contact
///   seen so far either clamped (\f$w_i = 0\f$, \f$f_i \ge 0\f$) or free (\f$f_i = 0\f$, \f$w_i \ge 0\f$);
///   exact up to round-off; needs A positive semidefinite with nonsingular pivots;
/// - Lemke's complementary pivoting: one artificial variable \f$z_0\f$ and a covering vector, pivoting
///   until \f$z_0\f$ leaves the basis; exact; handles non-symmetric matrices such as the friction
///   pyramid's, and stops on a *ray* when it can find no solution;
/// - projected Gauss-Seidel (PGS): \f$f_i \leftarrow \max(0,\ f_i - w_i / a_{ii})\f$ sweep after sweep;
///   cheap per sweep, approximate, slow on ill-conditioned (high mass ratio) problems. On symmetric
///   positive definite A each update minimizes the QP objective along \f$f_i\f$ within \f$f_i \ge 0\f$,
///   so the objective never increases from one sweep to the next (the residual below may: it is
///   not monotone). The cone variant projects each contact's (normal, tangent, tangent) block onto
///   the friction cone.
///
/// Glossary:
/// | symbol | code | meaning |
/// |---|---|---|
/// | \f$A\f$ | `A` | n x n matrix, \f$a_{ij}\f$ = effect of force j on \f$\ddot d_i\f$ |
/// | \f$b\f$ | `b` | n-vector, \f$\ddot d\f$ with all forces zero |
/// | \f$f\f$ | `f` | unknown forces (or impulses), \f$\ge 0\f$ |
/// | \f$w\f$ | `w` | \f$A f + b\f$, \f$\ge 0\f$ |
/// | \f$\mu\f$ | `mu` | Coulomb friction coefficient per contact, \f$\ge 0\f$ |
#pragma once

#include <string>
#include <vector>

#include "physlab/dense_lu.hpp"
#include "physlab/error.hpp"
#include "physlab/math.hpp"

namespace physlab {

/// A solver found no solution: Lemke's method ended on a ray, a pivot was singular, or the pivot
/// limit was reached. The message says which and after how many pivots.
class LcpFailure : public NumericalFailure {
 public:
  using NumericalFailure::NumericalFailure;
};

/// Knobs of the LCP solvers.
/// Both tolerances must be >= 0 (InvalidInput otherwise); 0 is allowed (PGS then runs every sweep
/// unless it lands exactly on a solution).
struct LcpOptions {
  int max_iterations = 100;       ///< PGS: largest number of sweeps; pivoting, Lemke: pivot limit is max(this, 10 n)
  double tolerance = 1e-10;       ///< PGS: stop when lcpResidual() <= tolerance; PGS cone: when no change exceeds it
  /// Pivoting and Lemke: pivots smaller than this in magnitude, relative to the entries they come
  /// from, are singular (LcpFailure, or not eligible in a ratio test), and ratios this close
  /// (relative) are ties; PGS: smallest allowed a_ii
  double pivot_tolerance = 1e-12;
  /// PGS and PGS cone: the f to start from when it has n entries (warm starting, e.g. last step's
  /// forces); its negative normal entries count as 0 and the cone's tangential pairs are first
  /// projected onto their discs. Otherwise, and for pivoting and Lemke, the solvers start from 0.
  VecX initial;
};

/// What a solver returns. An empty LCP (n = 0: no contact) is valid, not an error: every solver
/// returns empty f and w, pivoting and Lemke with no pivot and residual 0.
struct LcpSolution {
  VecX f;              ///< the forces, >= 0 (PGS cone: the normal ones; tangential ones have either sign)
  VecX w;              ///< A f + b
  int iterations = 0;  ///< pivots (pivoting, Lemke; 0 when b >= 0) or sweeps (PGS)
  double residual = 0.0;  ///< lcpResidual(A, b, f) of the returned f (PGS cone: see solveLcpPgsCone())
};

/// \name Framework
///@{

/// Checks that A is square and finite, b finite and of A's size; InvalidInput naming `what`
/// ("LCP matrix A is 3 x 4, not square", "LCP vector b has 2 entries, A is 3 x 3", ...).
void validateLcp(const MatX& A, const VecX& b, const std::string& what);

/// The complementarity residual \f$\max_i |\min(f_i, w_i)|\f$ with \f$w = A f + b\f$ (zero exactly at a
/// solution; it measures negative forces, negative \f$w\f$ and \f$f_i w_i \ne 0\f$ alike).
double lcpResidual(const MatX& A, const VecX& b, const VecX& f);
///@}

/// \name Student functions (Lab 6)
///@{

/// Dantzig's pivoting method as Baraff describes it: contacts are added one at a time, each time
/// the one not yet taken with the most negative \f$w_d\f$ (ties: the lowest index; in index order
/// Baraff's, on the 55-cube pyramid's LCP, needed 5388 pivots, this order 600: the contacts that
/// carry the most load are clamped first, and later drives move fewer clamped forces); while the new contact's \f$w_d < 0\f$ (beyond round-off of the terms it sums: below
/// \f$-\text{pivot\_tolerance}\,(\max|a_{ij}| + n(\sum_j |a_{dj}||f_j| + |b_d|))\f$), raise \f$f_d\f$ along the direction that keeps every
/// clamped contact at \f$w = 0\f$ and every free contact at \f$f = 0\f$, by the largest step that keeps
/// all \f$f \ge 0\f$ and \f$w \ge 0\f$; the contact that blocks the step changes set (d itself blocking
/// ends the drive; ties go to d, and a step that leaves \f$w_d\f$ within that round-off of zero is a
/// tie: d ends the drive with \f$w_d = 0\f$, the contact that blocked keeping its set). Requires A symmetric positive semidefinite, singular ones (a
/// contact counted twice) included, or a P-matrix (any A on which the clamped subsystems stay
/// nonsingular works). Each step is one pivot (`iterations`). The pivot limit, max(max_iterations,
/// 10 n), is a guard against cycling on round-off, not a bound of the method: every contact takes
/// one drive of at least one pivot, and each further pivot moves a contact between the sets; no
/// limit polynomial in n holds for every problem (Murty's example takes \f$2^n - 1\f$), so 10 n
/// allows ten set changes per contact, six times the 1.5 per contact the pyramid needs.
/// Throws LcpFailure ("... singular pivot ...") when nothing blocks the step (\f$w_d\f$ does not grow
/// with \f$f_d\f$: e.g. A = [[1, -1], [-1, 1]], b < 0, which has no solution), when the clamped block
/// \f$A_{CC}\f$ is singular, and when the pivot limit is reached. InvalidInput as validateLcp().
/// Where the solution is unique (A positive definite, or a P-matrix) the result is it up to
/// round-off; on singular PSD A it is one of the solutions (w and \f$A f\f$ are unique). An answer
/// whose lcpResidual() exceeds \f$\sqrt{\text{pivot\_tolerance}}\, \max(1, \max_i |b_i|)\f$ (round-off
/// wrecked it) is never returned: LcpFailure ("... lost accuracy ...").
/// Handout: Lab 6, section 3.
LcpSolution solveLcpPivoting(const MatX& A, const VecX& b, const LcpOptions& options = {});

/// Lemke's complementary pivoting with covering vector \f$e = (1, \dots, 1)\f$: returns f = 0 when
/// \f$b \ge 0\f$, else pivots on the tableau \f$w - A f - e z_0 = b\f$ from the most negative
/// \f$b_i\f$ (ties: the last such row), choosing the entering variable as the complement of the
/// one that left and the leaving one by the lexicographic minimum ratio test, until \f$z_0\f$
/// leaves (when \f$z_0\f$ ties for leaving, it leaves; it ties also when the step leaves it within
/// round-off of zero, at most n pivot_tolerance times max(1, the largest basic value)). The test: with the tableau's right-hand
/// side \f$\bar b = B^{-1} b\f$, its first n columns \f$B^{-1}\f$ (they start as I) and the entering
/// column \f$\bar a = B^{-1} a_e\f$, the leaving row r is the lexicographic minimum of
/// \f[ \frac{1}{\bar a_i}\,\big(\bar b_i,\ (B^{-1})_{i0},\ \dots,\ (B^{-1})_{i,n-1}\big) \quad\text{over } \bar a_i > 0, \f]
/// compared entry by entry (the ratios tie within pivot_tolerance, relative; later entries
/// within pivot_tolerance). The rows of \f$B^{-1}\f$ are independent, so no two of these vectors
/// are equal and the minimum is unique; each row of \f$(\bar b, B^{-1})\f$ stays lexicographically
/// positive: the plain ratio test on the perturbed \f$b + (\varepsilon, \varepsilon^2, \dots, \varepsilon^n)\f$
/// for small \f$\varepsilon > 0\f$, a problem with no ties: no almost-complementary basis repeats, and
/// the method ends, at a solution or on a ray, after finitely many pivots (in exact arithmetic). Throws LcpFailure("... ray
/// termination ...") when no variable can leave (the LCP has no solution Lemke can find; on
/// positive semidefinite or P-matrices, it has none at all) and on reaching the pivot limit.
/// InvalidInput as validateLcp().
/// An entry of the entering column within round-off of zero, at most n pivot_tolerance times
/// max(1, the column's largest magnitude), is no pivot, and a basic value within round-off below
/// zero counts as 0 in the ratios (exact arithmetic keeps it \f$\ge 0\f$). Redundant contacts (four
/// corners of a face are three constraints; A is singular) make degenerate rows (basic value 0)
/// whose entry in the entering column is zero in exact arithmetic and round-off in the tableau,
/// larger than that bound after many pivots; when such a row wins the lexicographic tie-break,
/// dividing by its entry wrecks the tableau and the run loses accuracy. Lemke then runs again
/// from the start, with ties (z0 still first) going to the row with the largest entry of the
/// entering column (Harris' choice: the least round-off; no proof against cycling, which the
/// pivot limit bounds). (The lexicographic run loses accuracy on the 55-cube pyramid's LCP after
/// 370 pivots; the second run solves it in 203 more, and the 210-cube one's in 840 after 619.)
/// iterations counts the pivots of both runs; each stops at the pivot limit. Like pivoting,
/// never returns an answer that lost accuracy: LcpFailure ("... lost accuracy ...") when the
/// answer's residual exceeds the bound given for pivoting, and as soon as a basic variable falls
/// below minus that bound (the tableau is already wrecked, and pivoting on would only reach the limit).
/// Handout: Lab 6, section 4.
LcpSolution solveLcpLemke(const MatX& A, const VecX& b, const LcpOptions& options = {});

/// Projected Gauss-Seidel from f = 0 (or options.initial): each sweep sets, for i = 0..n-1 in order,
/// \f$f_i \leftarrow \max(0,\ f_i - w_i / a_{ii})\f$ with \f$w_i\f$ from the current f; after each sweep
/// it computes lcpResidual() and stops when it is <= options.tolerance or after
/// options.max_iterations sweeps (no error: the residual says how good f is). `iterations` is the
/// number of sweeps run; when `residuals` is given, appends the residual after each sweep, so it
/// gains `iterations` entries, the last equal to the returned `residual` (with max_iterations <= 0
/// no sweep runs and `residual` is the start's). Deterministic: a run
/// with max_iterations = k repeats the first k sweeps of any longer run. Throws LcpFailure when
/// some \f$a_{ii} \le\f$ options.pivot_tolerance, InvalidInput as validateLcp().
/// Handout: Lab 6, section 5.
LcpSolution solveLcpPgs(const MatX& A, const VecX& b, const LcpOptions& options = {},
                        std::vector<double>* residuals = nullptr);

/// PGS with the quadratic friction cone: unknowns in blocks of three per contact
/// \f$(f_n, f_t, f_o)\f$, n = 3 mu.size(), from f = 0 (or options.initial). Each sweep updates, contact by contact, the normal as in
/// solveLcpPgs(), then the tangential pair \f$f_T = (f_t, f_o)\f$ together with \f$w_T = (w_t, w_o)\f$
/// from the current f: \f$f_T \leftarrow f_T - w_T / \lambda_T\f$, \f$\lambda_T\f$ the larger eigenvalue of
/// the (symmetrised) 2 x 2 tangential block of A, and projects \f$f_T\f$ onto the disc of radius
/// \f$\mu f_n\f$ (scaled towards 0 when longer). One step length for both entries (not
/// \f$w_t / a_{tt}\f$, \f$w_o / a_{oo}\f$ apart) makes a fixed point obey Coulomb's law: sticking with
/// \f$w_T = 0\f$ inside the cone, or \f$|f_T| = \mu f_n\f$ exactly opposite the sliding \f$w_T\f$; apart
/// steps would tilt the friction towards the stiffer direction. Stops when no entry changes by
/// more than options.tolerance (scaled by \f$a_{ii}\f$: \f$|\Delta f_i|\, a_{ii}\f$, a velocity or
/// acceleration change) or after options.max_iterations
/// sweeps (none when max_iterations <= 0). `residual` in the result is that largest change in the
/// last sweep (infinity when no sweep ran); `w` is A f + b. With all \f$\mu = 0\f$ it runs PGS's updates on the normal rows.
/// InvalidInput as validateLcp(), and when n is not a multiple of 3 ("not a multiple of 3"), when
/// mu.size() != n / 3 (naming "mu") and when some mu(k) is negative or not finite (naming "mu(k)");
/// LcpFailure when some \f$a_{ii} \le\f$ options.pivot_tolerance.
/// Handout: Lab 6, section 6.
LcpSolution solveLcpPgsCone(const MatX& A, const VecX& b, const VecX& mu, const LcpOptions& options = {});
///@}

}  // namespace physlab
