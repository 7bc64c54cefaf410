// Lab 2 demo: why stiff springs need implicit integration, what it costs, and a falling cloth.
// Writes stability-vs-stiffness, cloth energy, work-precision (CG vs LDLT), ground-stiffness
// charts and an animated GIF of a cloth landing on the ground.
#include <cmath>
#include <functional>
#include <iostream>

#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/integrators.hpp"
#include "physlab/particles.hpp"
#include "physlab/plot.hpp"
#include "physlab/springs.hpp"

using namespace physlab;

namespace {

// A free chain of n particles (mass m) and springs k at rest length 1 along x.
SpringNetwork chain(Index n, double m, double k) {
  SpringNetwork net;
  net.masses = VecX::Constant(n, m);
  net.rest_positions = Mat3X::Zero(3, n);
  for (Index i = 0; i < n; ++i) net.rest_positions(0, i) = static_cast<double>(i);
  for (Index i = 0; i + 1 < n; ++i) net.springs.push_back({i, i + 1, 1.0, k, 0.0});
  return net;
}

// One step of any of Lab 1's methods, or of the implicit spring step.
using Stepper = std::function<void(const SpringSystem&, VecX&, double)>;

Stepper lab1Stepper(Method method) {
  return [method](const SpringSystem& sys, VecX& X, double h) {
    Integrator integrator(method);
    integrator.step(sys, X, h);
  };
}

// CG at its default tolerance: its error is far below implicit Euler's own at these steps.
ImplicitSettings implicitSettings(LinearSolver solver) {
  ImplicitSettings settings;
  settings.solver = solver;
  settings.cg_max_iterations = 5000;
  return settings;
}

Stepper implicitStepper(LinearSolver solver) {
  return [solver](const SpringSystem& sys, VecX& X, double h) {
    implicitEulerStep(sys, X, h, implicitSettings(solver));
  };
}

// Largest step (bisection, 1e-3 relative) for which 2000 steps keep a small perturbation's
// energy below 10x its start; capped at `cap`.
double largestStableStep(const SpringSystem& sys, const Stepper& step, double cap) {
  VecX X0 = sys.restState();
  for (Index i = 0; i < sys.positionSize(); ++i) X0[i] += 1e-6 * std::sin(1.0 + 7.0 * i);
  const double E0 = sys.energy(X0);
  auto stable = [&](double h) {
    VecX X = X0;
    for (int n = 0; n < 2000; ++n) {
      try {
        step(sys, X, h);
      } catch (const InvalidInput&) {
        return false;  // the state blew up to infinity
      } catch (const NumericalFailure&) {
        return false;
      }
      if (!(sys.energy(X) < 10.0 * E0)) return false;
    }
    return true;
  };
  if (stable(cap)) return cap;
  double lo = cap * 1e-8, hi = cap;
  while (hi / lo > 1.001) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

void stabilityChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const Index n = 10;
  const double m = 0.1;
  Chart chart("Largest stable step on a 10-particle chain (m = 0.1 kg)", "spring stiffness k [N/m]",
              "largest stable step h [s]");
  chart.logX().logY();
  const std::vector<std::pair<std::string, Stepper>> methods = {
      {"explicit Euler", lab1Stepper(Method::ExplicitEuler)},
      {"symplectic Euler", lab1Stepper(Method::SymplecticEuler)},
      {"RK4", lab1Stepper(Method::RK4)},
      {"implicit Euler (capped at 1 s)", implicitStepper(LinearSolver::LDLT)}};
  const int points = options.quick ? 4 : 11;
  for (const auto& [name, step] : methods) {
    Series s{name, {}, {}, "linespoints"};
    // Structured bindings are captured by name only from C++20: give the lambda its own references
    attempt(name, [&, &name = name, &step = step] {
      for (int p = 0; p < points; ++p) {
        const double k = std::pow(10.0, 1.0 + 5.0 * p / (points - 1));
        const SpringSystem sys(chain(n, m, k));
        const double h_max = largestStableStep(sys, step, 1.0);
        s.x.push_back(k);
        s.y.push_back(h_max);
      }
      table.add({"chain, k = 1e6", name, "largest stable h = " + fmt(s.y.back())});
    });
    chart.add(s);
  }
  // Theory: the top mode of a free chain has w_max = 2 sqrt(k/m) sin((n-1) pi / (2n)), and
  // symplectic Euler is stable for h w_max < 2, RK4 for h w_max < 2 sqrt 2.
  Series theory{"theory: h w_{max} = 2", {}, {}, "lines dashtype 2"};
  for (double k = 10.0; k <= 1.0001e6; k *= 10.0) {
    theory.x.push_back(k);
    theory.y.push_back(2.0 / (2.0 * std::sqrt(k / m) * std::sin((n - 1) * M_PI / (2.0 * n))));
  }
  chart.add(theory);
  for (const auto& p : chart.save(options.out + "/lab02_stability")) written.push_back(p);
}

void clothEnergyChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  SpringNetwork net = makeCloth(10, 10, 1.0, 1.0, 0.3, 100.0, 0.0);
  net.masses[0] = net.masses[9] = std::numeric_limits<double>::infinity();
  const SpringSystem sys(net);
  const double T = options.quick ? 1.0 : 4.0;
  Chart chart("Cloth pinned at two corners, k = 100 N/m, no damping: total energy",
              "time [s]", "energy E - E_0 [J]");
  const std::vector<std::tuple<std::string, Stepper, double>> runs = {
      {"symplectic Euler, h = 1/600", lab1Stepper(Method::SymplecticEuler), 1.0 / 600},
      {"explicit Euler, h = 1/600", lab1Stepper(Method::ExplicitEuler), 1.0 / 600},
      {"RK4, h = 1/600", lab1Stepper(Method::RK4), 1.0 / 600},
      {"implicit Euler, h = 1/600", implicitStepper(LinearSolver::ConjugateGradient), 1.0 / 600},
      {"implicit Euler, h = 1/60", implicitStepper(LinearSolver::ConjugateGradient), 1.0 / 60}};
  for (const auto& [name, step, h] : runs) {
    // The long step dashed: the same method, so the same colour
    Series s{name, {}, {}, h > 1.0 / 100 ? "lines dt 2" : "lines"};
    attempt(name, [&, &name = name, &step = step, h = h] {
      VecX X = sys.restState();
      const double E0 = sys.energy(X);
      const long steps = std::lround(T / h);
      for (long n = 1; n <= steps; ++n) {
        step(sys, X, h);
        if (!X.allFinite() || std::abs(sys.energy(X) - E0) > 1e3) break;  // it has blown up
        if (n % std::max(1L, steps / 300) == 0) {
          s.x.push_back(n * h);
          s.y.push_back(sys.energy(X) - E0);
        }
      }
      table.add({"cloth 10x10, k = 100", name, "E - E0 at end = " + fmt(s.y.empty() ? NAN : s.y.back())});
    });
    chart.add(s);
  }
  chart.yRange(-2.0, 0.5);
  for (const auto& p : chart.save(options.out + "/lab02_cloth_energy")) written.push_back(p);
}

void workPrecisionChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  Chart chart("Work-precision: implicit Euler on a 12x12 cloth, 0.25 s, CG vs LDLT",
              "wall time [s]", "RMS position error [m]");
  chart.logX().logY();
  for (double k : {1e2, 1e4}) {
    SpringNetwork net = makeCloth(12, 12, 1.0, 1.0, 0.3, k, 0.1);
    net.masses[0] = net.masses[11] = std::numeric_limits<double>::infinity();
    const SpringSystem sys(net);
    const double T = 0.25;
    // Reference: RK4 far inside its stability limit (h w_max ~ 0.1 at k = 1e4).
    VecX reference = sys.restState();
    Integrator rk4(Method::RK4);
    bool have_reference = attempt("reference RK4", [&] {
      for (int n = 0; n < 20000; ++n) rk4.step(sys, reference, T / 20000);
    });
    if (!have_reference) continue;
    for (LinearSolver solver : {LinearSolver::ConjugateGradient, LinearSolver::LDLT}) {
      // Colour for the solver, dashes and marks for the stiffness
      Series s{solverName(solver) + ", k = " + fmt(k), {}, {}, k > 1e3 ? "linespoints dt 2 pt 6" : "linespoints pt 7"};
      attempt(s.title, [&] {
        for (int level = 0; level < (options.quick ? 4 : 7); ++level) {
          const long steps = 4L << level;
          VecX X = sys.restState();
          Stopwatch clock;
          for (long n = 0; n < steps; ++n) implicitEulerStep(sys, X, T / steps, implicitSettings(solver));
          s.x.push_back(clock.seconds());
          s.y.push_back((positions(X) - positions(reference)).norm() / std::sqrt(sys.count()));
        }
        table.add({"cloth 12x12, k = " + fmt(k), "implicit, " + solverName(solver),
                   "error " + fmt(s.y.back()) + " in " + fmt(s.x.back()) + " s"});
      });
      chart.add(s);
    }
  }
  for (const auto& p : chart.save(options.out + "/lab02_work_precision")) written.push_back(p);
}

void groundChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  Chart chart("A jelly cube dropped on the penalty ground: lowest point", "time [s]", "lowest z [m]");
  for (double kg : {1e2, 1e3, 1e4}) {
    SpringNetwork net = makeJelly(3, 0.3, 0.3, 1.0, 500.0, 1.0);
    net.ground = {0.0, kg, 2.0};
    const SpringSystem sys(net);
    Series s{"ground k = " + fmt(kg) + " N/m", {}, {}, "lines"};
    attempt(s.title, [&] {
      VecX X = sys.restState();
      const double h = 1.0 / 600;
      double lowest = 1e300;
      for (int n = 1; n <= (options.quick ? 400 : 1200); ++n) {
        implicitEulerStep(sys, X, h);
        const double z = positions(X).row(2).minCoeff();
        lowest = std::min(lowest, z);
        if (n % 4 == 0) {
          s.x.push_back(n * h);
          s.y.push_back(z);
        }
      }
      table.add({"jelly drop", "ground k = " + fmt(kg), "deepest penetration " + fmt(-lowest) + " m"});
    });
    chart.add(s);
  }
  for (const auto& p : chart.save(options.out + "/lab02_ground_stiffness")) written.push_back(p);
}

// The cloth's grid lines as one point list, NaN columns separating the lines.
Mat3X gridLines(const ConstPoints& x, Index nx, Index ny) {
  Mat3X lines(3, 2 * nx * ny + nx + ny);
  Index c = 0;
  const Vec3 gap = Vec3::Constant(NAN);
  for (Index j = 0; j < ny; ++j) {
    for (Index i = 0; i < nx; ++i) lines.col(c++) = x.col(j * nx + i);
    lines.col(c++) = gap;
  }
  for (Index i = 0; i < nx; ++i) {
    for (Index j = 0; j < ny; ++j) lines.col(c++) = x.col(j * nx + i);
    lines.col(c++) = gap;
  }
  return lines;
}

void clothAnimation(const DemoOptions& options, std::vector<std::string>& written) {
  const Index nx = 15;
  SpringNetwork net = makeCloth(nx, nx, 1.0, 0.6, 0.3, 2000.0, 0.5);
  net.ground = {0.0, 2e3, 1.0};
  net.drag = 0.01;
  // Tilt the cloth so that one corner lands first.
  for (Index i = 0; i < net.rest_positions.cols(); ++i) {
    net.rest_positions(2, i) += 0.3 * net.rest_positions(0, i);
  }
  const SpringSystem sys(net);
  VecX X = sys.restState();
  Animation animation("Cloth falling onto the ground (implicit Euler, h = 1/240 s)", Vec3(-0.2, -0.2, 0.0),
                      Vec3(1.4, 1.2, 1.0), true);
  // The same 1.5 s either way, so that the quick GIF also shows the landing: fewer frames only.
  const int frames = options.quick ? 20 : 60;
  const int steps_per_frame = 360 / frames;
  attempt("cloth animation", [&] {
    for (int f = 0; f < frames; ++f) {
      for (int n = 0; n < steps_per_frame; ++n) implicitEulerStep(sys, X, 1.0 / 240);
      animation.addFrame({{gridLines(positions(X), nx, nx), "lines lw 1 lc rgb '#3366aa'", ""}},
                         "t = " + fmt((f + 1) * steps_per_frame / 240.0, 3) + " s");
    }
    written.push_back(animation.save(options.out + "/lab02_cloth.gif", 5));
  });
}

}  // namespace

int main(int argc, char** argv) {
  keepFreedMemory();
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv, "Lab 2 demo: stiffness and stability, implicit integration, CG vs LDLT, cloth.");
    std::vector<std::string> written;
    Table table({"scene", "method", "outcome"});
    stabilityChart(options, written, table);
    clothEnergyChart(options, written, table);
    workPrecisionChart(options, written, table);
    groundChart(options, written, table);
    clothAnimation(options, written);
    reportDemo("Lab 2", written, table, options.out + "/lab02_summary.md");
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "demo_02_springs: " << e.what() << "\n";
    return 1;
  }
}
