// Lab 6 demo: resting contact as an LCP. PGS's convergence against the mass ratio, the cost of
// each solver against how well a stack stands, a pyramid over time at the acceleration and the
// velocity level, the largest pyramid the matrix-free PGS keeps standing against its sweeps,
// blocks on a friction ramp against g (sin - mu cos) t, the textbook contact scenes of the suite
// in Labs 5 and 6, a 10-cube stack's top drift against time per method (with and without shock
// propagation), and animations (pyramids that stand and fall, a stack that falls).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>

#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/plot.hpp"
#include "physlab/resting.hpp"
#include "physlab/soft_step.hpp"
#include "physlab/suite_report.hpp"
#include "physlab/world.hpp"

using namespace physlab;

namespace {

const double kG = 9.81;
const double kH = 1.0 / 60;
const double kHalf = 0.1;  // half edge of the scenes' cubes [m]

// One solver configuration of the charts: its title starts with the method's name, so that
// plot.hpp gives it the method's colour.
struct Solver {
  Formulation formulation = Formulation::Velocity;
  LcpMethod method = LcpMethod::Pivoting;
  int sweeps = 100;  // PGS only
  std::string name() const {
    std::string s = lcpMethodName(method);
    if (method == LcpMethod::Pgs) s += " " + std::to_string(sweeps);
    return s;
  }
};

RestingSettings restingSettings(const Solver& solver) {
  RestingSettings resting;
  resting.formulation = solver.formulation;
  resting.method = solver.method;
  resting.lcp.max_iterations = solver.sweeps;
  // Every PGS sweep is run, so that the sweep count on the charts is the work done
  if (solver.method == LcpMethod::Pgs) resting.lcp.tolerance = 0.0;
  return resting;
}

// The World for the solver's charts: restingWorldSettings() without the World's shock
// propagation (Lab 5, section 11), so that a chart shows what the solver's sweeps hold by
// themselves (with the pass, PGS at 20 sweeps stands every pyramid here)
Settings solverOnlySettings() {
  Settings settings = restingWorldSettings();
  settings.shock_propagation = false;
  return settings;
}

World restingWorld(Scene scene, const Solver& solver) {
  return World(std::move(scene), solverOnlySettings(), std::make_shared<LcpContactSolver>(restingSettings(solver)));
}

// Largest distance of any moving body from where it started [m].
double largestDrift(const World& world, const std::vector<BodyState>& start) {
  double drift = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i) {
    if (!world.bodies()[i].fixed) drift = std::max(drift, (world.states()[i].x - start[i].x).norm());
  }
  return drift;
}

// ---------------------------------------------------------------------------------------------
// PGS convergence against the mass ratio

// The velocity-level LCP of one 60 Hz step of heavyOnLight(ratio): the light cube on the ground
// and the heavy one on it, four corner contacts per face, both cubes moving down at g h as
// gravity left them. Built from the scene's bodies so that it is the World's problem.
LcpProblem heavyOnLightLcp(double ratio) {
  const Scene scene = heavyOnLight(ratio);
  std::vector<ContactBody> bodies;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDescription& d = scene.bodies[i];
    ContactBody body;
    body.x = scene.states[i].x;
    if (!d.fixed) {
      body.inv_mass = 1.0 / d.mass;
      const Mat3 R = scene.states[i].q.toRotationMatrix();
      body.I_inv_world = R * d.inertia_body.inverse() * R.transpose();
      body.v = Vec3(0.0, 0.0, -kG * kH);
    }
    bodies.push_back(body);
  }
  std::vector<ContactRow> rows;
  for (int face = 0; face < 2; ++face) {
    // Face 0: light cube (body 1) on the ground (body 0); face 1: heavy (2) on light (1)
    const double z = 2.0 * kHalf * face;
    for (const double sx : {-1.0, 1.0}) {
      for (const double sy : {-1.0, 1.0}) rows.push_back({face + 1, face, Vec3(sx * kHalf, sy * kHalf, z), Vec3::UnitZ()});
    }
  }
  const VecX depths = VecX::Zero(static_cast<Index>(rows.size()));
  const RestingSettings defaults;
  return {contactMatrix(bodies, rows), velocityBias(bodies, rows, depths, kH, defaults.baumgarte, defaults.slop)};
}

