// Lab 6, sections 3-6: the LCP solvers (pivoting, Lemke, projected Gauss-Seidel and its cone variant).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "physlab/lcp.hpp"

namespace physlab {

LcpSolution solveLcpPivoting(const MatX& A, const VecX& b, const LcpOptions& options) {
  // TODO(student): validateLcp(A, b, "solveLcpPivoting"), options.tolerance and pivot_tolerance >= 0 (InvalidInput);
  // TODO(student): start from f = 0, w = b, with no contact clamped (C) or free (NC).
  // TODO(student): then take each contact once: n times, the one d not yet taken with the most negative w.
  // Sign tests on w and dw need A's scale: below pivot_tolerance * scale is round-off
  // TODO(student): scale = the largest |a_ij|.
  // Contacts couple only through shared bodies: A is mostly zeros, and dw = A df costs its nonzeros
  // TODO(student): optional for speed: A.sparseView() once, then dw = A_sparse * df (and the same for |A| |df|).
  // Take the unseen contact with the most negative w (ties: the lowest index): the one the
  // others' forces are least likely to hold up, so later drives disturb fewer clamped forces
  // TODO(student): d = argmin of w_i over the contacts not yet taken (strict <, scanning i = 0..n-1); mark it taken.
  // Drive w_d to zero, changing one contact's set at each blocked step (steps that others
  // block may bring w_d to zero on the way: a degenerate contact). A w_d within round-off of
  // the terms it sums (b_d and a_dj f_j, each step adding its own) is zero: large opposing
  // forces on nearly dependent contacts leave w_d = -1e-11 where it is exactly 0
  // TODO(student): while w_d < -options.pivot_tolerance * (scale + n (sum_j |a_dj| |f_j| + |b_d|)) take a step, a pivot:
  // TODO(student): count it, and throw LcpFailure past max(options.max_iterations, 10 n).
  // Direction: raise f_d by 1, move the clamped forces so that every clamped contact keeps w = 0
  // TODO(student): df_d = 1, df_C solves A_CC df_C = -A_Cd (LcpFailure on an LU pivot of A_CC below
  // TODO(student): pivot_tolerance times its largest entry); df = 0 elsewhere; dw = A df.
  // TODO(student): factoring A_CC afresh at each pivot costs O(|C|^3): fine for the tests; for large
  // TODO(student): symmetric A keep a Cholesky factor L of A_CC up to date instead (handout, section 3).
  // A dw_i within round-off of the terms it sums is no direction at all, nor one within the
  // round-off the direction carries: the clamped contacts' dw, zero in exact arithmetic
  // TODO(student): noise_i = max(pivot_tolerance * sum_j |a_ij| |df_j|, max over clamped k of |dw_k|);
  // TODO(student): only |dw_i| > noise_i counts as a sign.
  // Find the blocking contact by the ratio test
  // TODO(student): i in C at f_i / -df_i when df_i < -pivot_tolerance; i in NC at w_i / -dw_i when dw_i < -noise_i;
  // TODO(student): the smallest s wins.
  // d blocks, ending the drive, also when the step the others allow leaves w_d within
  // round-off of zero (a tie, which goes to d): the contact that blocked would join C with
  // w = 0 where it is degenerate, and d, zero now too, would join C after it; when d's row
  // depends on C's and the blocking one's (A = B B^T of rank below n), that A_CC is singular
  // TODO(student): when dw_d > noise_d, d blocks at min(s, -w_d / dw_d) if -w_d / dw_d <= s or w_d + s dw_d is at
  // TODO(student): least minus the drive's round-off bound (with f + s df in it): ties go to d.
  // Nothing blocks: w_d does not grow with f_d (PSD: the Schur complement of A_CC is zero)
  // TODO(student): throw LcpFailure("... singular pivot ...") rather than step by infinity.
  // Move the blocking contact to its other set, setting the blocked value to zero exactly
  // TODO(student): f += s df, w += s dw; d blocks: w_d = 0; C -> NC: f_j = 0; NC -> C: w_j = 0.
  // Add d to the clamped set when it pushes, else to the free set (f_d = 0, w_d >= 0)
  // TODO(student): f_d > 0: d joins C; otherwise NC.
  // Report w from f itself, not from the accumulated steps
  // TODO(student): w = A f + b, residual = lcpResidual(A, b, f), iterations = pivots; LcpFailure("... lost accuracy ...")
  // TODO(student): when residual > sqrt(pivot_tolerance) * max(1, max |b_i|) (n = 0 is valid: max |b_i| = 0 there,
  // TODO(student): b.lpNorm<Eigen::Infinity>(); maxCoeff() of an empty vector reads past its end).
  notImplemented("solveLcpPivoting", "Lab 6 handout, section 3", A, b, options);
}

LcpSolution solveLcpLemke(const MatX& A, const VecX& b, const LcpOptions& options) {
  // TODO(student): validateLcp(A, b, "solveLcpLemke"), options.tolerance and pivot_tolerance >= 0 (InvalidInput).
  // f = 0 already solves it when b >= 0
  // TODO(student): return f = 0, w = b, no pivots.
  // Build the tableau [I | -A | -e | b] of w - A f - e z0 = b; variables 0..n-1 are w, n..2n-1 f, 2n z0
  // TODO(student): n x (2n + 2) tableau; the basis starts as w_0..w_{n-1}; a pivot on (row, column) divides the row
  // TODO(student): by its entry and subtracts multiples of it from every other row, and puts the column's variable in the basis.
  // requireAccurate()'s bound on the answer, applied to the basic values along the way
  // TODO(student): bound = sqrt(pivot_tolerance) * max(1, max |b_i|), the one the answer is checked against.
  // Let z0 enter where b is most negative: z0 = -min b makes every w >= 0 (ties: the last such
  // row, the lexicographic minimum of the rows of [b | I])
  // TODO(student): pivot on (argmin b, z0); the w that left says which variable enters next.
  // Let the complement of the leaving variable enter until z0 leaves
  // TODO(student): w_i <-> f_i; count pivots, LcpFailure past max(options.max_iterations, 10 n).
  // Find the leaving row by the minimum ratio test. Entries within round-off of zero (n
  // pivot_tolerance times max(1, the column's largest)) are no pivots, and a basic value
  // within round-off below zero counts as the zero it is in exact arithmetic
  // TODO(student): eligible rows: entry > n * pivot_tolerance * max(1, largest |entry| of the column); ratio
  // TODO(student): max(0, right-hand side) / entry; none eligible: throw LcpFailure("... ray termination ...").
  // TODO(student): ties: ratios within pivot_tolerance * max(1, smallest ratio) of the smallest.
  // z0 leaving among the ties ends the method at once. z0 ties when the step leaves it within
  // round-off of zero: z0 and a degenerate dependent contact reach 0 together in exact
  // arithmetic, and their ratios, quotients of entries that cancelled down to 1e-4, may differ
  // by more than pivot_tolerance (relative); a w leaving instead strands z0 at 1e-16 on a ray
  // TODO(student): z0's row leaves when its entry is eligible and its right-hand side minus the smallest ratio
  // TODO(student): times its entry is at most n * pivot_tolerance * max(1, largest |right-hand side|).
  // Redundant contacts make degenerate rows (basic value 0) whose entry is zero in exact
  // arithmetic and round-off here: the largest entry among the ties is a true pivot
  // TODO(student): second run: the tied row with the largest entry of the entering column.
  // Ties broken lexicographically by the rows of B^-1 (the tableau's first n columns)
  // TODO(student): first run: compare the tied rows' entries in columns 0, 1, ... divided by the pivot entry, keeping
  // TODO(student): the smallest (within pivot_tolerance).
  // The basic values stay >= 0 in exact arithmetic; one far below 0 is round-off that has
  // already wrecked the tableau: stop now rather than pivot on to the limit
  // TODO(student): after each pivot, LcpFailure("... lost accuracy ...") when some right-hand side < -bound.
  // Read f from the basic variables (round-off may leave -1e-17: clamp to the contract's f >= 0)
  // TODO(student): f_i = right-hand side of the row where f_i is basic, 0 when nonbasic; w = A f + b; residual;
  // TODO(student): LcpFailure("... lost accuracy ...") as in pivoting.
  // First run: ties broken lexicographically, the rule that never cycles. Redundant contacts (a
  // pyramid's four corners per face) make degenerate rows whose entry in the entering column is
  // zero in exact arithmetic and round-off here; when a tie goes to such a row, dividing by it
  // wrecks the tableau and the run loses accuracy. Then run again from the start with ties going
  // to the largest entry. Either way, iterations counts every pivot made
  // TODO(student): write the steps above as one run taking the tie rule: first lexicographic; when it lost
  // TODO(student): accuracy (not on a ray or at the limit), again from the start with ties to the largest entry;
  // TODO(student): iterations = the pivots of both runs.
  notImplemented("solveLcpLemke", "Lab 6 handout, section 4", A, b, options);
}

LcpSolution solveLcpPgs(const MatX& A, const VecX& b, const LcpOptions& options, std::vector<double>* residuals) {
  // TODO(student): validateLcp(A, b, "solveLcpPgs"); options: tolerances >= 0, initial finite (InvalidInput).
  // Check the diagonal: each update divides by a_ii
  // TODO(student): LcpFailure when some a_ii <= options.pivot_tolerance.
  // Start from the warm start when there is one, else from zero
  // TODO(student): f = options.initial with negative entries set to 0 when it has n entries, else f = 0.
  // Rows of A as contiguous columns: Eigen stores A by columns
  // TODO(student): optional for speed: At = A.transpose() once, then At.col(i) is row i.
  // Sweep: solve row i for f_i with the others fixed, then project onto f_i >= 0
  // TODO(student): for i = 0..n-1: w_i = A.row(i) f + b_i with the newest f; f_i = max(0, f_i - w_i / a_ii).
  // TODO(student): after each sweep: residual = lcpResidual(A, b, f), append it to *residuals when given,
  // TODO(student): stop when it is <= options.tolerance or after options.max_iterations sweeps (none when <= 0:
  // TODO(student): residual = the start's); w = A f + b of the f returned.
  notImplemented("solveLcpPgs", "Lab 6 handout, section 5", A, b, options, residuals);
}

LcpSolution solveLcpPgsCone(const MatX& A, const VecX& b, const VecX& mu, const LcpOptions& options) {
  // TODO(student): validateLcp and the options, as in PGS;
  // TODO(student): InvalidInput when n is not a multiple of 3, mu.size() != n / 3 or some mu < 0;
  // TODO(student): LcpFailure on a diagonal entry <= pivot_tolerance, as in PGS.
  // Start from the warm start when there is one, inside the cones, else from zero
  // TODO(student): f = options.initial (normal entries raised to >= 0) when it has n entries, else 0; then
  // TODO(student): scale each (f_t, f_o) longer than mu f_n down to that length.
  // Update the normal force as in PGS: f_n >= 0
  // TODO(student): per contact c (entries 3c, 3c + 1, 3c + 2): f_n = max(0, f_n - w_n / a_nn).
  // Update the tangential pair together, aiming at no sliding (w_t = w_o = 0): one step
  // along -w_T scaled by the largest eigenvalue of its 2 x 2 block, the same for both
  // entries, so that on the rim friction opposes the sliding w_T exactly (Coulomb)
  // TODO(student): w_T = (w_t, w_o) with the new f_n; lambda = larger eigenvalue of [[a_tt, a_to], [a_ot, a_oo]]
  // TODO(student): (symmetrised); (f_t, f_o) -= w_T / lambda.
  // Project the tangential force onto the disc |(f_t, f_o)| <= mu f_n
  // TODO(student): when longer than mu f_n, scale (f_t, f_o) down to that length.
  // Measure the change as a change of w (|df_i| a_ii), comparable across contacts
  // TODO(student): stop when the sweep's largest |df_i| a_ii <= options.tolerance (that is the residual) or after max_iterations
  // TODO(student): (none when <= 0: residual infinity when no sweep ran).
  notImplemented("solveLcpPgsCone", "Lab 6 handout, section 6", A, b, mu, options);
}

}  // namespace physlab
