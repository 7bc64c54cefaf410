// Lab 5 demo: penalty springs against impulses, sequential against simultaneous impulses (Newton's
// cradle, a resting stack, convergence per sweep), a bouncing ball's apex heights, friction
// (a thrown sphere that starts to roll, a sliding box), the cost of each phase of World::step,
// two animations (the cradle and a rain of boxes into a container), and Timewarp against the
// synchronous World on a fast ball through a row (event times, cost, the bodies' clocks).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/plot.hpp"
#include "physlab/rigid.hpp"
#include "physlab/timewarp.hpp"
#include "physlab/world.hpp"

using namespace physlab;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kG = 9.81;

// The method's colour in every chart (plot.hpp's table), for series whose titles do not start
// with the method's name.
std::string colourOf(ResponseMethod method) { return " lc rgb '" + methodColour(responseMethodName(method)) + "'"; }

Settings settingsFor(ResponseMethod method, const Vec3& gravity = Vec3(0.0, 0.0, -kG)) {
  Settings s;
  s.method = method;
  s.gravity = gravity;
  return s;
}

double heightAboveGround(const World& world, int i) {
  return world.states()[i].x.z() - std::get<Sphere>(world.bodies()[i].shape).radius;
}

double totalEnergy(const World& world) {
  return world.diagnostics().kinetic_energy + world.diagnostics().potential_energy;
}

// ---------------------------------------------------------------------------------------------
// Penalty springs against impulses

// A ball (1 kg) that falls from `drop` [m] onto the ground, or rests on it from the start
// (drop = 0), simulated for `duration` seconds. Reports the largest penetration, the depth the
// ball oscillates about (the midpoint of the smallest and largest depth over the second half:
// an undamped spring swings symmetrically about its rest depth, and a window of whole periods
// would be needed for a time average) and the largest total energy relative to the start.
struct BallRun {
  double largest_depth = 0.0, middle_depth = 0.0, energy_ratio = 1.0;
};

BallRun runBall(const Settings& settings, double drop, double epsilon, double h, double duration) {
  World world(bouncingBall(drop, epsilon), settings);
  const long steps = std::lround(duration / h);
  const double E0 = 1.0 * kG * (0.1 + drop);  // m g z of the centre, at rest
  BallRun run;
  double late_lo = std::numeric_limits<double>::infinity(), late_hi = -late_lo;
  for (long n = 1; n <= steps; ++n) {
    world.step(h);
    const double depth = std::max(0.0, -heightAboveGround(world, 1));
    run.largest_depth = std::max(run.largest_depth, depth);
    run.energy_ratio = std::max(run.energy_ratio, totalEnergy(world) / E0);
    if (n > steps / 2) {
      late_lo = std::min(late_lo, depth);
      late_hi = std::max(late_hi, depth);
    }
    // An unstable run would fly off to ever larger energies: what matters is that it did
    if (run.energy_ratio > 1e3) break;
  }
  run.middle_depth = late_hi >= late_lo ? 0.5 * (late_lo + late_hi) : kNaN;
  return run;
}

// Penetration against the stiffness k at a fixed step: the resting ball sinks to mg/k (soft
// springs), the dropped ball digs in by about v sqrt(m/k), and beyond k = 4 m / h^2 the spring
// is too stiff for the step and the run blows up. The impulse method does not depend on k.
void penaltyStiffnessChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const double h = 1e-3, duration = options.quick ? 0.6 : 1.5, drop = 0.5;
  const double k_limit = 4.0 / (h * h);  // 4 m / h^2 with m = 1 kg
  Chart chart("Ball (1 kg) on the ground, h = 1 ms: penetration against penalty stiffness", "penalty stiffness k [N/m]",
              "depth [m]");
  chart.logX().logY().mark({k_limit, "k = 4 m / h^2"});
  const double decade_step = options.quick ? 1.0 : 0.25;
  std::vector<double> ks;
  for (double e = 3.0; e <= 8.0 + 1e-9; e += decade_step) ks.push_back(std::pow(10.0, e));

  bool drawn = attempt("penalty against stiffness", [&] {
    Series resting{"penalty, resting (middle of its swing)", {}, {}, "linespoints pt 7" + colourOf(ResponseMethod::Penalty)};
    Series dropped{"penalty, dropped from 0.5 m (deepest)", {}, {}, "linespoints pt 5 dt 2" + colourOf(ResponseMethod::Penalty)};
    Series unstable{"penalty, unstable (E > 2 E_0)", {}, {}, "points pt 2 ps 2.5 lc rgb 'black'"};
    double last_stable_k = kNaN, first_unstable_k = kNaN;
    for (const double k : ks) {
      Settings s = settingsFor(ResponseMethod::Penalty);
      s.penalty_k = k;
      const BallRun rest = runBall(s, 0.0, 0.0, h, duration), fall = runBall(s, drop, 0.0, h, duration);
      resting.x.push_back(k);
      resting.y.push_back(rest.middle_depth);
      dropped.x.push_back(k);
      dropped.y.push_back(fall.largest_depth);
      if (rest.energy_ratio < 2.0 && fall.energy_ratio < 2.0) {
        last_stable_k = k;
      } else {
        if (std::isnan(first_unstable_k)) first_unstable_k = k;
        unstable.x.insert(unstable.x.end(), {k, k});
        unstable.y.insert(unstable.y.end(), {rest.middle_depth, fall.largest_depth});
      }
    }
    chart.add(resting).add(dropped).add(unstable);
    table.add({"penalty, h = 1 ms: stiffest stable k / first unstable k [N/m]",
               fmt(last_stable_k) + " / " + fmt(first_unstable_k), "4 m / h^2 = " + fmt(k_limit)});
    table.add({"penalty, resting ball at k = " + fmt(ks.front()) + ": depth it swings about [m]",
               fmt(resting.y.front()), "mg/k = " + fmt(kG / ks.front())});
  });
  Series sinking{"prediction: mg/k", {}, {}, "lines dt 3 lc rgb 'gray30'"};
  for (const double k : ks) {
    sinking.x.push_back(k);
    sinking.y.push_back(kG / k);
  }
  chart.add(sinking);
  drawn |= attempt("sequential at the same step", [&] {
    const BallRun fall = runBall(settingsFor(ResponseMethod::Sequential), drop, 0.0, h, duration);
    Series impulse{"sequential, dropped from 0.5 m", {ks.front(), ks.back()},
                   {fall.largest_depth, fall.largest_depth}, "lines" + colourOf(ResponseMethod::Sequential)};
    chart.add(impulse);
    table.add({"sequential, h = 1 ms: largest depth of the dropped ball [m]", fmt(fall.largest_depth),
               "at most v h = " + fmt(std::sqrt(2.0 * kG * drop) * h)});
  });
  if (!drawn) return;  // neither method is written yet: no chart rather than the prediction alone
  for (const auto& p : chart.save(options.out + "/lab05_penalty_vs_impulse")) written.push_back(p);
}

