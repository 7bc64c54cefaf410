/// \file soft_step.hpp
/// \brief Lab 6: the soft step, sub-stepping with soft contacts and relaxation (as Box2D v3 steps).
///
/// Plain PGS solves a rigid contact, \f$v_{rel,n}^+ \ge 0\f$, and removes overlap with a Baumgarte
/// push \f$\frac{\beta}{h}\max(0, depth - slop)\f$ that adds energy and fights the solve. The soft
/// step replaces both by a spring and damper at each point, integrated implicitly so that it is
/// stable at any stiffness, and splits the step h into n substeps \f$h_s = h/n\f$, each one
/// velocity sweep with the spring (solve), a position update, and one sweep without it (relax).
///
/// The spring of a contact with separation \f$s = -depth\f$ (negative when overlapping) and effective
/// mass \f$m_{eff} = 1/K\f$ (K of Lab 5's inverseEffectiveMass()) has stiffness \f$k = m_{eff}\,\omega^2\f$
/// and damping \f$c = 2\zeta\, m_{eff}\,\omega\f$, \f$\omega = 2\pi f\f$ for a chosen frequency f [Hz] and
/// damping ratio \f$\zeta\f$, so that every point rings at f whatever it carries. Over a substep,
/// implicit Euler with the impulse \f$\lambda = h_s(-k s_{+} - c v_{+})\f$, \f$s_{+} = s + h_s v_{+}\f$,
/// \f$v_{+} = v + \lambda / m_{eff}\f$, solves to
/// \f[ \lambda = -m_{eff}\, \gamma_m\, (v + \gamma_b\, s), \qquad
///     a_1 = 2\zeta + h_s\omega,\quad a_2 = h_s\omega\, a_1,\quad
///     \gamma_b = \frac{\omega}{a_1},\quad \gamma_m = \frac{a_2}{1 + a_2},\quad \gamma_i = \frac{1}{1 + a_2}, \f]
/// the bias rate \f$\gamma_b\f$ [1/s], the mass scale \f$\gamma_m\f$ and the impulse scale \f$\gamma_i\f$
/// (\f$\gamma_m + \gamma_i = 1\f$). Gauss-Seidel sweeps reach the same total from any accumulated
/// impulse \f$\lambda_{acc}\f$ already applied (v then holds it) with the increment
/// \f[ \Delta\lambda = -m_{eff}\,\gamma_m\,(v + \gamma_b\, s) - \gamma_i\, \lambda_{acc}, \qquad
///     \lambda_{acc} \leftarrow \max(0,\ \lambda_{acc} + \Delta\lambda). \f]
/// Stiff or heavily damped (\f$f \to \infty\f$ or \f$\zeta \to \infty\f$): \f$\gamma_m \to 1\f$, \f$\gamma_i \to 0\f$,
/// the rigid constraint. No spring (f = 0): \f$\gamma_b = \gamma_m = 0\f$, \f$\gamma_i = 1\f$, the impulse
/// lets go. A point still apart (s > 0) is rigid and speculative: its bias s/\f$h_s\f$ lets the gap
/// close within the substep and no further. The relax sweep is rigid without bias: it takes back
/// the velocity the spring used to push overlap out, so that pushing apart adds no energy.
///
/// Glossary:
/// | symbol | code | meaning |
/// |---|---|---|
/// | \f$f\f$ | `hertz` | contact spring frequency [Hz] |
/// | \f$\zeta\f$ | `zeta` | damping ratio (1: critical) |
/// | \f$h_s\f$ | `h` | substep [s] |
/// | \f$\gamma_b, \gamma_m, \gamma_i\f$ | `bias_rate`, `mass_scale`, `impulse_scale` | soft-constraint coefficients |
/// | \f$\lambda_{acc}\f$ | `lambda` | accumulated normal impulse of the substep [N s] |
/// | \f$m_{eff}\f$ | `effective_mass` | \f$1/K\f$ along the normal [kg] |
#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "physlab/resting.hpp"