// Whether the functions every chart builds its LCPs with are written (the stubs throw): without
// them a chart is skipped with one line instead of one per solver.
bool lcpReady(const std::string& chart) {
  return attempt(chart, [] { heavyOnLightLcp(1.0); });
}

void convergenceChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const int most = options.quick ? 3000 : 30000;
  // What the charts draw for an exact zero, which a log axis cannot show
  const double shown_zero = 1e-17;
  Chart chart("A heavy cube on a light one, one step's LCP (8 contacts): residual against PGS sweeps", "PGS sweeps",
              "LCP residual max_i |min(lambda_i, w_i)|");
  chart.logX().logY();
  const double ratios[] = {1.0, 10.0, 100.0, 1000.0};
  const char* dashes[] = {"1", "2", "4", "5"};
  if (!lcpReady("PGS convergence")) return;
  const bool drawn = attempt("PGS convergence", [&] {
    for (int r = 0; r < 4; ++r) {
      const double ratio = ratios[r];
      const LcpProblem lcp = heavyOnLightLcp(ratio);
      LcpOptions lcp_options;
      lcp_options.max_iterations = most;
      lcp_options.tolerance = 0.0;
      std::vector<double> residuals;
      solveLcpPgs(lcp.A, lcp.b, lcp_options, &residuals);
      // About 40 points per decade: a line through every sweep would weigh megabytes in SVG
      Series s{"PGS, ratio " + std::to_string(std::lround(ratio)), {}, {}, std::string("lines lw 2 dt ") + dashes[r]};
      double next = 1.0;
      for (std::size_t k = 0; k < residuals.size(); ++k) {
        const double sweep = static_cast<double>(k + 1);
        if (sweep < next && k + 1 != residuals.size()) continue;
        s.x.push_back(sweep);
        s.y.push_back(std::max(residuals[k], shown_zero));
        next = std::max(next + 1.0, sweep * std::pow(10.0, 1.0 / 40));
      }
      chart.add(s);
      auto after = [&](std::size_t sweeps) { return fmt(residuals[std::min(sweeps, residuals.size()) - 1], 2); };
      std::size_t reached = 0;
      while (reached < residuals.size() && residuals[reached] > 1e-8) ++reached;
      table.add({"PGS, mass ratio " + std::to_string(std::lround(ratio)) + ": residual after 10 / 100 / 1000 sweeps; sweeps to 1e-8",
                 after(10) + " / " + after(100) + " / " + after(1000) + "; " +
                     (reached < residuals.size() ? std::to_string(reached + 1) : "> " + std::to_string(most)),
                 "error shrinks about (1 - 1/(1 + ratio)) per sweep"});
    }
  });
  if (!drawn) return;  // PGS is not written yet: the exact solver alone says nothing about it
  for (const LcpMethod method : {LcpMethod::Pivoting, LcpMethod::Lemke}) {
    const std::string name = lcpMethodName(method);
    attempt(name + " on the mass-ratio LCPs", [&] {
      for (int r = 0; r < 4; ++r) {
        const LcpProblem lcp = heavyOnLightLcp(ratios[r]);
        MatX A = lcp.A;
        // As the World solves it: pivoting needs the regularisation of the four redundant corners
        // per face, which leaves a residual of about 1e-9 of the impulses
        if (method == LcpMethod::Pivoting) A.diagonal().array() += RestingSettings{}.regularization * A.diagonal().maxCoeff();
        const LcpSolution exact = method == LcpMethod::Pivoting ? solveLcpPivoting(A, lcp.b) : solveLcpLemke(A, lcp.b);
        const double residual = std::max(lcpResidual(lcp.A, lcp.b, exact.f), shown_zero);
        if (r == 3) {
          chart.add({name + ", ratio 1000", {1.0, static_cast<double>(most)}, {residual, residual},
                     method == LcpMethod::Pivoting ? "lines lw 2 dt 3" : "lines lw 2 dt 2"});
        }
        table.add({name + ", mass ratio " + std::to_string(std::lround(ratios[r])) + ": residual; pivots",
                   fmt(residual, 2) + "; " + std::to_string(exact.iterations),
                   method == LcpMethod::Pivoting ? "about 1e-9 of the impulses (regularisation)" : "round-off"});
      }
    });
  }
  for (const auto& p : chart.save(options.out + "/lab06_pgs_convergence")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// Cost against drift

struct StackRun {
  double drift = 0.0, ms_per_step = 0.0;
};

// A stack of `cubes` at 60 Hz for `duration` seconds: the largest drift at the end and the
// resting solver's milliseconds per step (PhaseTimes::resting: the LCP, not the collision).
StackRun runStack(int cubes, const Solver& solver, double duration) {
  World world = restingWorld(cubeStack(cubes), solver);
  const std::vector<BodyState> start = world.states();
  const long steps = std::lround(duration / kH);
  for (long n = 0; n < steps; ++n) world.step(kH);
  return {largestDrift(world, start), 1e3 * world.times().resting / static_cast<double>(steps)};
}

void workPrecisionChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  if (!lcpReady("work-precision")) return;
  const int cubes = 10;
  const double duration = options.quick ? 1.0 : 4.0;
  Chart chart("10 stacked cubes, " + fmt(duration) + " s at 60 Hz, velocity level: cost against drift",
              "largest drift of a cube after " + fmt(duration) + " s [m]", "resting solver, ms per step");
  chart.logX().logY();
  bool drawn = attempt("work-precision, PGS", [&] {
    Series pgs{"PGS, 5 to 1000 sweeps", {}, {}, "linespoints pt 7 ps 1.3"};
    std::string drifts;
    for (const int sweeps : {5, 10, 20, 50, 100, 200, 500, 1000}) {
      const StackRun run = runStack(cubes, {Formulation::Velocity, LcpMethod::Pgs, sweeps}, duration);
      pgs.x.push_back(run.drift);
      pgs.y.push_back(run.ms_per_step);
      drifts += (drifts.empty() ? "" : ", ") + std::to_string(sweeps) + ": " + fmt(run.drift, 2);
    }
    chart.add(pgs);
    table.add({"10-cube stack, PGS sweeps: largest drift after " + fmt(duration) + " s [m]", drifts, "< 1e-3 stands"});
    table.add({"10-cube stack, PGS 5 / 100 / 1000 sweeps: ms per step",
               fmt(pgs.y.front(), 2) + " / " + fmt(pgs.y[4], 2) + " / " + fmt(pgs.y.back(), 2), ""});
  });
  for (const LcpMethod method : {LcpMethod::Lemke, LcpMethod::Pivoting}) {
    const std::string name = lcpMethodName(method);
    drawn |= attempt("work-precision, " + name, [&] {
      const StackRun run = runStack(cubes, {Formulation::Velocity, method, 100}, duration);
      const std::string what = method == LcpMethod::Lemke ? " (pyramid)" : " (no friction)";
      chart.add({name + what, {run.drift}, {run.ms_per_step},
                 std::string("points ps 2.5 pt ") + (method == LcpMethod::Lemke ? "9" : "5")});
      table.add({"10-cube stack, " + name + what + ": largest drift [m]; ms per step",
                 fmt(run.drift, 2) + "; " + fmt(run.ms_per_step, 2), "< 1e-3 stands"});
    });
  }
  if (!drawn) return;
  for (const auto& p : chart.save(options.out + "/lab06_work_precision")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// A pyramid over time

void pyramidChart(const DemoOptions& options, int rows, std::vector<std::string>& written, Table& table) {
  if (!lcpReady("pyramid drift")) return;
  const double duration = options.quick ? 1.5 : 5.0;
  const int cubes = rows * (rows + 1) / 2;
  Chart chart("A pyramid of " + std::to_string(rows) + " rows (" + std::to_string(cubes) +
                  " cubes) at 60 Hz: the worst cube's drift, both formulations",
              "time [s]", "largest drift from the start [m]");
  chart.logY();
  // A solver that gives up (LcpFailure) ends its line with a cross rather than the whole chart
  Series failures{"solver failed", {}, {}, "points pt 2 ps 2.5 lw 2 lc rgb 'black'"};
  bool drawn = false;
  for (const Formulation formulation : {Formulation::Velocity, Formulation::Acceleration}) {
    for (const LcpMethod method : {LcpMethod::Pivoting, LcpMethod::Lemke, LcpMethod::Pgs}) {
      const Solver solver{formulation, method, 100};
      const std::string name = solver.name() + ", " + formulationName(formulation);
      drawn |= attempt("pyramid, " + name, [&] {
        World world = restingWorld(cubePyramid(rows), solver);
        const std::vector<BodyState> start = world.states();
        const bool velocity = formulation == Formulation::Velocity;
        const std::string point = method == LcpMethod::Pivoting ? "4" : method == LcpMethod::Lemke ? "6" : "8";
        Series s{name, {}, {}, std::string("linespoints pi 30 pt ") + point + (velocity ? " dt 1" : " dt 2")};
        std::string failure;
        for (long n = 1; n <= std::lround(duration / kH); ++n) {
          try {
            world.step(kH);
          } catch (const LcpFailure& e) {
            failure = e.what();
            break;
          }
          s.x.push_back(world.time());
          s.y.push_back(largestDrift(world, start));
        }
        if (s.x.empty()) throw LcpFailure(failure);
        const std::string ms = fmt(1e3 * world.times().resting / static_cast<double>(s.x.size()), 2);
        if (!failure.empty()) {
          std::cout << "  pyramid, " << name << ": failed at t = " << fmt(world.time(), 3) << " s: " << failure << "\n";
          failures.x.push_back(s.x.back());
          failures.y.push_back(s.y.back());
        }
        table.add({"pyramid of " + std::to_string(rows) + " rows, " + name + " level: drift after " + fmt(s.x.back(), 3) +
                       " s [m]; ms per step",
                   fmt(s.y.back(), 2) + "; " + ms + (failure.empty() ? "" : "; LcpFailure"),
                   velocity ? "< 1e-3 stands" : "no drift correction"});
        chart.add(std::move(s));
      });
    }
  }
  if (!drawn) return;
  if (!failures.x.empty()) chart.add(failures);
  chart.add({"1 mm", {0.0, duration}, {1e-3, 1e-3}, "lines dt 3 lc rgb 'gray30'"});
  for (const auto& p : chart.save(options.out + "/lab06_pyramid_drift")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// The largest pyramid PGS keeps standing, against its sweeps (the framework's matrix-free cone
// PGS, RestingSettings::matrix_free: solveLcpPgsCone()'s iterates at a cost linear in the rows)

World matrixFreeWorld(Scene scene, int sweeps) {
  RestingSettings resting;
  resting.method = LcpMethod::Pgs;
  resting.lcp.max_iterations = sweeps;
  resting.lcp.tolerance = 0.0;
  resting.matrix_free = true;
  resting.slop = 0.001;  // each layer sinks about one slop: 30 layers of 2 mm would reach the bar
  return World(std::move(scene), solverOnlySettings(), std::make_shared<LcpContactSolver>(resting));
}

void largestPyramidChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const std::vector<int> sizes = options.quick ? std::vector<int>{5, 10, 15, 20} : std::vector<int>{5, 10, 15, 20, 25, 30};
  const double duration = options.quick ? 3.0 : 10.0, bar = 0.05;
  Chart chart("Pyramids of " + std::to_string(sizes.front()) + " to " + std::to_string(sizes.back()) + " rows, " +
                  fmt(duration, 2) + " s at 60 Hz: drift against size, matrix-free cone PGS",
              "cubes", "largest drift of any cube [m] (a run stops at 1 m: fallen)");
  chart.logX().logY();
  const char* points[] = {"4 dt 4", "6 dt 3", "8 dt 2", "10 dt 1"};
  const int counts[] = {10, 20, 50, 100};
  const bool drawn = attempt("largest pyramid", [&] {
    for (int k = 0; k < 4; ++k) {
      Series s{"PGS " + std::to_string(counts[k]) + " sweeps", {}, {}, std::string("linespoints pt ") + points[k]};
      int largest = 0;
      for (const int rows : sizes) {
        World world = matrixFreeWorld(cubePyramid(rows), counts[k]);
        const std::vector<BodyState> start = world.states();
        double drift = 0.0;
        // A pyramid that has moved a metre has fallen: no need to watch the rest
        for (long n = 0; n < std::lround(duration / kH) && drift < 1.0; ++n) {
          world.step(kH);
          drift = std::max(drift, largestDrift(world, start));
        }
        s.x.push_back(rows * (rows + 1) / 2);
        s.y.push_back(drift);
        if (drift <= bar) largest = std::max(largest, rows);
      }
      table.add({"largest pyramid standing " + fmt(duration, 2) + " s (drift <= 5 cm), PGS " + std::to_string(counts[k]) +
                     " sweeps [rows]",
                 largest > 0 ? std::to_string(largest) : "none of those tried", "grows with the sweeps"});
      chart.add(std::move(s));
    }
  });
  if (!drawn) return;
  const double most = sizes.back() * (sizes.back() + 1) / 2.0;
  chart.add({"stands below 5 cm", {0.8 * sizes.front() * (sizes.front() + 1) / 2.0, 1.2 * most}, {bar, bar},
             "lines dt 3 lc rgb 'gray30'"});
  for (const auto& p : chart.save(options.out + "/lab06_largest_pyramid")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// Friction ramp

void frictionRampChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  if (!lcpReady("friction ramp")) return;
  const double theta = M_PI / 6, duration = 1.0;
  const std::vector<double> mu = {0.0, 0.2, 0.4, 0.5, 0.7};
  const Vec3 downhill = -Vec3(std::cos(theta), 0.0, std::sin(theta));
  Chart chart("Cubes on a 30 degree ramp, 60 Hz: speed down the slope, one curve per friction coefficient mu",
              "time [s]", "speed down the slope [m/s]");
  // Room right of the curves for their labels
  chart.xRange(0.0, 1.2 * duration);
  bool drawn = false;
  for (const LcpMethod method : {LcpMethod::Lemke, LcpMethod::Pgs}) {
    const bool lemke = method == LcpMethod::Lemke;
    const std::string name = std::string(lcpMethodName(method)) + (lemke ? " (pyramid)" : " (cone)");
    drawn |= attempt("friction ramp, " + name, [&] {
      World world = restingWorld(frictionRamp(theta, mu), {Formulation::Velocity, method, 200});
      std::vector<Series> speeds;
      // Untitled series get no colour from their title: name the method's
      const std::string colour = " lc rgb '" + methodColour(lcpMethodName(method)) + "'";
      for (std::size_t i = 0; i < mu.size(); ++i) {
        // One key entry per solver; each curve's mu is written at its end
        speeds.push_back({i == 0 ? name : "", {0.0}, {0.0}, (lemke ? "points pt 6 ps 1.5" : "lines lw 2") + colour});
      }
      const long steps = std::lround(duration / kH);
      for (long n = 1; n <= steps; ++n) {
        world.step(kH);
        // Lemke's points every fifth step, so that PGS's line shows between them
        if (lemke && n % 5 != 0) continue;
        for (std::size_t i = 0; i < mu.size(); ++i) {
          speeds[i].x.push_back(world.time());
          speeds[i].y.push_back(world.velocity(static_cast<int>(i) + 1).dot(downhill));
        }
      }
      std::string measured, expected;
      for (std::size_t i = 0; i < mu.size(); ++i) {
        measured += (i ? ", " : "") + fmt(speeds[i].y.back() / world.time(), 4);
        expected += (i ? ", " : "") + fmt(std::max(0.0, kG * (std::sin(theta) - mu[i] * std::cos(theta))), 4);
        chart.add(std::move(speeds[i]));
      }
      table.add({name + ", 30 degree ramp, mu = 0, 0.2, 0.4, 0.5, 0.7: acceleration [m/s^2]", measured, expected});
    });
  }
  if (!drawn) return;
  for (std::size_t i = 0; i < mu.size(); ++i) {
    const double a = std::max(0.0, kG * (std::sin(theta) - mu[i] * std::cos(theta)));
    chart.add({i == 0 ? "g (sin theta - mu cos theta) t" : "", {0.0, duration}, {0.0, a * duration},
               "lines lw 1 dt 2 lc rgb 'black'"});
    chart.label({duration, a * duration, "mu = " + fmt(mu[i]) + (a == 0.0 ? " (sticks)" : "")});
  }
  for (const auto& p : chart.save(options.out + "/lab06_friction_ramp")) written.push_back(p);
}

// ---------------------------------------------------------------------------------------------
// Animations

Mat3X toMatrix(const std::vector<Vec3>& points) {
  Mat3X m(3, std::max<std::size_t>(points.size(), 1));
  if (points.empty()) m.col(0) = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < points.size(); ++i) m.col(static_cast<Index>(i)) = points[i];
  return m;
}

// The 12 edges of a box at (x, q), each followed by two NaN columns: in 3D gnuplot joins blocks
// separated by one blank line into a mesh.
void appendBox(std::vector<Vec3>& out, const Vec3& half, const Vec3& x, const Quat& q) {
  const Vec3 gap = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
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
        out.push_back(gap);
        out.push_back(gap);
      }
    }
  }
}

