// Lab 1 demo: how the integrators trade cost for accuracy, and where they break.
// Writes energy-drift, work-precision and stability charts and an N-body animation; then a flock
// of boids (an animation and its order parameter) and tracer paths in a curl-noise flow.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <random>

#include "physlab/curl_noise.hpp"
#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/integrators.hpp"
#include "physlab/neighbours.hpp"
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

// A force that keeps each particle near the cruising speed s: f = k (s - |v|) v / |v|. Boids
// steer but do not propel: alignment averages velocities, which shrinks them, and without this a
// flock of random headings slows to a stop instead of flying off together.
class Cruise final : public Force {
 public:
  Cruise(double speed_, double k_) : speed(speed_), k(k_) {}
  std::string name() const override { return "cruise"; }
  void accumulate(const ParticleView& s, Points F) const override {
    for (Index i = 0; i < s.v.cols(); ++i) {
      const double v = s.v.col(i).norm();
      if (v > 0.0) F.col(i) += (k * (speed - v) / v) * s.v.col(i);
    }
  }
  double potential(const ParticleView& /*s*/) const override { return 0.0; }
  const double speed, k;
};

// A flock of boids in the plane (with a cruise force), stepped by symplectic Euler: with
// alignment (w_a = 8) and without (w_a = 0, separation and cohesion only), from the same random
// headings. Writes the order parameter of both over time, and an animation of the aligning flock.
void flockDemo(const DemoOptions& options, std::vector<std::string>& written) {
  const Index n = 250;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5), angle(0.0, 2.0 * M_PI);
  Mat3X x0 = Mat3X::Zero(3, n), v0 = Mat3X::Zero(3, n);
  for (Index i = 0; i < n; ++i) {
    x0.col(i) << coordinate(rng), coordinate(rng), 0.0;
    const double a = angle(rng);
    v0.col(i) << std::cos(a), std::sin(a), 0.0;
  }
  const double h = 0.02;
  const int frames = options.quick ? 30 : 60, steps_per_frame = 5;
  Chart order("Boids: order parameter |mean unit heading| (N = " + std::to_string(n) + ", R = 1.2)", "time [s]",
              "order parameter");
  order.yRange(0.0, 1.05);
  for (const double wa : {8.0, 0.0}) {
    const std::string title = wa > 0.0 ? "separation + alignment + cohesion" : "separation + cohesion only";
    attempt("boids flock (" + title + ")", [&] {
      ParticleSystem sys(VecX::Ones(n));
      sys.addForce(std::make_shared<Boids>(1.2, 0.02, wa, 1.5));
      sys.addForce(std::make_shared<Cruise>(1.0, 2.0));
      VecX X = sys.makeState(x0, v0);
      Integrator integrator(Method::SymplecticEuler);
      Series series{title, {0.0}, {orderParameter(velocities(X))},
                    wa > 0.0 ? "lines lw 2 lc rgb '#2266aa'" : "lines lw 2 lc rgb '#cc6633'"};
      std::vector<Mat3X> shots{positions(X)}, headings{velocities(X)};
      for (int f = 1; f <= frames; ++f) {
        for (int k = 0; k < steps_per_frame; ++k) integrator.step(sys, X, h);
        series.x.push_back(f * steps_per_frame * h);
        series.y.push_back(orderParameter(velocities(X)));
        shots.push_back(positions(X));
        headings.push_back(velocities(X));
      }
      order.add(series);
      if (wa == 0.0) return;
      // The animation's box holds every frame; each boid is a dot with a short line along its heading.
      Vec3 lo = shots[0].rowwise().minCoeff(), hi = shots[0].rowwise().maxCoeff();
      for (const Mat3X& shot : shots) {
        lo = lo.cwiseMin(shot.rowwise().minCoeff());
        hi = hi.cwiseMax(shot.rowwise().maxCoeff());
      }
      Animation animation("Boids: separation, alignment, cohesion (symplectic Euler, h = 0.02)",
                          lo - Vec3(0.3, 0.3, 0.0), hi + Vec3(0.3, 0.3, 0.0), false);
      for (std::size_t f = 0; f < shots.size(); f += options.quick ? 2 : 1) {
        Mat3X ticks(3, 3 * n);
        for (Index i = 0; i < n; ++i) {
          const double speed = headings[f].col(i).norm();
          const Vec3 dir = speed > 0.0 ? Vec3(headings[f].col(i) / speed) : Vec3::Zero();
          ticks.col(3 * i) = shots[f].col(i);
          ticks.col(3 * i + 1) = shots[f].col(i) + 0.25 * dir;
          ticks.col(3 * i + 2).setConstant(NAN);
        }
        animation.addFrame({{ticks, "lines lw 1 lc rgb '#2266aa'", ""}, {shots[f], "points pt 7 ps 0.8 lc rgb '#2266aa'", ""}},
                           "t = " + fmt(static_cast<double>(f) * steps_per_frame * h, 3) + " s, order " +
                               fmt(series.y[f], 2));
      }
      written.push_back(animation.save(options.out + "/lab01_flock.gif", 8));
    });
  }
  for (const auto& p : order.save(options.out + "/lab01_flock_order")) written.push_back(p);
}