// The largest energy of a ball dropped from 0.5 m (elastic: penalty without damping, impulses
// with epsilon = 1) against the step, at k = 10^4 N/m: penalty contact gains energy as h nears
// 2 sqrt(m/k); impulses do not care about k.
void penaltyStepChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const double k = 1e4, drop = 0.5, duration = options.quick ? 2.0 : 4.0;
  const double h_limit = 2.0 * std::sqrt(1.0 / k);
  Chart chart("Ball dropped from 0.5 m, elastic, over " + fmt(duration) + " s: energy gain against step size (k = 10^4 N/m)",
              "step size h [s]", "largest E / E_0");
  chart.logX().logY().mark({h_limit, "h = 2 sqrt(m/k) = " + fmt(h_limit) + " s"});
  const double per_decade = options.quick ? 4.0 : 8.0;
  std::vector<double> hs;
  for (double e = -4.0; e <= std::log10(0.05) + 1e-9; e += 1.0 / per_decade) hs.push_back(std::pow(10.0, e));
  bool drawn = false;
  for (const ResponseMethod method : {ResponseMethod::Penalty, ResponseMethod::Sequential}) {
    drawn |= attempt(std::string(responseMethodName(method)) + " against step size", [&] {
      Series s{responseMethodName(method), {}, {}, "linespoints pt 7" + colourOf(method)};
      Settings settings = settingsFor(method);
      settings.penalty_k = k;
      double first_gain = kNaN;
      for (const double h : hs) {
        const BallRun run = runBall(settings, drop, 1.0, h, duration);
        s.x.push_back(h);
        s.y.push_back(run.energy_ratio);
        if (run.energy_ratio > 2.0 && std::isnan(first_gain)) first_gain = h;
      }
      chart.add(s);
      table.add({std::string(responseMethodName(method)) + ", k = 10^4: smallest step with E doubled [s]",
                 std::isnan(first_gain) ? "none up to " + fmt(hs.back()) : fmt(first_gain),
                 "2 sqrt(m/k) = " + fmt(h_limit)});
    });
  }
  if (!drawn) return;  // no method is written yet: no chart rather than an empty one
  for (const auto& p : chart.save(options.out + "/lab05_penalty_stability")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// Sequential against simultaneous impulses

// Newton's cradle with a gap: the first ball starts `gap` [m] away from the others, so the
// collision happens at t = gap / v0 and the charts show before and after.
Scene cradleWithGap(int balls, double v0, double gap) {
  Scene scene = newtonsCradle(balls, v0);
  scene.states[0].x.x() -= gap;
  return scene;
}

void cradleChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const int balls = 5;
  const double v0 = 1.0, gap = 0.1, h = 1e-3, duration = 0.5;
  Chart chart("Newton's cradle (5 balls, epsilon = 1, no gravity): the first ball hits at t = 0.1 s", "time [s]",
              "ball velocity v_x [m/s]");
  chart.yRange(-0.7, 1.15);
  bool drawn = false;
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    const std::string name = responseMethodName(method);
    drawn |= attempt("cradle, " + name, [&] {
      World world(cradleWithGap(balls, v0, gap), settingsFor(method, Vec3::Zero()));
      Series first{name + ", first ball", {0.0}, {v0}, "lines" + colourOf(method)};
      Series middle{name + ", balls 2-4", {0.0}, {0.0}, "linespoints dt 3 pt 6 ps 1.5 pi 40" + colourOf(method)};
      Series last{name + ", last ball", {0.0}, {0.0}, "lines dt 2" + colourOf(method)};
      for (long n = 1; n <= std::lround(duration / h); ++n) {
        world.step(h);
        first.x.push_back(world.time());
        first.y.push_back(world.velocity(0).x());
        middle.x.push_back(world.time());
        middle.y.push_back(world.velocity(2).x());
        last.x.push_back(world.time());
        last.y.push_back(world.velocity(balls - 1).x());
      }
      chart.add(first).add(middle).add(last);
      std::string speeds;
      for (int i = 0; i < balls; ++i) speeds += (i ? ", " : "") + fmt(world.velocity(i).x(), 3);
      table.add({name + ": cradle final v_x of balls 1-5 [m/s]", speeds, "cradle: 0, 0, 0, 0, 1"});
    });
  }
  if (!drawn) return;  // no method is written yet: no chart rather than an empty one
  for (const auto& p : chart.save(options.out + "/lab05_cradle")) written.push_back(p);
}

// A stack of `count` boxes (0.4 x 0.4 x 0.2 m, 1 kg) on the ground, each `gap` [m] above the
// one below, so that the stack settles in the first steps.
Scene boxStack(int count, double gap) {
  const Vec3 half(0.2, 0.2, 0.1);
  Scene scene;
  scene.bodies.push_back(BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.0, 0.5));
  scene.states.push_back(BodyState{});
  for (int i = 0; i < count; ++i) {
    scene.bodies.push_back(BodyDescription::box(1.0, half, 0.0, 0.5));
    BodyState s;
    s.x = Vec3(0.0, 0.0, half.z() + i * 2.0 * half.z() + (i + 1) * gap);
    scene.states.push_back(s);
  }
  return scene;
}

void stackChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const int boxes = 4;
  const double h = 1.0 / 60, duration = options.quick ? 2.0 : 5.0;
  // The World's position correction leaves this much overlap alone
  const double slop = Settings{}.slop;
  Chart chart("A stack of 4 boxes settling on the ground (dropped from 1 mm gaps), h = 1/60 s", "time [s]",
              "largest penetration [m]");
  bool drawn = false;
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    const std::string name = responseMethodName(method);
    drawn |= attempt("stack, " + name, [&] {
      World world(boxStack(boxes, 1e-3), settingsFor(method));
      Series depth{name, {}, {}, "lines" + colourOf(method)};
      const Vec3 top_start = world.states()[boxes].x;
      for (long n = 1; n <= std::lround(duration / h); ++n) {
        world.step(h);
        depth.x.push_back(world.time());
        depth.y.push_back(world.diagnostics().max_penetration);
      }
      chart.add(depth);
      const Vec3 drift = world.states()[boxes].x - top_start;
      table.add({name + ": stack after " + fmt(duration) + " s: penetration [m], top box speed [m/s], sideways drift [m]",
                 fmt(depth.y.back()) + ", " + fmt(world.velocity(boxes).norm()) + ", " + fmt(drift.head<2>().norm()),
                 "slop " + fmt(slop) + ", 0, 0"});
    });
  }
  if (!drawn) return;  // no method is written yet: no chart rather than an empty one
  chart.add({"Settings::slop", {0.0, duration}, {slop, slop}, "lines dt 2 lc rgb 'gray30'"});
  for (const auto& p : chart.save(options.out + "/lab05_stack")) written.push_back(p);
}

// The velocity of body i's material point at p as the response left it: momenta after the step
// (integration does not change them) with the position and orientation before it, as the solver
// saw them. (World::angularVelocity() would use the orientation after the step, which differs
// by the step's rotation and shows as a false residual of about 10^{-7} m/s.)
Vec3 pointVelocity(const World& world, const std::vector<BodyState>& before, int i, const Vec3& p) {
  const BodyDescription& body = world.bodies()[i];
  if (body.fixed) return Vec3::Zero();
  const BodyState& after = world.states()[i];
  const Mat3 R = before[i].q.toRotationMatrix();
  const Vec3 omega = R * body.inertia_body.inverse() * R.transpose() * after.L;
  return after.P / body.mass + omega.cross(p - before[i].x);
}

// The largest approaching speed at the last step's contacts after the response.
double largestApproach(const World& world, const std::vector<BodyState>& before) {
  double largest = 0.0;
  for (const Contact& c : world.contacts()) {
    const Vec3 v = pointVelocity(world, before, c.a, c.p) - pointVelocity(world, before, c.b, c.p);
    largest = std::max(largest, -c.n.dot(v));
  }
  return largest;
}

// Residual against sweeps: one step of the settled stack with the solver capped at 1, 2, 4, ...
// sweeps, each from a fresh World (cold start: no warm starting), tolerance 0.
void convergenceChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const int boxes = 4;
  const double h = 1.0 / 60;
  Chart chart("One step of a resting stack of 4 boxes, cold start: residual against solver sweeps (exact 0 drawn at 10^{-16})",
              "sweeps (Settings::iterations)", "largest approaching speed after the step [m/s]");
  chart.logX().logY();
  const int most = options.quick ? 256 : 4096;
  // The stack at rest, the same for both solvers: settled by the simultaneous one, which brings
  // it to rest
  Scene rest;
  const bool settled = attempt("convergence, the resting stack", [&] {
    rest = boxStack(boxes, 0.0);  // needs Lab 3's boxInertia: inside the attempt
    World settle(rest, settingsFor(ResponseMethod::Simultaneous));
    for (int n = 0; n < 120; ++n) settle.step(h);
    rest.states = settle.states();
  });
  if (!settled) return;
  bool drawn = false;
  for (const ResponseMethod method : {ResponseMethod::Sequential, ResponseMethod::Simultaneous}) {
    const std::string name = responseMethodName(method);
    drawn |= attempt("convergence, " + name, [&] {
      Series s{name, {}, {}, "linespoints pt 7" + colourOf(method)};
      for (int sweeps = 1; sweeps <= most; sweeps *= 2) {
        Settings settings = settingsFor(method);
        settings.iterations = sweeps;
        settings.tolerance = 0.0;
        World world(rest, settings);
        world.step(h);
        s.x.push_back(sweeps);
        s.y.push_back(std::max(largestApproach(world, rest.states), 1e-16));
      }
      chart.add(s);
      table.add({name + ": stack residual after 8 / " + std::to_string(most) + " sweeps [m/s]",
                 fmt(s.y[3]) + " / " + fmt(s.y.back()), "g h = " + fmt(kG * h) + " before"});
    });
  }
  if (!drawn) return;  // no method is written yet: no chart rather than an empty one
  for (const auto& p : chart.save(options.out + "/lab05_impulse_convergence")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// Restitution and friction

// Successive apex heights of a ball dropped from 1 m against h_k = h_0 epsilon^(2k).
void apexChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const double h0 = 1.0, h = options.quick ? 1e-3 : 2.5e-4, duration = 6.0;
  Chart chart("Ball dropped from 1 m (sequential, h = " + fmt(h) + " s): apex heights against h_0 epsilon^{2k}",
              "bounce k", "apex height above the ground [m]");
  chart.logY();
  const std::string colours[] = {"#1f5fbf", "#2ca02c", "#9467bd"};
  const bool drawn = attempt("apex heights", [&] {
    int c = 0;
    for (const double epsilon : {0.9, 0.7, 0.5}) {
      const std::string colour = colours[c++];
      const std::string tag = "epsilon = " + fmt(epsilon);
      World world(bouncingBall(h0, epsilon), settingsFor(ResponseMethod::Sequential));
      Series measured{"sequential, " + tag, {}, {}, "points pt 7 ps 1.3 lc rgb '" + colour + "'"};
      Series predicted{"prediction, " + tag, {}, {}, "lines dt 2 lc rgb '" + colour + "'"};
      double vz_before = 0.0;
      for (long n = 1; n <= std::lround(duration / h); ++n) {
        world.step(h);
        const double vz = world.velocity(1).z();
        if (vz_before > 0.0 && vz <= 0.0) {
          const double k = static_cast<double>(measured.x.size() + 1);
          measured.x.push_back(k);
          measured.y.push_back(heightAboveGround(world, 1));
        }
        vz_before = vz;
      }
      for (int k = 0; k <= static_cast<int>(measured.x.size()); ++k) {
        predicted.x.push_back(k);
        predicted.y.push_back(h0 * std::pow(epsilon, 2 * k));
      }
      if (measured.y.size() < 3 || measured.y[1] <= 0.01) throw InvalidInput("fewer than 2 bounces above 1 cm");
      // The ratio of successive apexes, averaged in the log over the bounces above 1 cm: lower
      // ones are distorted by the step (the ball turns up to v h below the ground)
      std::size_t high = 1;
      while (high < measured.y.size() && measured.y[high] > 0.01) ++high;
      const double ratio = std::pow(measured.y[high - 1] / measured.y.front(), 1.0 / (high - 1));
      chart.add(measured).add(predicted);
      table.add({"apex ratio h_{k+1}/h_k, " + tag + " (" + std::to_string(high) + " bounces above 1 cm)",
                 fmt(ratio, 4), "epsilon^2 = " + fmt(epsilon * epsilon, 4)});
    }
  });
  if (!drawn) return;
  for (const auto& p : chart.save(options.out + "/lab05_apex_heights")) written.push_back(p);
}