// Films a World's boxes for `duration` seconds in `frames` frames over the view box lo..hi, with
// the ground's outline, the caption giving the time and the largest drift.
std::string film(World world, const std::string& title, const Vec3& lo, const Vec3& hi, int frames, double duration,
                 const std::string& path) {
  // The view starts a little below the ground, so that gnuplot does not clip the bottom edges of
  // cubes that overlap it by a hair
  Animation movie(title, Vec3(lo.x(), lo.y(), lo.z() - 0.02), hi, true);
  const std::vector<Vec3> ground = {Vec3(lo.x(), lo.y(), 0.0), Vec3(hi.x(), lo.y(), 0.0), Vec3(hi.x(), hi.y(), 0.0),
                                    Vec3(lo.x(), hi.y(), 0.0), Vec3(lo.x(), lo.y(), 0.0)};
  const std::vector<BodyState> start = world.states();
  const long steps_per_frame = std::max(1L, std::lround(duration / kH / frames));
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> boxes;
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
      const BodyDescription& b = world.bodies()[i];
      if (const auto* box = std::get_if<Box>(&b.shape); box && !b.fixed) {
        appendBox(boxes, box->half_extents, world.states()[i].x, world.states()[i].q);
      }
    }
    // Three digits of time: captions that repeat make frames that repeat, which gnuplot's GIF
    // optimiser drops with a warning
    movie.addFrame({{toMatrix(ground), "lines lc rgb 'gray50'", ""}, {toMatrix(boxes), "lines lw 1.5 lc rgb '#1f5fbf'", ""}},
                   "t = " + fmt(world.time(), 3) + " s, drift " + fmt(largestDrift(world, start), 2) + " m");
    for (long n = 0; n < steps_per_frame; ++n) world.step(kH);
  }
  return movie.save(path, 5);
}