namespace physlab {

namespace remote {
template <int>
struct Access;  // the grader's wire (tests/support/remote): what crosses to a grading worker
}  // namespace remote

/// The soft-constraint coefficients of one substep (see the file's formula).
struct SoftCoefficients {
  double bias_rate = 0.0;      ///< \f$\gamma_b\f$, separation to velocity [1/s], >= 0
  double mass_scale = 1.0;     ///< \f$\gamma_m\f$, in [0, 1]
  double impulse_scale = 0.0;  ///< \f$\gamma_i = 1 - \gamma_m\f$, in [0, 1]
};

// ---------------------------------------------------------------------------------------------
/// \name Student functions (Lab 6, section 9)
///@{

/// The coefficients of the file's formula for a spring of frequency `hertz` [Hz] and damping ratio
/// `zeta` over the substep h [s]. hertz = 0 (no spring, and so no damper) gives exactly
/// \f$(\gamma_b, \gamma_m, \gamma_i) = (0, 0, 1)\f$ for every \f$\zeta\f$, \f$\zeta = 0\f$ included (where
/// \f$\omega / a_1\f$ would be 0/0). InvalidInput when hertz or zeta is negative or not finite, or h is
/// not positive and finite; the message names the argument ("hertz", "zeta", or " h " as a word).
/// Handout: Lab 6, section 9.
SoftCoefficients softCoefficients(double hertz, double zeta, double h);

/// One Gauss-Seidel update of a point's normal impulse; returns the new accumulated impulse
/// \f$\lambda_{acc} \ge 0\f$ [N s]. `v_n` is the relative normal velocity now (the impulses applied so
/// far included) [m/s], `separation` s the gap now (< 0 overlapping) [m]. Three cases:
/// - s > 0 (apart): rigid with bias s / h: \f$\Delta\lambda = -m_{eff}(v_n + s/h)\f$;
/// - s <= 0 and not `relax`: soft, \f$\Delta\lambda = -m_{eff}\gamma_m(v_n + b) - \gamma_i\lambda_{acc}\f$
///   with the push \f$b = \max(\gamma_b s, -v_{push})\f$ (never faster apart than `max_push` \f$v_{push}\f$);
/// - s <= 0 and `relax`: rigid without bias, \f$\Delta\lambda = -m_{eff} v_n\f$;
/// and then \f$\max(0, \lambda_{acc} + \Delta\lambda)\f$ (the total never pulls).
/// InvalidInput, naming the argument ("lambda", "v_n", "separation", "effective_mass", " h ",
/// "max_push", "bias_rate", "mass_scale", "impulse_scale"), when lambda is negative or not finite, v_n or separation
/// is not finite, effective_mass or h is not positive and finite, max_push is negative or NaN
/// (+infinity: no limit), or a coefficient of `soft` is outside its range above (mass_scale and
/// impulse_scale in [0, 1], bias_rate >= 0 and finite). Handout: Lab 6, section 9.
double softNormalImpulse(double lambda, double v_n, double separation, double effective_mass,
                         const SoftCoefficients& soft, double h, double max_push, bool relax);
///@}

// ---------------------------------------------------------------------------------------------
/// \name The soft-step solver that World steps with (framework)
///@{

/// Every knob of the soft step.
struct SoftStepSettings {
  /// n, substeps per World step, >= 1: 8, as a 90 Hz spring needs; at 4 to 6 substeps of the
  /// same springs the 465-cube pyramid sags, springs back, its points part (the World finds no
  /// contact between boxes a micrometre apart) and it falls
  int substeps = 8;
  /// f of a contact between two moving bodies [Hz], >= 0: stiff enough that a 6 m wall one cube
  /// thick (the 465-cube pyramid) does not tip over on its springs' sag (60 Hz lets it lean out
  /// of its plane within 5 s), and below the quarter of the substep rate (120 Hz at 8 substeps of
  /// 1/60 s), beyond which a stiffer spring only rings against the sweeps
  double contact_hertz = 90.0;
  /// f of a contact with a fixed body, as a multiple of contact_hertz, >= 0 (Box2D doubles it:
  /// the ground does not give; 1 here, as contact_hertz is near the quarter of the substep rate already)
  double fixed_hertz_scale = 1.0;
  /// \f$\zeta\f$, >= 0: heavily over-damped, overlap creeps out and never rings; 20 rather than
  /// Box2D's 10 damps what the sweeps' lag leaves in a tall stack (the 465-cube pyramid drifts
  /// 19 mm at most over 10 s, against 48 mm at 10)
  double damping_ratio = 20.0;
  int relax_iterations = 1;     ///< rigid sweeps after each substep's position update, >= 0
  double max_push = 3.0;        ///< fastest push apart of overlap [m/s], > 0 (infinity: none)
  int solve_iterations = 1;     ///< soft sweeps per substep, >= 1
  /// Sweep the contact pairs from the highest to the lowest along gravity (a pair at its highest
  /// point, its points together): one sweep then carries the weight of a stack down to the
  /// ground (else the pairs go in the World's order)
  bool top_down = true;
  /// One line naming every setting.
  std::string toString() const;
};

/// The soft step as a RestingContactSolver: it answers every point (bounces() is true), moves the
/// bodies itself in SoftStepSettings::substeps substeps (placeBodies()), and stores in Contact::j and
/// Contact::j_t the impulse over the whole step. Per step: gravity, applied by the World over h, is
/// taken back and given again per substep; each point keeps its anchors \f$r_a, r_b\f$ relative to
/// the body centres at the step's start, its effective masses along the normal and two tangents,
/// and its separation now, \f$s = -depth + \hat n \cdot ((\Delta x_a + \Delta\theta_a \times r_a) -
/// (\Delta x_b + \Delta\theta_b \times r_b))\f$ from the bodies' motion \f$\Delta x, \Delta\theta\f$ since
/// the step's start (no new collision detection inside the step). A substep: warm start (the last
/// substep's impulses again), soft sweeps (softNormalImpulse(), then friction, rigid, clamped to
/// the disc \f$|\lambda_t| \le \mu\lambda_n\f$), positions, relax sweeps (the normal row only,
/// the friction impulse then shrunk onto the new disc: relaxing takes back the spring's push, and
/// friction was solved by the soft sweep); the sweeps visit the contact pairs from the top down
/// (SoftStepSettings::top_down), each pair's points together, its two bodies' velocities held in
/// local copies meanwhile (as Box2D solves a manifold). A point's three relative velocities are
/// read at once; its normal impulse moves the tangent ones through the rows' coupling (the
/// off-diagonal of K), and one update applies all three rows to the bodies. The separations are
/// found by the first sweep after the bodies move and reused until they move again. A substep's impulses add up to the change
/// they made to its bodies' velocities, so the next warm start is taken per body from that change,
/// and no pass reads the points for it. After the substeps, a colliding
/// point (Contact::kind) with \f$\epsilon > 0\f$ that was pushed gets one restitution update towards
/// \f$v_{rel}^+ = -\epsilon\, v_{rel}^-\f$. Reuses its buffers: no allocation once they have grown.
class SoftStepSolver : public RestingContactSolver {
 public:
  /// Validates the settings (InvalidInput naming the field).
  explicit SoftStepSolver(SoftStepSettings settings);
  std::string describe() const override;
  bool bounces() const override { return true; }
  int solve(std::vector<ContactBody>& bodies, std::vector<Contact>& contacts, const std::vector<int>& resting,
            const std::vector<BodyDescription>& descriptions, const std::vector<BodyState>& states, const Vec3& gravity,
            double h) override;
  bool placeBodies(std::vector<BodyState>& states) override;
  bool substeps() const override { return true; }
  const SoftStepSettings& settings() const { return settings_; }  ///< the settings