// A sphere thrown without spin slides, friction slows it and spins it up until v = r omega =
// 5/7 v0 at t = 2 v0 / (7 mu g); a box slides and decelerates at mu g until it stops.
void rollingChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const double v0 = 3.0, mu = 0.3, r = 0.1, h = 1e-3;
  const double t_roll = 2.0 * v0 / (7.0 * mu * kG), t_stop = v0 / (mu * kG);
  Chart chart("Thrown sphere and sliding box, v_0 = 3 m/s, mu = 0.3 (sequential, h = 1 ms)", "time [s]", "speed [m/s]");
  chart.yRange(0.0, 3.3)
      .mark({t_roll, "sphere rolls: 2 v_0 / (7 mu g)"})
      .mark({t_stop, "box stops: v_0 / (mu g)"});
  const double duration = 1.2 * t_stop;
  const bool drawn = attempt("rolling and sliding", [&] {
    World box(slidingBox(v0, mu), settingsFor(ResponseMethod::Sequential));
    Series box_v{"sequential, box v", {0.0}, {v0}, "linespoints pt 4 ps 1.5 pi 100 lc rgb '#d62728'"};
    double t_stopped = kNaN;
    for (long n = 1; n <= std::lround(duration / h); ++n) {
      box.step(h);
      box_v.x.push_back(box.time());
      box_v.y.push_back(box.velocity(1).x());
      if (std::isnan(t_stopped) && box_v.y.back() < 1e-3) t_stopped = box.time();
    }
    chart.add(box_v);
    table.add({"box: time to stop [s]", fmt(t_stopped, 4), "v0 / (mu g) = " + fmt(t_stop, 4)});
    World world(thrownSphere(v0, mu), settingsFor(ResponseMethod::Sequential));
    Series v{"sequential, sphere v", {0.0}, {v0}, "lines lc rgb '#1f5fbf'"};
    Series spin{"sequential, sphere r omega", {0.0}, {0.0}, "lines lc rgb '#2ca02c'"};
    double v_at_roll = kNaN;
    for (long n = 1; n <= std::lround(duration / h); ++n) {
      world.step(h);
      v.x.push_back(world.time());
      v.y.push_back(world.velocity(1).x());
      spin.x.push_back(world.time());
      spin.y.push_back(r * world.angularVelocity(1).y());
      if (std::isnan(v_at_roll) && world.time() >= t_roll + 0.1) v_at_roll = v.y.back();
    }
    chart.add(v).add(spin);
    table.add({"sphere: v at t_roll + 0.1 s / at the end [m/s]", fmt(v_at_roll, 4) + " / " + fmt(v.y.back(), 4),
               "5/7 v0 = " + fmt(5.0 / 7.0 * v0, 4)});
  });
  if (!drawn) return;
  Series sphere_v{"analytic", {0.0, t_roll, duration}, {v0, 5.0 / 7.0 * v0, 5.0 / 7.0 * v0}, "lines dt 2 lc rgb 'gray20'"};
  Series sphere_spin{"", {0.0, t_roll}, {0.0, 5.0 / 7.0 * v0}, "lines dt 2 lc rgb 'gray20'"};
  Series box_v{"", {0.0, t_stop, duration}, {v0, 0.0, 0.0}, "lines dt 2 lc rgb 'gray20'"};
  chart.add(sphere_v).add(sphere_spin).add(box_v);
  for (const auto& p : chart.save(options.out + "/lab05_rolling")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// Cost

// Milliseconds per step spent in each phase, per scene, with the sequential solver at 60 Hz.
// One column per scene, named with its number of moving bodies; no lines join the columns, since
// the scenes differ in kind and a line would suggest a trend. Within a column each phase stands
// a little aside from the next, with a colour and a point type of its own, so that close costs
// do not hide each other.
void phaseCostChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  struct Case {
    std::string name;
    Scene scene;
    Vec3 gravity;
  };
  const int rain = 100;
  // PhaseTimes::resting is left out: Lab 5's World has no resting-contact solver, so it stays 0
  const char* phases[] = {"forces", "broad phase", "narrow phase", "classify", "respond", "integrate",
                          "correct positions", "diagnostics"};
  const char* colours[] = {"#8c564b", "#17becf", "#ff7f0e", "#7f7f7f", "#1f5fbf", "#2ca02c", "#e377c2", "#bcbd22"};
  const char* point_types[] = {"5", "7", "9", "11", "13", "15", "3", "2"};
  const int kPhases = 8;
  const double spread = 0.08;  // column offset between neighbouring phases
  std::vector<Series> series;
  for (int p = 0; p < kPhases; ++p) {
    series.push_back({phases[p], {}, {}, std::string("points ps 1.6 pt ") + point_types[p] + " lc rgb '" + colours[p] + "'"});
  }
  Series total{"whole step", {}, {}, "points pt 6 ps 3 lw 2 lc rgb 'black'"};
  std::vector<std::pair<double, std::string>> columns;
  const double h = 1.0 / 60;
  const long steps = options.quick ? 120 : 300;
  const bool drawn = attempt("phase cost", [&] {
    // The scenes need Lab 3's inertia functions: made inside the attempt
    const std::vector<Case> cases = {
        {"ball", bouncingBall(1.0, 0.7), Vec3(0, 0, -kG)},
        {"stack", boxStack(4, 1e-3), Vec3(0, 0, -kG)},
        {"cradle", newtonsCradle(5, 1.0), Vec3::Zero()},
        {"stack", boxStack(10, 1e-3), Vec3(0, 0, -kG)},
        {"box rain", boxRain(rain / 4, 3), Vec3(0, 0, -kG)},
        {"box rain", boxRain(rain, 3), Vec3(0, 0, -kG)},
    };
    for (const Case& c : cases) {
      World world(c.scene, settingsFor(ResponseMethod::Sequential, c.gravity));
      Stopwatch clock;
      for (long n = 0; n < steps; ++n) world.step(h);
      const double wall_ms = 1e3 * clock.seconds() / steps;
      const PhaseTimes& t = world.times();
      const double per_phase[] = {t.forces,  t.broad_phase, t.narrow_phase, t.classify,
                                  t.respond, t.integrate,   t.correct,      t.diagnostics};
      int moving = 0;
      for (const BodyDescription& b : c.scene.bodies) moving += b.fixed ? 0 : 1;
      const double column = static_cast<double>(columns.size() + 1);
      for (int p = 0; p < kPhases; ++p) {
        series[p].x.push_back(column + spread * (p - 0.5 * (kPhases - 1)));
        series[p].y.push_back(1e3 * per_phase[p] / steps);
      }
      total.x.push_back(column);
      total.y.push_back(wall_ms);
      columns.emplace_back(column, c.name + ", " + std::to_string(moving) + (moving == 1 ? " body" : " bodies"));
      table.add({c.name + " (" + std::to_string(moving) + " bodies): ms per step; share in respond",
                 fmt(wall_ms, 3) + "; " + fmt(100.0 * t.respond / (1e-3 * wall_ms * steps), 2) + " %", ""});
    }
  });
  if (!drawn) return;
  Chart chart("Per-phase cost of World::step, one column per scene (sequential impulses, 60 Hz)", "",
              "ms per step");
  chart.logY().xTics(columns);
  for (Series& s : series) chart.add(std::move(s));
  chart.add(total);
  for (const auto& p : chart.save(options.out + "/lab05_phase_cost")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// Islands and sleeping (section 12)

// A field of 6 x 6 stacks of five 20 cm boxes, each box dropped 2 cm above the one below, shifted
// and turned a little (every stack its own island once it stands; the falls and the tilts take
// about a second to settle).
Scene stackField() {
  Scene scene;
  scene.bodies.push_back(BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.0, 0.5));
  scene.states.push_back(BodyState{});
  const int side = 6, levels = 5;
  for (int k = 0; k < side * side; ++k) {
    for (int level = 0; level < levels; ++level) {
      scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(0.1), 0.0, 0.5));
      BodyState s;
      const double sign = level % 2 == 0 ? 1.0 : -1.0;
      s.x = Vec3(0.6 * (k % side) + 0.02 * sign, 0.6 * (k / side), 0.1 + 0.22 * level);
      s.q = Quat(Eigen::AngleAxisd(0.1 * sign * (1 + k % 3), Vec3::UnitZ()));
      scene.states.push_back(s);
    }
  }
  return scene;
}