void pyramidAnimation(const DemoOptions& options, int rows, std::vector<std::string>& written) {
  if (!lcpReady("pyramid animation")) return;
  attempt("pyramid animation", [&] {
    const double width = rows * (2.0 * kHalf + 0.02);
    const Solver solver{Formulation::Velocity, LcpMethod::Pivoting, 100};
    written.push_back(film(restingWorld(cubePyramid(rows), solver),
                           "Pyramid of " + std::to_string(rows) + " rows, velocity level, pivoting",
                           Vec3(-0.6 * width, -0.6 * width, 0.0), Vec3(0.6 * width, 0.6 * width, 1.2 * width),
                           options.quick ? 30 : 60, options.quick ? 1.0 : 3.0, options.out + "/lab06_pyramid.gif"));
  });
}

// A cube 100 times heavier on a light one, PGS at 10 sweeps: the heavy cube sinks through.
void heavyOnLightAnimation(const DemoOptions& options, std::vector<std::string>& written) {
  if (!lcpReady("heavy-on-light animation")) return;
  attempt("heavy-on-light animation", [&] {
    const Solver solver{Formulation::Velocity, LcpMethod::Pgs, 10};
    written.push_back(film(restingWorld(heavyOnLight(100.0), solver),
                           "A cube 100 times heavier on a light one, PGS at 10 sweeps per step",
                           Vec3(-0.4, -0.4, 0.0), Vec3(0.4, 0.4, 0.6), options.quick ? 30 : 60, 3.0,
                           options.out + "/lab06_heavy_on_light.gif"));
  });
}

