/// \file timewarp.hpp
/// \brief Lab 5, section 9: Timewarp (Mirtich 2000), asynchronous stepping of spheres with rollback.
///
/// A synchronous World advances every body by the same step, so one fast collision forces small
/// steps (or time-of-impact sub-steps) on the whole scene. Timewarp lets every body keep its own
/// time \f$t_i\f$ and advance by its own step; a body that ran ahead optimistically and is later
/// found to have been hit in its past is *rolled back* to the time of impact, together with the
/// bodies that depend on it (those it has met since), and nobody else.
///
/// Between events every sphere flies freely under the uniform gravity \f$g\f$:
/// \f$x(t) = x_k + v_k (t - t_k) + \frac12 g (t - t_k)^2\f$ from its last saved state
/// \f$(t_k, x_k, v_k)\f$. Two spheres feel the same \f$g\f$, so their relative motion is a straight
/// line: with \f$d = x_A - x_B\f$ and \f$w = v_A - v_B\f$ at a common time, they touch after
/// \f$s \ge 0\f$ when \f$|d + w s| = r_A + r_B\f$, the quadratic
/// \f[ (w \cdot w)\, s^2 + 2 (d \cdot w)\, s + (d \cdot d - (r_A + r_B)^2) = 0, \f]
/// whose smaller root is the time of impact (sphereImpactTime()).
///
/// Glossary: \f$t_i\f$ `time` (a body's local time), \f$t_c\f$ `t_c` (time of impact), \f$r_b\f$
/// (rollback time of body b, rollbackTimes()), \f$j\f$ `j` (impulse, as in section 2).
#pragma once

#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "physlab/math.hpp"