// The stack field settling, sequential impulses at 60 Hz, sleeping off and on: the largest speed
// and spin of any body (where the thresholds stand against what a settling pile still does) and
// the time of each step (what sleeping saves once it rests).
void sleepCharts(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const double h = 1.0 / 60, duration = options.quick ? 4.0 : 8.0;
  const long steps = std::lround(duration / h);
  // Each point is the least step time of this many steps: other jobs on the machine only add to a step
  const long window = 10;
  const Settings awake_settings = settingsFor(ResponseMethod::Sequential);
  Settings sleep_settings = awake_settings;
  sleep_settings.sleeping = true;
  Series largest_v{"largest |v| [m/s]", {}, {}, "lines lc rgb '#1f5fbf'"};
  Series largest_w{"largest |omega| [rad/s]", {}, {}, "lines dt 2 lc rgb '#1f5fbf'"};
  Series cost_off{"sequential, sleeping off", {}, {}, "lines"};
  Series cost_on{"sequential, sleeping on", {}, {}, "lines dt 2"};
  const bool drawn = attempt("sleeping", [&] {
    const Scene scene = stackField();
    const int boxes = static_cast<int>(scene.bodies.size()) - 1;
    for (const bool sleeping : {false, true}) {
      World world(scene, sleeping ? sleep_settings : awake_settings);
      Series& cost = sleeping ? cost_on : cost_off;
      double window_least = kNaN, settled_least = kNaN;
      double all_asleep = kNaN;
      for (long n = 1; n <= steps; ++n) {
        Stopwatch clock;
        world.step(h);
        const double seconds = clock.seconds();
        window_least = std::isnan(window_least) ? seconds : std::min(window_least, seconds);
        // The last second: the field at rest
        if (world.time() > duration - 1.0) settled_least = std::isnan(settled_least) ? seconds : std::min(settled_least, seconds);
        if (n % window == 0) {
          cost.x.push_back(world.time());
          cost.y.push_back(1e3 * window_least);
          window_least = kNaN;
        }
        if (!sleeping) {
          double v = 0.0, w = 0.0;
          for (int i = 0; i < static_cast<int>(world.bodies().size()); ++i) {
            v = std::max(v, world.velocity(i).norm());
            w = std::max(w, world.angularVelocity(i).norm());
          }
          largest_v.x.push_back(world.time());
          largest_v.y.push_back(std::max(v, 1e-6));
          largest_w.x.push_back(world.time());
          largest_w.y.push_back(std::max(w, 1e-6));
        } else if (std::isnan(all_asleep) && world.diagnostics().asleep == boxes) {
          all_asleep = world.time();
        }
      }
      table.add({std::string("field of ") + std::to_string(boxes) + " boxes, sleeping " + (sleeping ? "on" : "off") +
                     ": least ms per step in the last second" + (sleeping ? "; all asleep at [s]" : ""),
                 fmt(1e3 * settled_least, 3) + (sleeping ? "; " + fmt(all_asleep, 3) : ""), ""});
    }
  });
  if (!drawn) return;
  Chart speeds("36 stacks of 5 boxes settling, sleeping off: the fastest body against the sleep thresholds",
               "time [s]", "speed");
  speeds.logY().add(largest_v).add(largest_w);
  speeds.add({"sleep thresholds (0.05)", {0.0, duration}, {Settings{}.sleep_linear, Settings{}.sleep_linear},
              "lines dt 3 lc rgb 'gray30'"});
  for (const auto& p : speeds.save(options.out + "/lab05_sleep_speeds")) written.push_back(p);
  Chart cost("36 stacks of 5 boxes settling (60 Hz): time of a step (least of 10), sleeping off and on", "time [s]",
             "ms per step");
  cost.logY().add(cost_off).add(cost_on);
  for (const auto& p : cost.save(options.out + "/lab05_sleep_cost")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// Animations

Mat3X toMatrix(const std::vector<Vec3>& points) {
  Mat3X m(3, std::max<std::size_t>(points.size(), 1));
  if (points.empty()) m.col(0) = Vec3::Constant(kNaN);
  for (std::size_t i = 0; i < points.size(); ++i) m.col(static_cast<Index>(i)) = points[i];
  return m;
}

// A circle of radius r about c in the plane of the unit vectors u, v. Two NaN columns end it:
// in 3D gnuplot joins blocks separated by one blank line into a mesh.
void appendCircle(std::vector<Vec3>& out, const Vec3& c, const Vec3& u, const Vec3& v, double r) {
  for (int k = 0; k <= 24; ++k) {
    const double t = 2.0 * M_PI * k / 24;
    out.push_back(c + r * (std::cos(t) * u + std::sin(t) * v));
  }
  out.push_back(Vec3::Constant(kNaN));
  out.push_back(Vec3::Constant(kNaN));
}

// The 12 edges of a box at (x, q), each followed by two NaN columns (see appendCircle).
void appendBox(std::vector<Vec3>& out, const Vec3& half, const Vec3& x, const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (double su : {-1.0, 1.0}) {
      for (double sv : {-1.0, 1.0}) {
        Vec3 a = Vec3::Zero();
        a[u] = su * half[u];
        a[v] = sv * half[v];
        Vec3 b = a;
        a[axis] = -half[axis];
        b[axis] = half[axis];
        out.push_back(x + R * a);
        out.push_back(x + R * b);
        out.push_back(Vec3::Constant(kNaN));
        out.push_back(Vec3::Constant(kNaN));
      }
    }
  }
}

void cradleAnimation(const DemoOptions& options, std::vector<std::string>& written) {
  attempt("cradle animation", [&] {
    const int balls = 5, frames = options.quick ? 40 : 80;
    // 1.4 s: the last ball is still in view at the end (frames that do not change upset gnuplot's GIF optimiser)
    const double v0 = 1.0, gap = 0.2, h = 1e-3, frame_time = 1.4 / frames;
    World world(cradleWithGap(balls, v0, gap), settingsFor(ResponseMethod::Sequential, Vec3::Zero()));
    Animation movie("Newton's cradle, sequential impulses", Vec3(-0.45, -0.35, 0.0), Vec3(2.2, 0.35, 0.0), false);
    const long steps_per_frame = std::lround(frame_time / h);
    for (int f = 0; f < frames; ++f) {
      std::vector<Vec3> circles;
      for (int i = 0; i < balls; ++i) appendCircle(circles, world.states()[i].x, Vec3::UnitX(), Vec3::UnitY(), 0.1);
      std::string speeds;
      for (int i = 0; i < balls; ++i) speeds += (i ? " " : "") + fmt(world.velocity(i).x(), 2);
      movie.addFrame({{toMatrix(circles), "lines lc rgb '#1f5fbf'", ""}},
                     "t = " + fmt(world.time(), 2) + " s, v_x = " + speeds);
      for (long n = 0; n < steps_per_frame; ++n) world.step(h);
    }
    written.push_back(movie.save(options.out + "/lab05_cradle.gif", 4));
  });
}

void rainAnimation(const DemoOptions& options, std::vector<std::string>& written) {
  attempt("box rain animation", [&] {
    const int count = options.quick ? 30 : 60, frames = options.quick ? 45 : 90;
    const double h = 1.0 / 60, duration = options.quick ? 1.5 : 3.0;
    World world(boxRain(count, 7), settingsFor(ResponseMethod::Sequential));
    Animation movie("Box rain into a container, sequential impulses, h = 1/60 s", Vec3(-1.2, -1.2, 0.0),
                    Vec3(1.2, 1.2, 2.2), true);
    const long steps_per_frame = std::max(1L, std::lround(duration / h / frames));
    std::vector<Vec3> walls;
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
      const BodyDescription& b = world.bodies()[i];
      if (const auto* box = std::get_if<Box>(&b.shape); box && b.fixed) {
        appendBox(walls, box->half_extents, world.states()[i].x, world.states()[i].q);
      }
    }
    for (int f = 0; f < frames; ++f) {
      std::vector<Vec3> boxes, spheres;
      for (std::size_t i = 0; i < world.bodies().size(); ++i) {
        const BodyDescription& b = world.bodies()[i];
        const BodyState& s = world.states()[i];
        if (b.fixed) continue;
        if (const auto* box = std::get_if<Box>(&b.shape)) appendBox(boxes, box->half_extents, s.x, s.q);
        if (const auto* sphere = std::get_if<Sphere>(&b.shape)) {
          const Mat3 R = s.q.toRotationMatrix();
          appendCircle(spheres, s.x, R.col(0), R.col(1), sphere->radius);
          appendCircle(spheres, s.x, R.col(1), R.col(2), sphere->radius);
        }
      }
      movie.addFrame({{toMatrix(walls), "lines lc rgb 'gray50'", "walls"},
                      {toMatrix(boxes), "lines lw 1.5 lc rgb '#1f5fbf'", "boxes"},
                      {toMatrix(spheres), "lines lw 1.5 lc rgb '#d62728'", "spheres"}},
                     "t = " + fmt(world.time(), 2) + " s, " + std::to_string(world.diagnostics().contacts) +
                         " contact points");
      for (long n = 0; n < steps_per_frame; ++n) world.step(h);
    }
    written.push_back(movie.save(options.out + "/lab05_rain.gif", 5));
  });
}