 private:
  // A body's velocities, or a change of them
  struct Velocity {
    Vec3 v = Vec3::Zero();
    Vec3 omega = Vec3::Zero();
  };
  // What the sweeps read and write of a body, packed (the sweeps' working set stays in cache):
  // its velocities during the substeps and its motion since the step's start
  struct Motion {
    Vec3 v = Vec3::Zero();
    Vec3 omega = Vec3::Zero();
    double inv_mass = 0.0;
    Vec3 dx = Vec3::Zero();
    Vec3 dtheta = Vec3::Zero();
  };
  // A contact pair's points share its bodies and its rows' directions n, t, o (a manifold has
  // one normal); its points are points_[first] to points_[first + count - 1]
  struct Pair {
    std::size_t a = 0, b = 0;
    Vec3 d[3];                // n, t, o
    bool soft_fixed = false;  // one body fixed: the stiffer spring
    int first = 0, count = 0;
  };
  // A point's parts along one row of direction d
  struct Row {
    Vec3 ang_a, ang_b;    // r x d
    Vec3 turn_a, turn_b;  // I^-1 (r x d)
  };
  // One contact point: its rows' parts and the accumulated impulses, what every sweep reads
  // first and each row's parts together (a relax sweep reads the n row's three cache lines of
  // the point's seven), then what only the substep's end and the step's end read
  struct Point {
    double separation = 0.0;                      // the gap now [m]
    double depth = 0.0;                           // at the step's start [m]
    double mu = 0.0;
    double mass[3] = {};                          // effective masses 1/K along n, t, o [kg]
    Vec3 lambda = Vec3::Zero();                   // accumulated impulses of the substep (n, t, o) [N s]
    Eigen::Vector2d coupling = Eigen::Vector2d::Zero();  // K between n and t, o [1/kg]
    Row rows[3];                                  // n, t, o
    bool bounce = false;                          // colliding with epsilon > 0
    double target = 0.0;                          // the bounce's -epsilon v_rel^- [m/s]
    double pushed = 0.0;                          // largest normal impulse of the step [N s]
    Vec3 total = Vec3::Zero();                    // the substeps' impulses summed over the step [N s]
    /// Adds the substep's impulses to the step's.
    void addToStep() {
      total += lambda;
      pushed = std::max(pushed, lambda(0));
    }
    /// The relative velocity of the touching points along row i of direction d [m/s], given
    /// dv = A.v - B.v (A and B a Motion or a Velocity).
    template <class Body>
    double velocity(const Vec3& d, const Vec3& dv, const Body& A, const Body& B, int i) const {
      return d.dot(dv) + rows[i].ang_a.dot(A.omega) - rows[i].ang_b.dot(B.omega);
    }
    /// The gap now along n [m] (< 0 overlapping): the anchors moved with their bodies, to first
    /// order in the rotation.
    double gap(const Vec3& n, const Motion& A, const Motion& B) const {
      return -depth + n.dot(A.dx - B.dx) + rows[0].ang_a.dot(A.dtheta) - rows[0].ang_b.dot(B.dtheta);
    }
    /// Applies the impulses `change` [N s] along the pair's rows first to last - 1 at once to the
    /// velocities of A and B (a Motion, or a Velocity or its change), of inverse masses inv_a and inv_b.
    template <class Body>
    void apply(const Pair& pair, Body& A, Body& B, double inv_a, double inv_b, const Vec3& change, int first = 0,
               int last = 3) const {
      Vec3 J = change(first) * pair.d[first], turn_A = change(first) * rows[first].turn_a,
           turn_B = change(first) * rows[first].turn_b;
      for (int i = first + 1; i < last; ++i) {
        J += change(i) * pair.d[i];
        turn_A += change(i) * rows[i].turn_a;
        turn_B += change(i) * rows[i].turn_b;
      }
      A.v += inv_a * J;
      A.omega += turn_A;
      B.v -= inv_b * J;
      B.omega -= turn_B;
    }
  };
  // One sweep over the points, soft or relaxing (compiled apart: each is a loop of its own, with
  // no test of the kind per point); the substep's closing sweep (`closing`) also adds each
  // point's impulses to the step's totals; the first after the bodies moved (`moved`) finds the
  // points' separations
  template <bool relax>
  void sweep(double h_s, bool closing, bool moved);
  template <int>
  friend struct remote::Access;  // in a grade, solve() runs in the worker: the state crosses with it

  SoftStepSettings settings_;
  SoftCoefficients soft_, soft_fixed_;
  std::vector<Pair> pairs_;    // in sweep order
  std::vector<Point> points_;  // in sweep order, a pair's together
  // A contact pair's points, consecutive in `resting`: from `first`, `count` of them, and the
  // height against gravity of its highest point
  struct Run {
    double height = 0.0;
    int first = 0, count = 0;
  };
  std::vector<Run> order_;            // the pairs in sweep order
  std::vector<int> sweep_contacts_;   // index into contacts of each point, in sweep order
  std::vector<Motion> motion_;  // each body's velocities and motion
  std::vector<Velocity> warm_;  // each body's warm start for the next substep
  std::vector<Quat> dq_;        // each body's rotation since the step's start
  bool moved_ = false;
};
///@}

}  // namespace physlab