namespace physlab {

/// One sphere of a Timewarp scene: constant description.
struct TimewarpSphere {
  double mass = 1.0;     ///< m [kg], > 0
  double radius = 0.1;   ///< r [m], > 0
  double epsilon = 1.0;  ///< coefficient of restitution, in [0, 1]; a pair uses the smaller
};

/// A sphere's saved state: position and velocity at the time `t` (world frame).
struct SphereState {
  double t = 0.0;          ///< the time of the state [s]
  Vec3 x = Vec3::Zero();   ///< centre [m]
  Vec3 v = Vec3::Zero();   ///< velocity [m/s]
};

/// A resolved collision between spheres a and b at time t (a < b).
struct TimewarpEvent {
  double t = 0.0;  ///< time of impact [s]
  int a = 0;       ///< the lower body index
  int b = 0;       ///< the higher body index
  double j = 0.0;  ///< the impulse magnitude applied [N s]
};

/// One rollback: what caused it and which bodies went back to which time.
struct TimewarpRollback {
  double t_c = 0.0;             ///< the time of impact that caused it [s]
  int a = 0;                    ///< the colliding pair's lower body index
  int b = 0;                    ///< the colliding pair's higher body index
  std::vector<int> bodies;      ///< the bodies rolled back, ascending
  std::vector<double> times;    ///< the time each of them went back to, same order [s]
};

/// Knobs of a Timewarp run.
struct TimewarpSettings {
  Vec3 gravity = Vec3::Zero();  ///< uniform gravitational acceleration [m/s^2]
  double max_step = 0.1;        ///< largest step of a body's own clock [s], > 0
  double max_travel = 0.05;     ///< a body's step is at most max_travel / |v| [m], > 0
};

/// Counts of a run (cost measures).
struct TimewarpStats {
  long steps = 0;           ///< body steps taken (each advances one body's clock)
  long pair_checks = 0;     ///< sphereImpactTime() calls
  long events = 0;          ///< collisions resolved, undone ones included
  long rollbacks = 0;       ///< collisions that rolled back at least one body that was ahead
  long bodies_rolled_back = 0;  ///< bodies rolled back, summed over rollbacks
  long events_undone = 0;   ///< resolved collisions undone by rollbacks
};

// ---------------------------------------------------------------------------------------------
/// \name Student functions (Lab 5, section 9)
///@{

/// The time \f$s \ge 0\f$ from now until two spheres, at x_a and x_b moving at v_a and v_b now
/// (the same time for both; a common gravity cancels), first touch: the smaller root of
/// \f$(w \cdot w) s^2 + 2 (d \cdot w) s + d \cdot d - (r_a + r_b)^2 = 0\f$, \f$d = x_a - x_b\f$,
/// \f$w = v_a - v_b\f$ [s]. +infinity when they never touch while approaching: moving apart or
/// side by side (\f$d \cdot w \ge 0\f$, touching at \f$s = 0\f$ included), or missing (negative
/// discriminant, grazing included), or at relative rest. 0 when they touch or overlap now and
/// approach (\f$d \cdot w < 0\f$). InvalidInput naming the argument ("sphereImpactTime radius r_a",
/// "... position x_b", ...) when a radius is not positive and finite or a vector is not finite.
double sphereImpactTime(const Vec3& x_a, const Vec3& v_a, double r_a, const Vec3& x_b, const Vec3& v_b, double r_b);

/// Which bodies a collision at time t_c must roll back, and to when (Timewarp's dependency rule).
/// The `seeds` (the colliding pair) go back to t_c. Every resolved event \f$(t, a, b)\f$ of `events`
/// (sorted by t, ascending) that happened after the rollback time of one of its bodies
/// (\f$t > r_a\f$ or \f$t > r_b\f$; an event exactly at the rollback time stands) is undone, so
/// both its bodies go back to at most t: \f$r_a \leftarrow \min(r_a, t)\f$, the same for b, and
/// so on through the later events (one pass in time order). Returns \f$r_b\f$ for each of the
/// `body_count` bodies: +infinity for a body that keeps its state. InvalidInput, naming it, when
/// body_count is negative, t_c is not finite, a seed or an event names a body outside
/// [0, body_count), an event time is not finite, or the events are not sorted by time.
std::vector<double> rollbackTimes(const std::vector<TimewarpEvent>& events, int body_count, const std::vector<int>& seeds,
                                  double t_c);

/// Resolves the collision of two touching spheres (centres x_a, x_b at the time of impact) with
/// the Lab 5 impulse: normal \f$\hat n = (x_A - x_B)/|x_A - x_B|\f$ (from B to A), point
/// \f$p = x_B + r_B \hat n\f$, \f$j\f$ = impulseMagnitude() with \f$\epsilon\f$, applied with
/// applyImpulse() when the spheres approach (j > 0). Changes v_a, v_b; returns j, 0 when they do
/// not approach (velocities unchanged). InvalidInput naming it when a mass is not positive and
/// finite, the centres coincide, or as impulseMagnitude() and applyImpulse().
double resolveSphereImpact(const Vec3& x_a, Vec3& v_a, double m_a, const Vec3& x_b, Vec3& v_b, double m_b, double r_b,
                           double epsilon);
///@}

// ---------------------------------------------------------------------------------------------
/// \name The Timewarp scheduler (framework)
///@{

/// Spheres stepped asynchronously with rollback. Each body keeps its history of saved states
/// (its start and every collision it took part in) and its local time \f$t_i\f$. run() repeats:
/// take the body with the smallest local time (priority queue; ties by index); advance it by its
/// own step \f$h_i = \min(h_{max}, \Delta x_{max}/|v_i|)\f$ (TimewarpSettings::max_step and
/// max_travel), not beyond t_end; check
/// it against every other body j over the window both have computed, \f$[t_i, \min(t_i + h_i,
/// t_j)]\f$ (j's part beyond \f$t_j\f$ is checked when j steps), piece by piece of j's history,
/// with sphereImpactTime(); at the earliest impact \f$t_c\f$ cut the step short, roll back the
/// bodies rollbackTimes() names (j when it ran past \f$t_c\f$, and those that met them since),
/// undo their later events, and resolve the impact with resolveSphereImpact().
class TimewarpWorld {
 public:
  /// InvalidInput naming the body and field for a bad description or state (masses and radii
  /// positive, epsilon in [0, 1], finite vectors, a common start time), or bad settings.
  TimewarpWorld(std::vector<TimewarpSphere> spheres, std::vector<SphereState> states, TimewarpSettings settings = {});
  /// Advances every body to t_end [s]. InvalidInput when t_end is not finite or before time();
  /// NumericalFailure, naming the pair, when an impact is left approaching (v_rel below
  /// \f$-10^{-9}\f$ m/s times the speeds) or unanswered at the start of a step (j <= 0), which the
  /// scheduler would otherwise find again for ever.
  void run(double t_end);