// A large pyramid with the matrix-free PGS: 100 sweeps keep it standing, 20 let it fall.
void largePyramidAnimations(const DemoOptions& options, std::vector<std::string>& written) {
  // 20 rows in both modes: at 20 sweeps this pyramid falls within 6 s, at 100 it stands
  const int rows = 20;
  const double width = rows * (2.0 * kHalf + 0.02);
  for (const int sweeps : {100, 20}) {
    attempt("large pyramid animation, " + std::to_string(sweeps) + " sweeps", [&] {
      written.push_back(film(matrixFreeWorld(cubePyramid(rows), sweeps),
                             std::to_string(rows * (rows + 1) / 2) + " cubes, matrix-free PGS at " +
                                 std::to_string(sweeps) + " sweeps per step",
                             Vec3(-0.7 * width, -0.7 * width, 0.0), Vec3(0.7 * width, 0.7 * width, 1.1 * width),
                             options.quick ? 30 : 60, options.quick ? 6.0 : 10.0,
                             options.out + "/lab06_pyramid_" + std::to_string(sweeps) + "_sweeps.gif"));
    });
  }
}

void collapseAnimation(const DemoOptions& options, std::vector<std::string>& written) {
  if (!lcpReady("collapse animation")) return;
  attempt("collapse animation", [&] {
    const int cubes = 10;
    const Solver solver{Formulation::Velocity, LcpMethod::Pgs, 5};
    const double height = 2.0 * kHalf * cubes;
    written.push_back(film(restingWorld(cubeStack(cubes), solver), "10 cubes, PGS at 5 sweeps per step",
                           Vec3(-0.75 * height, -0.75 * height, 0.0), Vec3(0.75 * height, 0.75 * height, 1.1 * height),
                           options.quick ? 40 : 80, options.quick ? 2.0 : 4.0, options.out + "/lab06_collapse.gif"));
  });
}

