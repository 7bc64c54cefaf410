/// \file resting.hpp
/// \brief Lab 6: resting-contact forces from an LCP, at the acceleration level (Baraff) and at
/// the velocity level (impulses over a step), with Coulomb friction as a pyramid or a cone.
///
/// Two bodies touch at \f$p_i\f$ with normal \f$\hat n_i\f$ from B to A. Their separation
/// \f$d_i(t) = \hat n_i \cdot (p_a(t) - p_b(t))\f$ is zero and not changing; the contact force
/// \f$f_i \hat n_i\f$ must keep it from becoming negative (lecture 002):
/// \f[ \ddot d_i = \hat n_i \cdot (\ddot p_a - \ddot p_b) + 2 \dot{\hat n}_i \cdot (\dot p_a - \dot p_b),
///     \qquad \ddot p = \dot v + \dot\omega \times r + \omega \times (\omega \times r). \f]
/// The forces enter linearly: \f$\ddot d = A f + b\f$ with
/// \f[ a_{ij} = \hat n_i \cdot \big( s_{aj} (m_a^{-1} \hat n_j + (I_a^{-1} (r_{aj} \times \hat n_j)) \times r_{ai})
///            - s_{bj} (m_b^{-1} \hat n_j + (I_b^{-1} (r_{bj} \times \hat n_j)) \times r_{bi}) \big), \f]
/// where \f$s_{kj}\f$ = +1 when body k is contact j's A, -1 when it is its B, 0 otherwise, and
/// \f$r_{kj} = p_j - x_k\f$; and with every contact force zero,
/// \f[ b_i = \hat n_i \cdot (\ddot p^0_a - \ddot p^0_b) + 2 \dot{\hat n}_i \cdot (\dot p_a - \dot p_b), \quad
///     \ddot p^0 = \frac{F}{m} + \big(I^{-1}(\tau + L \times \omega)\big) \times r + \omega \times (\omega \times r), \quad
///     \dot{\hat n}_i = \omega_b \times \hat n_i \f]
/// (the normal turns with body B, whose face it is). The same \f$A\f$ maps impulses to velocity
/// changes, so a velocity-level step solves \f$v^+ = A \lambda + b\f$ with \f$b_i\f$ the relative normal
/// velocity now, minus a Baumgarte term \f$\frac{\beta}{h}\max(0, depth_i - slop)\f$ that pushes
/// overlapping bodies apart over a few steps.
///
/// Friction, velocity level: the pyramid replaces the cone by k directions \f$d_{il}\f$ in the
/// tangent plane and becomes the larger LCP (Stewart and Trinkle)
/// \f[ \begin{pmatrix} w_n \\ w_d \\ w_\gamma \end{pmatrix} =
///     \begin{pmatrix} A_{nn} & A_{nd} & 0 \\ A_{dn} & A_{dd} & E \\ \mu & -E^T & 0 \end{pmatrix}
///     \begin{pmatrix} \lambda_n \\ \beta \\ \gamma \end{pmatrix} + \begin{pmatrix} b_n \\ b_d \\ 0 \end{pmatrix},
///     \qquad 0 \le w \perp (\lambda_n, \beta, \gamma) \ge 0, \f]
/// E holding a column of k ones per contact and \f$\mu\f$ the diagonal of friction coefficients:
/// \f$\gamma_i\f$ is contact i's sliding speed, and a sliding contact's friction lies on the
/// pyramid's boundary opposite its motion (maximal dissipation). The cone is solved by PGS with
/// a projection per contact (solveLcpPgsCone()).
///
/// Glossary:
/// | symbol | code | meaning |
/// |---|---|---|
/// | \f$A, b\f$ | `A`, `b` | \f$\ddot d = A f + b\f$ (or \f$v^+ = A\lambda + b\f$) |
/// | \f$f_i\f$ | `f` | normal contact force [N] (acceleration level) |
/// | \f$\lambda_i\f$ | `lambda` | normal impulse over the step [N s] (velocity level) |
/// | \f$\beta\f$ | `baumgarte` | fraction of the overlap removed per step, in [0, 1] |
/// | \f$\mu\f$ | `mu` | Coulomb friction coefficient per contact |
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "physlab/lcp.hpp"
#include "physlab/world.hpp"