  int size() const { return static_cast<int>(spheres_.size()); }  ///< number of bodies
  double time() const { return time_; }  ///< the time every body has reached [s]
  /// Body i's state at its local time. InvalidInput when i is not a body.
  SphereState state(int i) const;
  /// Body i's position and velocity at time t from its history, t <= its local time.
  SphereState stateAt(int i, double t) const;
  const std::vector<TimewarpEvent>& events() const { return events_; }        ///< kept collisions, by time
  const std::vector<TimewarpRollback>& rollbacks() const { return rollbacks_; }  ///< every rollback
  const TimewarpStats& stats() const { return stats_; }                       ///< counts so far
  /// The largest amount by which a body's local time has been behind the time at which another
  /// body used its state (a collision they had, still in that body's history), checked after
  /// every collision (steps only move clocks forward): 0 when no body ever fell behind [s].
  double largestLag() const { return largest_lag_; }
  /// Calls `observer` after every scheduler action of run() (a step, or an impact with its
  /// rollback), so that a demo can watch the bodies' clocks; none by default.
  void observe(std::function<void(const TimewarpWorld&)> observer) { observer_ = std::move(observer); }

 private:
  void stepBody(int i, double t_end);
  void rollBack(const std::vector<double>& r, double t_c, int i, int partner);
  void checkLag();

  std::vector<TimewarpSphere> spheres_;
  std::vector<std::vector<SphereState>> history_;  // per body, ascending t; front is the start
  std::vector<std::vector<int>> partner_;           // the body met at each history entry (-1: start)
  std::vector<double> local_;                       // t_i
  std::vector<int> moved_;                          // bodies whose clock the last action set
  std::vector<TimewarpEvent> events_;
  std::vector<TimewarpRollback> rollbacks_;
  TimewarpSettings settings_;
  TimewarpStats stats_;
  double time_ = 0.0;
  double largest_lag_ = 0.0;
  std::function<void(const TimewarpWorld&)> observer_;
};

/// Counts of a synchronous run.
struct SynchronousStats {
  long steps = 0;         ///< steps of the whole scene (sub-steps included)
  long body_updates = 0;  ///< body states advanced (bodies times steps)
  long pair_checks = 0;   ///< sphereImpactTime() calls
  long events = 0;        ///< collisions resolved
};

/// The synchronous baseline with time-of-impact sub-stepping: every step h, find the earliest
/// impact of any pair within the rest of the step (sphereImpactTime()), advance *every* body to
/// it, resolve it with resolveSphereImpact(), and go on until the step is done. Returns the final
/// states at t_end and fills `events` (by time) and `stats`. InvalidInput as TimewarpWorld, and
/// when h is not positive and finite.
std::vector<SphereState> runSynchronousToi(const std::vector<TimewarpSphere>& spheres, std::vector<SphereState> states,
                                           const Vec3& gravity, double h, double t_end,
                                           std::vector<TimewarpEvent>& events, SynchronousStats& stats);

/// A sphere's free flight: the state at time t from `state` under gravity g (t >= state.t or not).
SphereState ballistic(const SphereState& state, const Vec3& gravity, double t);

/// The sparse scene: a row of `row` spheres (1 kg, radius 0.1 m, epsilon 1) at rest along x with
/// centres 0.2 + gap apart starting at x = 1, a fast ball (the same sphere) at x = 0 moving at v0
/// along +x, and `background` slow spheres (at most 0.1 m/s, never meeting each other or the row in
/// [0, 10] s) on a grid in the plane y = 2 .. ; the same seed gives the same scene. Body 0 is the
/// ball, 1..row the row. The exact collision times: the ball hits sphere 1 at (0.8 / v0) and sphere
/// k hits k + 1 at \f$(0.8 + k\,\text{gap}) / v_0\f$.
void fastBallThroughRow(int row, double gap, double v0, int background, unsigned seed,
                        std::vector<TimewarpSphere>& spheres, std::vector<SphereState>& states);
///@}

}  // namespace physlab