// The contact suite in Lab 5's World and in Lab 6's, each measure's error over its tolerance
// (the benchmark adds Bullet and ODE).
void suiteChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const std::vector<SuiteColumn> columns = {
      {"World(scene, Settings{}): " + Settings{}.toString(), "PhysLab sequential (Lab 5)", "points pt 7 ps 1.3",
       [](const Scene& scene) { return std::make_unique<WorldEngine>(World(scene, Settings{})); }},
      {"World(scene, restingWorldSettings(), LcpContactSolver(RestingSettings{})): " + RestingSettings{}.toString(),
       "PhysLab PGS (Lab 6)", "points pt 5 ps 1.3",
       [](const Scene& scene) {
         return std::make_unique<WorldEngine>(
             World(scene, restingWorldSettings(), std::make_shared<LcpContactSolver>(RestingSettings{})));
       }}};
  const SuiteReport report = contactSuiteReport(
      columns, "Lab 6 demo: the contact suite (textbook scenes against physical truth), h = 1/60 s",
      options.out + "/lab06_suite", std::cout);
  written.insert(written.end(), report.paths.begin(), report.paths.end());
  table.add({"contact suite: measures passed, Lab 5 / Lab 6",
             std::to_string(report.passed[0]) + " / " + std::to_string(report.passed[1]),
             "of " + std::to_string(report.measures)});
}