namespace physlab {

namespace remote {
template <int>
struct Access;  // the grader's wire (tests/support/remote): what crosses to a grading worker
}  // namespace remote

/// One row of a contact problem: the direction d at the point p, between bodies a and b (indices
/// into the bodies). A normal row has d = the contact normal (from B to A); a friction row a unit
/// tangent. An impulse \f$\lambda\f$ on the row is \f$\lambda d\f$ on A at p and \f$-\lambda d\f$ on B.
struct ContactRow {
  int a = 0;               ///< body A
  int b = 0;               ///< body B
  Vec3 p = Vec3::Zero();   ///< the point, world frame [m]
  Vec3 d = Vec3::UnitZ();  ///< unit direction, world frame
};

/// What the acceleration-level \f$b\f$ needs of a body besides ContactBody: world frame.
struct AppliedLoads {
  Vec3 F = Vec3::Zero();    ///< applied force (gravity included) [N]
  Vec3 tau = Vec3::Zero();  ///< applied torque about the centre of mass [N m]
  Vec3 L = Vec3::Zero();    ///< angular momentum [kg m^2/s]
};

/// An LCP: find f with w = A f + b >= 0, f >= 0, f^T w = 0.
struct LcpProblem {
  MatX A;  ///< n x n
  VecX b;  ///< n
};

// ---------------------------------------------------------------------------------------------
/// \name Student functions (Lab 6)
///@{

/// The matrix \f$a_{ij}\f$ of the file's formula for any rows: the change of the relative velocity
/// along row i, \f$d_i \cdot (\Delta\dot p_a - \Delta\dot p_b)\f$ at \f$p_i\f$, caused by a unit
/// impulse on row j (equally, of relative acceleration per unit force). Symmetric positive
/// semidefinite; rows on bodies that share no moving body give 0; fixed bodies (zero inverses)
/// add nothing. InvalidInput when a row names a body that does not exist (an index outside
/// [0, bodies.size())), a row's direction d is not a finite unit vector (its length off 1 by more
/// than 1e-9) or its point p not finite, or a body's inv_mass is negative or not finite or its
/// I_inv_world not finite. Handout: Lab 6, section 1.
MatX contactMatrix(const std::vector<ContactBody>& bodies, const std::vector<ContactRow>& rows);

/// Baraff's \f$b_i\f$ for normal rows (d = \f$\hat n_i\f$): the relative normal acceleration with every
/// contact force zero, plus \f$2 \dot{\hat n}_i \cdot (\dot p_a - \dot p_b)\f$ with
/// \f$\dot{\hat n}_i = \omega_b \times \hat n_i\f$; see the file's formula [m/s^2]. `loads` has one
/// entry per body (a fixed body's are ignored). InvalidInput when `loads` has another size, and on
/// the rows and bodies contactMatrix() refuses. Handout: Lab 6, section 2.
VecX accelerationBias(const std::vector<ContactBody>& bodies, const std::vector<AppliedLoads>& loads,
                      const std::vector<ContactRow>& normals);

/// The velocity-level \f$b_i\f$: the relative velocity along row i now,
/// \f$d_i \cdot (\dot p_a - \dot p_b)\f$, minus \f$\frac{\beta}{h}\max(0, depth_i - slop)\f$ (depth_i > 0
/// overlapping; a friction row passes depth 0) [m/s]. `depths` has one entry per row.
/// InvalidInput when `depths` has another size or a non-finite entry, h is not positive and finite,
/// \f$\beta\f$ is outside [0, 1], slop is negative or not finite, or a row names a body that does not
/// exist, has a direction that is not a finite unit vector or a point that is not finite.
/// Handout: Lab 6, section 7.
VecX velocityBias(const std::vector<ContactBody>& bodies, const std::vector<ContactRow>& rows, const VecX& depths,
                  double h, double baumgarte, double slop);

/// The friction pyramid's LCP of the file's formula for m contacts with k directions each. `A`
/// and `b` are contactMatrix() and velocityBias() of the rows ordered as the m normals, then
/// contact 0's k directions, contact 1's k directions, ...; the result has size m + m k + m with
/// unknowns \f$(\lambda_n, \beta, \gamma)\f$ in that order. InvalidInput on sizes that do not
/// fit (m is mu's size; A must be (m + m k) square and b of size m + m k), k < 3, a negative or
/// non-finite \f$\mu\f$, or a non-finite entry of A or b.
/// Handout: Lab 6, section 8.
LcpProblem frictionPyramid(const MatX& A, const VecX& b, const VecX& mu, int k);
///@}

// ---------------------------------------------------------------------------------------------
/// \name The resting-contact solver that World steps with (framework)
///@{

/// Which equation the contact forces satisfy.
enum class Formulation {
  Acceleration,  ///< Baraff: forces with \f$\ddot d = A f + b\f$, applied over the step as \f$f h\f$ (no friction, no drift correction)
  Velocity,      ///< impulses with \f$v^+ = A\lambda + b\f$ over the step, Baumgarte-corrected, with friction
};

/// Which LCP solver finds the forces. Friction (velocity level, \f$\mu > 0\f$): Lemke solves the
/// pyramid, PGS the cone; pivoting needs a symmetric matrix and so ignores friction.
enum class LcpMethod {
  Pivoting,  ///< solveLcpPivoting()
  Lemke,     ///< solveLcpLemke()
  Pgs,       ///< solveLcpPgs(), or solveLcpPgsCone() with friction
};

/// "acceleration" or "velocity".
const char* formulationName(Formulation formulation);
/// "pivoting", "Lemke" or "PGS".
const char* lcpMethodName(LcpMethod method);

/// Every knob of the resting-contact solver.
struct RestingSettings {
  Formulation formulation = Formulation::Velocity;  ///< acceleration or velocity level
  LcpMethod method = LcpMethod::Pgs;                ///< the LCP solver (PGS: the one that takes friction as a cone)
  LcpOptions lcp;                                   ///< its options (PGS sweeps, tolerances)
  int pyramid_directions = 4;                       ///< k, friction directions per contact (Lemke)
  double baumgarte = 0.2;                           ///< \f$\beta\f$ in [0, 1] (velocity level)
  double slop = 0.001;                              ///< overlap left alone [m] (velocity level)
  /// Pivoting: added to A's diagonal, relative to its largest diagonal entry (ODE's constraint
  /// force mixing): the four corners of a face are redundant contacts whose clamped block would
  /// otherwise be singular. It changes the forces by about this fraction.
  double regularization = 1e-9;
  /// Velocity-level PGS on the friction cone without forming A: each row keeps its Jacobian and
  /// the sweep updates per-body velocity changes, \f$w_i = b_i + J_i \Delta v\f$, as Bullet, Box2D
  /// and ODE's QuickStep do. Its iterates are solveLcpPgsCone()'s on contactMatrix() and
  /// velocityBias() up to round-off, at a cost linear in the rows instead of quadratic. It computes
  /// what solveLcpPgsCone() computes, so it is a framework answer (common/answers/): a student's copy
  /// has it only once Lab 6 is released (released/06_resting_contact/framework/). Until then the
  /// same setting runs the same sweeps point by point with your own functions, each point's 3 x 3
  /// block from contactMatrix() and one sweep of your solveLcpPgsCone() on it: the same iterates, a
  /// cost still linear in the rows, about 9 times the framework's (the benchmark's figures are the
  /// framework's). Only for method PGS at the velocity level; the tests leave it off (but for the
  /// 10-row pyramid) so that the students' functions run whole.
  bool matrix_free = false;
  /// One line naming every setting.
  std::string toString() const;
};

/// The LCP-based RestingContactSolver: builds the rows of the resting points, the LCP of the
/// formulation, solves it with the chosen method and applies the result. A solver failure
/// (LcpFailure) propagates out of World::step().
class LcpContactSolver : public RestingContactSolver {
 public:
  /// Validates the settings (InvalidInput naming the field).
  explicit LcpContactSolver(RestingSettings settings);
  /// What it solves with, and what it leaves out: "friction ignored" when the method takes no
  /// friction (pivoting, or the acceleration level), so that a run with \f$\mu > 0\f$ says so.
  std::string describe() const override;
  /// True at the velocity level: an impulse LCP can aim a colliding point at its bounce. Its
  /// normal rows then read \f$b_i = v_{rel,i} - \max(-\epsilon_i v^-_{rel,i},\ \frac{\beta}{h}\max(0, depth_i - slop))\f$
  /// for a colliding point: the bounce or the Baumgarte push, whichever is faster, never both
  /// (a bounce plus a push would return more energy than came in).
  bool bounces() const override;
  int solve(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const std::vector<int>& resting,
            const std::vector<BodyDescription>& descriptions, const std::vector<BodyState>& states, const Vec3& gravity,
            double h) override;
  const RestingSettings& settings() const { return settings_; }  ///< the settings
  /// The residual of the last LCP solved (lcpResidual(), or the cone PGS's last change).
  double lastResidual() const { return last_residual_; }