// Tracers in a curl-noise flow around a disc (radius 0.5 at the origin, ramp width 0.5): RK4
// paths from a line of starting points upstream.
void curlNoiseDemo(const DemoOptions& options, std::vector<std::string>& written) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<NoiseWave> waves;
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * M_PI * unit(rng), size = 1.0 + 2.0 * unit(rng);
    waves.push_back({0.05 + 0.1 * unit(rng), size * Eigen::Vector2d(std::cos(a), std::sin(a)), 2.0 * M_PI * unit(rng)});
  }
  // A uniform stream to the right on top of the noise: psi_0 += U y, as the long wave
  // U sin(eps y) / eps would give for small eps.
  waves.push_back({40.0, Eigen::Vector2d(0.0, 0.01), 0.0});
  const CurlNoise field(waves, Vec3::Zero(), 0.5, 0.5, 1e-4);
  Chart chart("Curl noise: RK4 tracer paths around a solid disc (h = 0.01)", "x [m]", "y [m]");
  chart.equalAxes().xRange(-2.2, 2.2).yRange(-1.6, 1.6);
  Series circle{"solid boundary", {}, {}, "lines lw 2 lc rgb '#cc3333'"};
  for (int k = 0; k <= 200; ++k) {
    circle.x.push_back(0.5 * std::cos(2.0 * M_PI * k / 200));
    circle.y.push_back(0.5 * std::sin(2.0 * M_PI * k / 200));
  }
  double closest = 1e300;
  attempt("curl-noise tracers", [&] {
    Series paths{"tracer paths", {}, {}, "lines lw 1 lc rgb '#2266aa'"};
    const int tracers = options.quick ? 15 : 31;
    const double h = 0.01;
    for (int k = 0; k < tracers; ++k) {
      Vec3 p(-2.0, -1.5 + 3.0 * k / (tracers - 1), 0.0);
      for (int step = 0; step < 1500 && std::abs(p.x()) < 2.2; ++step) {
        paths.x.push_back(p.x());
        paths.y.push_back(p.y());
        const Vec3 k1 = curlNoiseVelocity(field, p);
        const Vec3 k2 = curlNoiseVelocity(field, p + 0.5 * h * k1);
        const Vec3 k3 = curlNoiseVelocity(field, p + 0.5 * h * k2);
        const Vec3 k4 = curlNoiseVelocity(field, p + h * k3);
        p += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        closest = std::min(closest, field.distance(p));
      }
      paths.x.push_back(NAN);
      paths.y.push_back(NAN);
    }
    chart.add(paths).add(circle);  // the disc alone, without paths, would show nothing of the student's code
    std::cout << "curl noise: closest approach of any tracer to the disc: " << fmt(closest) << " m\n";
  });
  for (const auto& p : chart.save(options.out + "/lab01_curl_noise")) written.push_back(p);
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
    flockDemo(options, written);
    curlNoiseDemo(options, written);

    reportDemo("Lab 1", written, table, options.out + "/lab01_summary.md");
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "demo_01_particles: " << e.what() << "\n";
    return 1;
  }
}