// The suite's 10-cube stack over 10 s, the top's sideways distance against time: each World with
// and without shock propagation (Lab 5, section 11), and the soft step (the benchmark adds the peers)
void stackDriftDemo(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const auto world = [](Settings settings, std::shared_ptr<RestingContactSolver> solver) {
    return [settings, solver](const Scene& scene) { return std::make_unique<WorldEngine>(World(scene, settings, solver)); };
  };
  Settings lab5_off, lab6_off = restingWorldSettings();
  lab5_off.shock_propagation = lab6_off.shock_propagation = false;
  const auto pgs = [] { return std::make_shared<LcpContactSolver>(RestingSettings{}); };
  const std::vector<SuiteColumn> columns = {
      {"", "PhysLab sequential (Lab 5)", "lines lw 2", world(Settings{}, nullptr)},
      {"", "PhysLab sequential (Lab 5), no shock propagation", "lines dt 2 lw 2", world(lab5_off, nullptr)},
      {"", "PhysLab PGS (Lab 6)", "lines lw 2", world(restingWorldSettings(), pgs())},
      {"", "PhysLab PGS (Lab 6), no shock propagation", "lines dt 2 lw 2", world(lab6_off, pgs())},
      {"", "PhysLab soft step (Lab 6)", "lines lw 2",
       world(restingWorldSettings(), std::make_shared<SoftStepSolver>(SoftStepSettings{}))}};
  const StackDrift drift = stackDriftChart(columns, options.out + "/lab06_stack_drift", std::cout);
  written.insert(written.end(), drift.paths.begin(), drift.paths.end());
  for (std::size_t c = 0; c < columns.size(); ++c) {
    table.add({"10-cube stack, 10 s: top's largest sideways drift [mm], " + columns[c].label.substr(8),
               fmt(1e3 * drift.largest[c], 3), "0 (suite's bar: 1)"});
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv,
        "Lab 6 demo: PGS convergence against the mass ratio, solver cost against stack drift, a pyramid at "
        "both levels, the largest pyramid PGS keeps standing, a friction ramp, the textbook contact scenes, a stack's top drift against time, standing "
        "and falling pyramids and a collapsing stack.");
    std::vector<std::string> written;
    Table table({"quantity", "measured", "expected"});
    // A pyramid's LCP is dense and the exact solvers' cost grows fast with its size: with 4 rows
    // (64 contacts) pivoting takes about 7 ms per step and Lemke 16 ms; with 5 rows pivoting takes 40 ms
    const int rows = 4;
    convergenceChart(options, written, table);
    workPrecisionChart(options, written, table);
    pyramidChart(options, rows, written, table);
    largestPyramidChart(options, written, table);
    frictionRampChart(options, written, table);
    attempt("contact suite", [&] { suiteChart(options, written, table); });
    attempt("stack drift", [&] { stackDriftDemo(options, written, table); });
    pyramidAnimation(options, rows, written);
    collapseAnimation(options, written);
    largePyramidAnimations(options, written);
    heavyOnLightAnimation(options, written);
    reportDemo("Lab 6", written, table, options.out + "/lab06_summary.md");
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "demo_06_resting_contact: " << e.what() << "\n";
    return 1;
  }
}