// ---------------------------------------------------------------------------------------------
// Timewarp (section 9) against synchronous stepping

// One colour per way of stepping, in the three Timewarp charts
const std::string kTimewarpStyle = " lc rgb '#6a3d9a'";
const std::string kToiStyle = " lc rgb '#33a02c'";
const std::string kFixedStyle = " lc rgb '#1f5fbf'";

// The sparse scene of the section: a ball at 4 m/s through a row of 5 spheres 0.3 m apart, and
// `background` slow spheres that never meet anything. Exact impact k at (0.8 + 0.3 k) / 4 s.
constexpr int kRow = 5;
constexpr double kGap = 0.3, kV0 = 4.0;
double exactImpact(int k) { return (0.8 + kGap * k) / kV0; }

struct SparseScene {
  std::vector<TimewarpSphere> spheres;
  std::vector<SphereState> states;
};

SparseScene sparseScene(int background) {
  SparseScene scene;
  fastBallThroughRow(kRow, kGap, kV0, background, 5u, scene.spheres, scene.states);
  return scene;
}

// The same largest step for both exact methods, so that they differ in what an impact costs:
// every body (synchronous) or only the bodies involved (Timewarp)
constexpr double kLargestStep = 0.5;

TimewarpSettings timewarpSettings() {
  TimewarpSettings settings;
  settings.max_step = kLargestStep;
  settings.max_travel = 0.05;
  return settings;
}