 private:
  // One contact point of the matrix-free cone PGS (common/answers/): rows n, t, o with their Jacobians
  struct PointRows {
    std::size_t a = 0, b = 0;
    double inv_ma = 0.0, inv_mb = 0.0;
    Vec3 d[3];                 // directions n, t, o
    Vec3 ang_a[3], ang_b[3];   // r_a x d, r_b x d
    Vec3 turn_a[3], turn_b[3];  // I_a^-1 (r_a x d), I_b^-1 (r_b x d)
    double diag[3] = {};       // a_ii
    double bias[3] = {};       // velocityBias()
    double inv_diag_n = 0.0;   // 1 / a_nn
    double inv_lambda_T = 0.0;  // 1 / the larger eigenvalue of the tangential 2 x 2 block
    double mu = 0.0;
    Vec3 f = Vec3::Zero();     // (f_n, f_t, f_o)
  };
  // RestingSettings::matrix_free: common/answers/06_resting_contact/cone_matrix_free.cpp, or before
  // Lab 6 is released in a student's copy its stand-in, common/unreleased/06_resting_contact/
  int solveConeMatrixFree(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts,
                          const std::vector<int>& resting, double h);
  // Whose code solveConeMatrixFree() is, for describe(): the framework answer's ("framework
  // answer", no student code: the viewer labels such a run so) or the stand-in's (built on the
  // student's solveLcpPgsCone()); each of the two files defines it.
  static const char* matrixFreeSource();
  // The relative normal velocity of contact c's points now [m/s].
  static double normalVelocity(const std::vector<ContactBody>& bodies, const Contact& c);
  // A colliding point's normal bias aims at its bounce when that is faster than the push apart.
  static double bounceBias(double bias, const std::vector<ContactBody>& bodies, const Contact& c);
  template <int>
  friend struct remote::Access;  // in a grade, solve() runs in the worker: the state crosses with it

