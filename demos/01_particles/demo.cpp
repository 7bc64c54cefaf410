// Lab 1 demo: how the integrators trade cost for accuracy, and where they break.
// Writes energy-drift, work-precision and stability charts and an N-body animation.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <memory>

#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/integrators.hpp"
#include "physlab/particles.hpp"
#include "physlab/plot.hpp"
#include "physlab/scenes.hpp"

using namespace physlab;

namespace {

struct DriftRun {
  std::vector<double> t, error;
  double final_error = NAN;
  std::string failure;  // why the run stopped early, if it did
  long evaluations = 0;
  double seconds = 0.0;
};

// Relative energy error |E - E0| / |E0| over time, sampled about 400 times.
DriftRun energyDrift(Method method, const System& sys, const std::function<double(const VecX&)>& energy,
                     VecX X, double h, long steps) {
  DriftRun run;
  const double E0 = energy(X);
  Integrator integrator(method);
  sys.resetCount();
  const long every = std::max(1L, steps / 400);
  Stopwatch clock;
  try {
    for (long n = 1; n <= steps; ++n) {
      integrator.step(sys, X, h);
      if (n % every == 0) {
        run.t.push_back(n * h);
        run.error.push_back(std::abs(energy(X) - E0) / std::abs(E0));
      }
    }
  } catch (const NumericalFailure&) {
    // The method broke down (implicit Euler's orbit decays into the sun): keep what it did.
    run.failure = "broke down at t = " + fmt(run.t.empty() ? 0.0 : run.t.back());
  }
  run.seconds = clock.seconds();
  run.evaluations = sys.forceEvaluations();
  run.final_error = std::abs(energy(X) - E0) / std::abs(E0);
  return run;
}

std::vector<std::string> driftChart(const std::string& title, const std::map<Method, DriftRun>& runs,
                                    const std::string& stem) {
  Chart chart(title, "time [s]", "relative energy error |E - E_0| / |E_0|");
  chart.logY();
  for (const auto& [method, run] : runs) chart.add({methodName(method), run.t, run.error, "lines"});
  return chart.save(stem);
}

// One orbit of the Kepler problem (e = 0.6) at several step sizes: position error after one
// period (when the exact state equals the initial one) against force evaluations and seconds.
void workPrecision(const DemoOptions& options, std::vector<std::string>& written) {
  const Kepler kepler(1.0);
  const VecX X0 = kepler.perihelionState(1.0, 0.6);
  const double T = kepler.period(1.0);
  Chart by_evals("Work-precision: Kepler orbit, e = 0.6, one period", "force evaluations",
                 "position error after one period");
  Chart by_time("Work-precision: Kepler orbit, e = 0.6, one period", "wall time [s]",
                "position error after one period");
  by_evals.logX().logY();
  by_time.logX().logY();
  const int levels = options.quick ? 6 : 9;
  for (Method method : kAllMethods) {
    Series evals{methodName(method), {}, {}, "linespoints"};
    Series seconds{methodName(method), {}, {}, "linespoints"};
    attempt(methodName(method), [&] {
      for (int level = 0; level < levels; ++level) {
        const long steps = 100L << level;
        if (method == Method::ImplicitEuler && steps < 1600) continue;  // spirals into the sun
        VecX X = X0;
        Integrator integrator(method);
        // Repeat short runs until 20 ms have passed so the timer's resolution does not matter;
        // the fastest of three such windows, so that a busy moment does not zig-zag the line.
        double best = INFINITY;
        long evaluations = 0;
        for (int window = 0; window < 3; ++window) {
          kepler.resetCount();
          Stopwatch clock;
          int repeats = 0;
          do {
            X = X0;
            for (long n = 0; n < steps; ++n) integrator.step(kepler, X, T / steps);
            ++repeats;
          } while (clock.seconds() < 0.02);
          best = std::min(best, clock.seconds() / repeats);
          evaluations = kepler.forceEvaluations() / repeats;
        }
        const double error = (X.head<3>() - X0.head<3>()).norm();
        evals.x.push_back(static_cast<double>(evaluations));
        evals.y.push_back(error);
        seconds.x.push_back(best);
        seconds.y.push_back(error);
      }
    });
    by_evals.add(evals);
    by_time.add(seconds);
  }
  for (const auto& p : by_evals.save(options.out + "/lab01_work_precision_evals")) written.push_back(p);
  for (const auto& p : by_time.save(options.out + "/lab01_work_precision_time")) written.push_back(p);
}

// Growth factor per step (spectral radius of the step map) on the oscillator against h omega.
void stabilityChart(const DemoOptions& options, std::vector<std::string>& written) {
  const HarmonicOscillator osc(1.0);
  Chart chart("Stability on the oscillator: growth of the amplitude per step",
              "h omega", "spectral radius of one step (> 1: unstable)");
  chart.logX().yRange(0.0, 2.5);
  for (Method method : kAllMethods) {
    Series s{methodName(method), {}, {}, "lines"};
    attempt(methodName(method), [&] {
      for (double hw = 0.01; hw <= 10.0; hw *= 1.02) {
        Eigen::Matrix2d A;
        Integrator integrator(method);
        for (int j = 0; j < 2; ++j) {
          VecX X = VecX::Unit(2, j);
          integrator.step(osc, X, hw);
          A.col(j) = X;
        }
        s.x.push_back(hw);
        s.y.push_back(spectralRadius(A));
      }
    });
    chart.add(s);
  }
  chart.mark({2.0, "h omega = 2 (symplectic Euler, Verlet)"});
  chart.mark({2.0 * std::sqrt(2.0), "2 sqrt 2 (RK4)"});
  for (const auto& p : chart.save(options.out + "/lab01_stability")) written.push_back(p);
}

// The figure-eight three-body choreography (Chenciner & Montgomery), integrated with Verlet
// on the student's N-body gravity.
void nbodyAnimation(const DemoOptions& options, std::vector<std::string>& written) {
  auto sys = std::make_shared<ParticleSystem>(VecX::Ones(3));
  sys->addForce(std::make_shared<NBodyGravity>(1.0, 0.0));
  Mat3X x(3, 3), v(3, 3);
  x << 0.97000436, -0.97000436, 0.0, -0.24308753, 0.24308753, 0.0, 0.0, 0.0, 0.0;
  v << 0.466203685, 0.466203685, -0.93240737, 0.43236573, 0.43236573, -0.86473146, 0, 0, 0;
  VecX X = sys->makeState(x, v);
  Animation animation("Figure-eight three-body orbit (Verlet, h = 0.002)", Vec3(-1.3, -1.3, 0),
                      Vec3(1.3, 1.3, 0), false);
  animation.axes("x (G = m = 1 units)", "y (G = m = 1 units)");  // Chenciner-Montgomery's units
  Integrator verlet(Method::Verlet);
  const double h = 0.002, period = 6.3259;
  const int frames = options.quick ? 30 : 90;
  const long steps_per_frame = std::lround(period / h / frames);
  std::vector<Mat3X> trail;
  attempt("N-body animation", [&] {
    for (int f = 0; f < frames; ++f) {
      for (long n = 0; n < steps_per_frame; ++n) verlet.step(*sys, X, h);
      trail.push_back(positions(X));
      Mat3X path(3, 3 * trail.size() + 3);
      for (Index body = 0; body < 3; ++body) {
        for (std::size_t k = 0; k < trail.size(); ++k) path.col(body * (trail.size() + 1) + k) = trail[k].col(body);
        path.col(body * (trail.size() + 1) + trail.size()).setConstant(NAN);
      }
      animation.addFrame({{path.leftCols(3 * (trail.size() + 1)), "lines lw 1 lc rgb '#9999cc'", "paths"},
                          {positions(X), "points pt 7 ps 2.5 lc rgb '#cc3333'", "bodies"}},
                         "t = " + fmt(f * steps_per_frame * h, 3) + " s");
    }
    written.push_back(animation.save(options.out + "/lab01_nbody.gif", 6));
  });
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const DemoOptions options =
        parseDemoOptions(argc, argv, "Lab 1 demo: energy drift, work-precision and stability of the integrators.");
    std::vector<std::string> written;
    Table table({"system", "integrator", "h", "final |dE|/E0", "force evals", "wall time [s]"});

    // Energy drift on the oscillator (omega = 1) and the Kepler orbit (e = 0.6).
    const HarmonicOscillator osc(1.0);
    const Kepler kepler(1.0);
    const double osc_h = 0.1, kepler_h = 0.01;
    const long osc_steps = options.quick ? 1000 : 10000;
    const long kepler_steps = std::lround((options.quick ? 10 : 100) * kepler.period(1.0) / kepler_h);
    std::map<Method, DriftRun> osc_runs, kepler_runs;
    for (Method method : kAllMethods) {
      attempt(methodName(method), [&] {
        osc_runs[method] = energyDrift(method, osc, [&](const VecX& Y) { return osc.energy(Y); },
                                       Eigen::Vector2d(1.0, 0.0), osc_h, osc_steps);
      });
      attempt(methodName(method), [&] {
        kepler_runs[method] = energyDrift(method, kepler, [&](const VecX& Y) { return kepler.energy(Y); },
                                          kepler.perihelionState(1.0, 0.6), kepler_h, kepler_steps);
      });
    }
    for (const auto& [name, runs, h] : {std::tuple{"oscillator", &osc_runs, osc_h},
                                        std::tuple{"Kepler e=0.6", &kepler_runs, kepler_h}}) {
      for (const auto& [method, run] : *runs) {
        table.add({name, methodName(method), fmt(h), run.failure.empty() ? fmt(run.final_error) : run.failure,
                   std::to_string(run.evaluations),
                   fmt(run.seconds)});
      }
    }
    for (const auto& p : driftChart("Energy drift: harmonic oscillator, h omega = 0.1", osc_runs,
                                    options.out + "/lab01_energy_oscillator")) {
      written.push_back(p);
    }
    for (const auto& p : driftChart("Energy drift: Kepler orbit, e = 0.6, h = 0.01", kepler_runs,
                                    options.out + "/lab01_energy_kepler")) {
      written.push_back(p);
    }
    workPrecision(options, written);
    stabilityChart(options, written);
    nbodyAnimation(options, written);

    reportDemo("Lab 1", written, table, options.out + "/lab01_summary.md");
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "demo_01_particles: " << e.what() << "\n";
    return 1;
  }
}