// The largest error of the row's impact times in a list of events [s]; NaN when one is missing.
double largestTimeError(const std::vector<TimewarpEvent>& events) {
  double error = 0.0;
  for (int k = 0; k < kRow; ++k) {
    const auto it = std::find_if(events.begin(), events.end(),
                                 [k](const TimewarpEvent& e) { return e.a == k && e.b == k + 1; });
    if (it == events.end()) return kNaN;
    error = std::max(error, std::abs(it->t - exactImpact(k)));
  }
  return error;
}

// The fixed-step World on the row alone: impact k is seen when sphere k + 1 first moves; the
// largest error against the exact times [s].
double fixedStepTimeError(double h, double duration) {
  const SparseScene row = sparseScene(0);
  Scene scene;
  for (std::size_t i = 0; i < row.spheres.size(); ++i) {
    scene.bodies.push_back(BodyDescription::sphere(1.0, 0.1, 1.0, 0.0));
    BodyState state;
    state.x = row.states[i].x;
    state.P = row.states[i].v;
    scene.states.push_back(state);
  }
  World world(scene, settingsFor(ResponseMethod::Sequential, Vec3::Zero()));
  std::vector<double> seen(kRow, kNaN);
  for (long n = 1; n <= std::lround(duration / h); ++n) {
    world.step(h);
    for (int k = 0; k < kRow; ++k) {
      if (std::isnan(seen[k]) && world.velocity(k + 1).x() > 1e-9) seen[k] = world.time();
    }
  }
  double error = 0.0;
  for (int k = 0; k < kRow; ++k) error = std::max(error, std::abs(seen[k] - exactImpact(k)));
  return error;
}

// Impact-time error against work: the fixed-step World needs a step as short as the error it may
// make, the synchronous sub-stepping and Timewarp hit every impact to round-off. Work is counted
// as body states advanced (the World: bodies times steps).
void timewarpTimesChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const double duration = 1.0, floor = 1e-16;
  const int background = options.quick ? 20 : 100;
  const int bodies = 1 + kRow + background;
  Chart chart("Ball through a row of 5 (+" + std::to_string(background) +
                  " drifting spheres): impact-time error (round-off drawn at 1e-16) against work",
              "body states advanced", "largest impact-time error [s]");
  chart.logX().logY();
  bool drawn = false;
  drawn |= attempt("timewarp impact times, fixed step", [&] {
    Series fixed{"fixed step (Lab 5 World)", {}, {}, "linespoints pt 7" + kFixedStyle};
    for (const double h : {1e-2, 3e-3, 1e-3, 3e-4, 1e-4}) {
      const double error = fixedStepTimeError(h, 0.6);
      fixed.x.push_back(bodies * duration / h);
      fixed.y.push_back(std::max(error, floor));
      if (h == 1e-3) table.add({"timewarp: fixed-step World, h = 1 ms: largest impact-time error [s]", fmt(error, 3), "about h"});
    }
    chart.add(fixed);
  });
  drawn |= attempt("timewarp impact times, synchronous sub-steps", [&] {
    Series toi{"synchronous, TOI sub-steps", {}, {}, "linespoints pt 5" + kToiStyle};
    for (const double h : {kLargestStep, 0.1, 0.03, 0.01}) {
      const SparseScene scene = sparseScene(background);
      std::vector<TimewarpEvent> events;
      SynchronousStats stats;
      runSynchronousToi(scene.spheres, scene.states, Vec3::Zero(), h, duration, events, stats);
      toi.x.push_back(static_cast<double>(stats.body_updates));
      toi.y.push_back(std::max(largestTimeError(events), floor));
    }
    chart.add(toi);
  });
  drawn |= attempt("timewarp impact times, Timewarp", [&] {
    Series warp{"Timewarp", {}, {}, "linespoints pt 9 ps 1.5" + kTimewarpStyle};
    for (const double travel : {0.2, 0.05, 0.01}) {
      const SparseScene scene = sparseScene(background);
      TimewarpSettings settings = timewarpSettings();
      settings.max_travel = travel;
      TimewarpWorld world(scene.spheres, scene.states, settings);
      world.run(duration);
      warp.x.push_back(static_cast<double>(world.stats().steps));
      const double error = largestTimeError(world.events());
      warp.y.push_back(std::max(error, floor));
      if (travel == 0.05) {
        table.add({"timewarp: Timewarp largest impact-time error [s]", fmt(error, 3), "round-off"});
        table.add({"timewarp: Timewarp rollbacks, bodies rolled back", std::to_string(world.stats().rollbacks) + ", " +
                       std::to_string(world.stats().bodies_rolled_back), "one or more per row sphere"});
      }
    }
    chart.add(warp);
  });
  if (!drawn) return;
  for (const auto& p : chart.save(options.out + "/lab05_timewarp_times")) written.push_back(p);
}