  RestingSettings settings_;
  std::vector<PointRows> points_;
  std::vector<Vec3> dv_, dw_;
  std::vector<ContactRow> rows_;
  std::vector<AppliedLoads> loads_;
  double last_residual_ = 0.0;
};

// ---------------------------------------------------------------------------------------------
/// \name Scenes for tests and demos
/// Ground: the plane z <= 0; bodies have epsilon = 0. A body at rest approaches at 0 (World
/// classifies with the velocities before gravity), so its points are resting at any step size.
///@{

/// Lab 5's Settings for resting scenes: no position correction (the velocity-level solver has its
/// own), everything else default (restitution threshold 0.05 m/s).
Settings restingWorldSettings();
/// A box (2 kg, half extents 0.3 x 0.2 x 0.1 m) resting on the ground, turned by `yaw` [rad] about z.
Scene restingBox(double yaw);
/// A plank (1 kg, half extents 1 x 0.1 x 0.05 m) lying level on two fixed spheres (radius 0.1 m)
/// under x = -a and x = +b [m] from its centre (a, b > 0, at most 0.9 m): the lever rule gives the
/// supports Mg b / (a + b) and Mg a / (a + b). Body 0 is the plank, 1 and 2 the supports at -a and +b.
Scene plankOnTwoSupports(double a, double b);
/// n cubes (1 kg, edge 0.2 m) stacked on the ground, each on the one below.
Scene cubeStack(int n);
/// A two-dimensional pyramid of cubes (1 kg, edge 0.2 m): `rows` on the ground, one fewer on
/// each row above, 0.02 m apart, rows (rows + 1) / 2 cubes in all.
Scene cubePyramid(int rows);
/// The ground tilted by `theta` [rad] about the y axis (a fixed plane through the origin) with one
/// cube (1 kg, edge 0.2 m) at rest on it per entry of `mu`, 0.5 m apart along y; the pair of
/// the plane and block i has friction mu[i] (the plane's mu is 1, block i's mu[i]^2: their
/// geometric mean). Block i is body i + 1.
Scene frictionRamp(double theta, const std::vector<double>& mu);
/// A light cube (1 kg, edge 0.2 m) on the ground and a cube `ratio` times heavier on top of it.
Scene heavyOnLight(double ratio);
///@}

/// An orthonormal pair (t, o) spanning the plane normal to the unit vector n, t chosen from n alone
/// (the friction rows of the cone solvers). No checks: n must be a unit vector.
std::pair<Vec3, Vec3> tangentPair(const Vec3& n);

/// k unit directions evenly spaced in the plane normal to the unit vector n, the first along a
/// tangent chosen from n alone (the same n gives the same directions).
std::vector<Vec3> tangentDirections(const Vec3& n, int k);
///@}

}  // namespace physlab