// Work against the number of drifting spheres: states advanced and pair checks of the synchronous
// sub-stepping (every body to every impact) and of Timewarp (only the bodies involved).
void timewarpCostChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const double duration = 1.0, h = kLargestStep;
  const std::vector<int> backgrounds = options.quick ? std::vector<int>{10, 30, 100} : std::vector<int>{10, 30, 100, 300, 1000};
  Chart chart("Ball through a row of 5 among N drifting spheres, 1 s: work of each method", "bodies N",
              "count");
  chart.logX().logY();
  bool drawn = false;
  drawn |= attempt("timewarp cost, synchronous sub-steps", [&] {
    Series checks{"synchronous, TOI sub-steps (h = 0.5 s): pair checks", {}, {}, "linespoints pt 5" + kToiStyle};
    Series updates{"synchronous: states advanced", {}, {}, "linespoints dt 2 pt 4" + kToiStyle};
    for (const int background : backgrounds) {
      const SparseScene scene = sparseScene(background);
      std::vector<TimewarpEvent> events;
      SynchronousStats stats;
      runSynchronousToi(scene.spheres, scene.states, Vec3::Zero(), h, duration, events, stats);
      const double n = static_cast<double>(scene.spheres.size());
      checks.x.push_back(n);
      checks.y.push_back(static_cast<double>(stats.pair_checks));
      updates.x.push_back(n);
      updates.y.push_back(static_cast<double>(stats.body_updates));
      if (background == backgrounds.back()) {
        table.add({"timewarp: synchronous sub-steps at N = " + fmt(n, 4) + ": pair checks, states advanced",
                   std::to_string(stats.pair_checks) + ", " + std::to_string(stats.body_updates), "N^2/2 and N per step and impact"});
      }
    }
    chart.add(checks).add(updates);
  });
  drawn |= attempt("timewarp cost, Timewarp", [&] {
    Series checks{"Timewarp (largest step 0.5 s): pair checks", {}, {}, "linespoints pt 9 ps 1.5" + kTimewarpStyle};
    Series updates{"Timewarp: body steps", {}, {}, "linespoints dt 2 pt 8 ps 1.5" + kTimewarpStyle};
    for (const int background : backgrounds) {
      const SparseScene scene = sparseScene(background);
      TimewarpWorld world(scene.spheres, scene.states, timewarpSettings());
      world.run(duration);
      const double n = static_cast<double>(scene.spheres.size());
      checks.x.push_back(n);
      checks.y.push_back(static_cast<double>(world.stats().pair_checks));
      updates.x.push_back(n);
      updates.y.push_back(static_cast<double>(world.stats().steps));
      if (background == backgrounds.back()) {
        table.add({"timewarp: Timewarp at N = " + fmt(n, 4) + ": pair checks, body steps",
                   std::to_string(world.stats().pair_checks) + ", " + std::to_string(world.stats().steps), "N per body step"});
      }
    }
    chart.add(checks).add(updates);
  });
  if (!drawn) return;
  for (const auto& p : chart.save(options.out + "/lab05_timewarp_cost")) written.push_back(p);
}

// The clocks: each body's local time after every scheduler action of Timewarp on the row (no
// background). The row's spheres run ahead by whole steps and drop back when the ball's
// impacts roll them back to the time of impact.
void timewarpClocksChart(const DemoOptions& options, std::vector<std::string>& written, Table& /*table*/) {
  Chart chart("Timewarp on the ball and the row: every body's own clock, step by step", "scheduler step",
              "local time of the body [s]");
  const bool drawn = attempt("timewarp clocks", [&] {
    const SparseScene scene = sparseScene(0);
    TimewarpSettings settings = timewarpSettings();
    settings.max_step = 0.25;
    TimewarpWorld world(scene.spheres, scene.states, settings);
    std::vector<Series> clocks;
    for (int k = 0; k <= kRow; ++k) {
      const std::string name = k == 0 ? "ball" : "sphere " + std::to_string(k);
      clocks.push_back({name, {0.0}, {0.0}, k == 0 ? "steps lw 3 lc rgb '#000000'" : "steps"});
    }
    long action = 0;
    world.observe([&](const TimewarpWorld& w) {
      ++action;
      for (int k = 0; k <= kRow; ++k) {
        clocks[k].x.push_back(static_cast<double>(action));
        clocks[k].y.push_back(w.state(k).t);
      }
    });
    world.run(0.6);
    for (Series& s : clocks) chart.add(s);
  });
  if (!drawn) return;
  for (const auto& p : chart.save(options.out + "/lab05_timewarp_clocks")) written.push_back(p);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv,
        "Lab 5 demo: penalty against impulses, sequential against simultaneous (cradle, stack, convergence), "
        "apex heights, rolling and sliding, the cost of each phase, a cradle and a box rain.");
    std::vector<std::string> written;
    Table table({"quantity", "measured", "expected"});
    penaltyStiffnessChart(options, written, table);
    penaltyStepChart(options, written, table);
    cradleChart(options, written, table);
    stackChart(options, written, table);
    convergenceChart(options, written, table);
    apexChart(options, written, table);
    rollingChart(options, written, table);
    phaseCostChart(options, written, table);
    sleepCharts(options, written, table);
    cradleAnimation(options, written);
    rainAnimation(options, written);
    timewarpTimesChart(options, written, table);
    timewarpCostChart(options, written, table);
    timewarpClocksChart(options, written, table);
    reportDemo("Lab 5", written, table, options.out + "/lab05_summary.md");
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "demo_05_impulses: " << e.what() << "\n";
    return 1;
  }
}
