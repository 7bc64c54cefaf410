// Lab 1 benchmark: time per particle-step of every explicit integrator on gravity + drag for
// N = 10^3 ... 10^6, next to a memory-bandwidth bound measured in the same run, and RK4 next to
// Boost.Odeint's runge_kutta4 on the same system.
//
// The bound: any one-step method must at least read the state and write it back. A STREAM-style
// triad a = b + s c over arrays of the state's length (6N doubles) is the cheapest such update,
// so "steps cost k triads" says how far a method is from the memory floor. Every step is also
// counted for heap allocations (after the timing, so the workspace is sized): a step makes none.
//
// Then the fixed-radius neighbour search (section 5): time per search on a uniform cloud of
// constant density (about 10 neighbours within r per particle) for N = 10^2 ... 10^6, the grid
// against brute force (up to N = 3 10^4, where one search already takes about a second), drawn on a
// log-log chart with O(N^2) and O(N) slope guides, and the crossover N where the grid wins.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <utility>

#if __has_include(<boost/numeric/odeint.hpp>)
#include <boost/numeric/odeint.hpp>
#include <boost/numeric/odeint/external/eigen/eigen.hpp>
#define PHYSLAB_HAVE_ODEINT 1
#endif

#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/integrators.hpp"
#include "physlab/neighbours.hpp"
#include "physlab/particles.hpp"
#include "physlab/plot.hpp"

#include "../allocation_counter.hpp"

using namespace physlab;

namespace {

// Seconds per call of `work` over one batch of calls lasting at least `min_seconds`.
template <class Work>
double secondsPerBatch(Work& work, double min_seconds) {
  Stopwatch clock;
  long calls = 0;
  do {
    work();
    ++calls;
  } while (clock.seconds() < min_seconds);
  return clock.seconds() / calls;
}

// Seconds per call of `work`, the best of several batches of at least `min_seconds` after one
// warm-up batch: the minimum filters out other processes on a shared machine.
template <class Work>
double secondsPerCall(Work&& work, double min_seconds) {
  for (Stopwatch warm_up; warm_up.seconds() < 0.2 * min_seconds;) work();
  double best = 1e300;
  for (int batch = 0; batch < 3; ++batch) best = std::min(best, secondsPerBatch(work, min_seconds));
  return best;
}

// Seconds per call of `a` and of `b`, each the best of five batches of at least `min_seconds`,
// the batches of the two alternating (after a warm-up of each) so that both sides see the same
// periods of a shared machine's load.
template <class A, class B>
std::pair<double, double> secondsPerCallSideBySide(A&& a, B&& b, double min_seconds) {
  secondsPerBatch(a, min_seconds);
  secondsPerBatch(b, min_seconds);
  std::pair<double, double> best{1e300, 1e300};
  for (int round = 0; round < 5; ++round) {
    best.first = std::min(best.first, secondsPerBatch(a, min_seconds));
    best.second = std::min(best.second, secondsPerBatch(b, min_seconds));
  }
  return best;
}

double triadSeconds(Index length, double min_seconds) {
  VecX a = VecX::Zero(length), b = VecX::Random(length), c = VecX::Random(length);
  const double s = 1e-3;
  return secondsPerCall([&] { a.noalias() = b + s * c; b.swap(a); }, min_seconds);
}

std::shared_ptr<ParticleSystem> gravityAndDrag(Index n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mass(0.5, 2.0);
  VecX m(n);
  for (Index i = 0; i < n; ++i) m[i] = mass(rng);
  auto sys = std::make_shared<ParticleSystem>(m);
  sys->addForce(std::make_shared<UniformGravity>(Vec3(0, 0, -9.81)));
  sys->addForce(std::make_shared<ViscousDrag>(0.1));
  return sys;
}

// The anchor: symplectic Euler on gravity + drag fused into one pass over the particles, the
// forces written out (a = g - (d / m) v, then v += h a, x += h v): the same arithmetic as the
// framework's step with nothing but it, for the "within 1.5x of a fused step".
void fusedSymplecticEuler(VecX& X, const VecX& inverse_masses, const Vec3& g, double drag, double h) {
  const Index n = inverse_masses.size();
  double* x = X.data();
  double* v = X.data() + 3 * n;
  for (Index i = 0; i < n; ++i) {
    const double k = drag * inverse_masses[i];
    for (int c = 0; c < 3; ++c) {
      v[3 * i + c] += h * (g[c] - k * v[3 * i + c]);
      x[3 * i + c] += h * v[3 * i + c];
    }
  }
}

// The floor for any step that keeps force and integrator apart: the forces leave their sum in an
// acceleration buffer (one pass, a = g - (d / m) v, here written out as a single pass, which
// no real set of separate forces beats), then the integrator reads it back in one pass of its own
// (v += h a, x += h v). It moves 3 more doubles out and 3 more in per particle than the fused
// loop, the price of the buffer between the two concepts.
void twoPassSymplecticEuler(VecX& X, VecX& a, const VecX& inverse_masses, const Vec3& g, double drag,
                            double h) {
  const Index n = inverse_masses.size();
  double* x = X.data();
  double* v = X.data() + 3 * n;
  for (Index i = 0; i < n; ++i) {
    const double k = drag * inverse_masses[i];
    for (int c = 0; c < 3; ++c) a[3 * i + c] = g[c] - k * v[3 * i + c];
  }
  for (Index j = 0; j < 3 * n; ++j) {
    v[j] += h * a[j];
    x[j] += h * v[j];
  }
}

// N points uniform in a cube whose side keeps the density at 10 / (4/3 pi r^3), r = 1: about 10
// neighbours each, whatever N.
Mat3X uniformCloud(Index n) {
  std::mt19937_64 rng(3);
  const double side = std::cbrt(static_cast<double>(n) * (4.0 / 3.0) * M_PI / 10.0);
  std::uniform_real_distribution<double> coordinate(0.0, side);
  Mat3X x(3, n);
  for (Index i = 0; i < n; ++i) x.col(i) << coordinate(rng), coordinate(rng), coordinate(rng);
  return x;
}

void neighbourBenchmark(const DemoOptions& options, double min_seconds) {
  const std::vector<Index> sizes = options.quick ? std::vector<Index>{100, 1000, 10000, 100000}
                                                 : std::vector<Index>{100, 300, 1000, 3000, 10000, 30000,
                                                                      100000, 300000, 1000000};
  const Index brute_limit = options.quick ? 10000 : 30000;
  const double r = 1.0;
  Table table({"N", "method", "ms / search", "distance checks", "pairs", "allocations per search"});
  Series grid_series{"uniform grid", {}, {}, "linespoints lw 2 lc rgb '#2266aa'"};
  Series brute_series{"brute force", {}, {}, "linespoints lw 2 lc rgb '#cc6633'"};
  std::vector<NeighbourPair> pairs;
  NeighbourGrid grid;
  NeighbourStats stats;
  for (const Index n : sizes) {
    const Mat3X cloud = uniformCloud(n);
    const ConstPoints x(cloud.data(), 3, n);
    const auto grid_search = [&] { neighbourPairs(x, r, pairs, grid, stats); };
    const double grid_time = secondsPerCall(grid_search, min_seconds);
    const std::string allocations =
        bench::allocationsCounted() ? fmt(static_cast<double>(bench::allocationsOf(grid_search))) : "-";
    table.add({std::to_string(n), "uniform grid", fmt(1e3 * grid_time), std::to_string(stats.distance_checks),
               std::to_string(pairs.size()), allocations});
    grid_series.x.push_back(static_cast<double>(n));
    grid_series.y.push_back(grid_time);
    if (n > brute_limit) continue;
    const std::size_t grid_pairs = pairs.size();
    const double brute_time = secondsPerCall([&] { bruteForcePairs(x, r, pairs, stats); }, min_seconds);
    if (pairs.size() != grid_pairs) throw NumericalFailure("grid and brute force found different pair counts");
    table.add({std::to_string(n), "brute force", fmt(1e3 * brute_time), std::to_string(stats.distance_checks),
               std::to_string(pairs.size()), "-"});
    brute_series.x.push_back(static_cast<double>(n));
    brute_series.y.push_back(brute_time);
  }
  // The crossover: where log(brute / grid) changes sign between two measured sizes, interpolated in log N.
  double crossover = NAN;
  for (std::size_t k = 1; k < brute_series.x.size() && std::isnan(crossover); ++k) {
    const double before = std::log(brute_series.y[k - 1] / grid_series.y[k - 1]);
    const double after = std::log(brute_series.y[k] / grid_series.y[k]);
    if (before <= 0.0 && after > 0.0) {
      const double t = -before / (after - before);
      crossover = std::exp((1.0 - t) * std::log(brute_series.x[k - 1]) + t * std::log(brute_series.x[k]));
    }
  }
  if (std::isnan(crossover) && !brute_series.y.empty() && brute_series.y[0] > grid_series.y[0]) {
    crossover = brute_series.x[0];  // the grid already wins at the smallest size
  }
  // Slope guides through the last brute-force point (N^2) and the last grid point (N).
  const double nb = brute_series.x.back(), tb = brute_series.y.back();
  const double ng = grid_series.x.back(), tg = grid_series.y.back();
  Series quadratic{"O(N^2)", {}, {}, "lines dt 2 lw 1 lc rgb '#888888'"};
  Series linear{"O(N)", {}, {}, "lines dt 3 lw 1 lc rgb '#444444'"};
  for (const double n : {grid_series.x.front(), ng}) {
    quadratic.x.push_back(n);
    quadratic.y.push_back(tb * (n / nb) * (n / nb));
    linear.x.push_back(n);
    linear.y.push_back(tg * n / ng);
  }
  Chart chart("Fixed-radius neighbour search, about 10 neighbours per particle", "N (particles)",
              "seconds per search (all pairs within r)");
  chart.logX().logY().add(grid_series).add(brute_series).add(quadratic).add(linear);
  if (!std::isnan(crossover)) chart.mark({crossover, "crossover N = " + fmt(crossover, 2)});
  std::cout << "\nLab 1 benchmark: fixed-radius neighbour search, best of 3 batches after a warm-up\n";
  table.print(std::cout);
  std::cout << "crossover (grid faster than brute force from): N = " << fmt(crossover, 2) << "\n";
  std::cout << "wrote " << table.saveMarkdown(options.out + "/lab01_bench_neighbours.md") << "\n";
  for (const std::string& path : chart.save(options.out + "/lab01_bench_neighbours")) std::cout << "wrote " << path << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv, "Lab 1 benchmark: integrator cost per particle-step against a bandwidth bound.");
    const double min_seconds = options.quick ? 0.05 : 0.3;
    const std::vector<Index> sizes = options.quick ? std::vector<Index>{1000, 100000}
                                                   : std::vector<Index>{1000, 10000, 100000, 1000000};
    Table table({"N", "integrator", "ns / particle-step", "triad ns / particle", "cost in triads",
                 "allocations per step"});
    // Heap allocations of `steps` more calls of `step`, per call ("-" where they are not counted).
    const auto allocations = [](auto&& step) {
      if (!bench::allocationsCounted()) return std::string("-");
      constexpr int steps = 3;
      return fmt(static_cast<double>(bench::allocationsOf([&] {
                   for (int k = 0; k < steps; ++k) step();
                 })) / steps);
    };
    for (Index n : sizes) {
      const std::shared_ptr<ParticleSystem> sys = gravityAndDrag(n);
      const VecX X0 = VecX::Random(sys->size());
      const double triad = triadSeconds(sys->size(), min_seconds);
      for (Method method : kAllMethods) {
        // Implicit Euler here is dense Newton, O(N^3): Lab 2 builds the sparse version.
        if (method == Method::ImplicitEuler) continue;
        VecX X = X0;
        Integrator integrator(method);
        const auto one_step = [&] { integrator.step(*sys, X, 1e-4); };
        const double step = secondsPerCall(one_step, min_seconds);
        table.add({std::to_string(n), methodName(method), fmt(1e9 * step / n),
                   fmt(1e9 * triad / n), fmt(step / triad), allocations(one_step)});
      }
      {
        // The fused anchor against the framework's symplectic Euler, from the same state
        const VecX inverse_masses = sys->inverseMasses();
        VecX A = X0, B = X0;
        Integrator ours(Method::SymplecticEuler);
        const auto [fused, mine] = secondsPerCallSideBySide(
            [&] { fusedSymplecticEuler(A, inverse_masses, Vec3(0, 0, -9.81), 0.1, 1e-4); },
            [&] { ours.step(*sys, B, 1e-4); }, min_seconds);
        table.add({std::to_string(n), "anchor: symplectic Euler fused into one pass", fmt(1e9 * fused / n),
                   fmt(1e9 * triad / n), fmt(fused / triad) + " (ours/anchor " + fmt(mine / fused) + ")", "-"});
      }
      {
        // The two-pass floor against the fused anchor: what keeping the concepts apart must cost
        const VecX inverse_masses = sys->inverseMasses();
        VecX A = X0, B = X0, a(sys->size() / 2);
        const auto [fused, apart] = secondsPerCallSideBySide(
            [&] { fusedSymplecticEuler(A, inverse_masses, Vec3(0, 0, -9.81), 0.1, 1e-4); },
            [&] { twoPassSymplecticEuler(B, a, inverse_masses, Vec3(0, 0, -9.81), 0.1, 1e-4); }, min_seconds);
        table.add({std::to_string(n), "floor apart: forces pass, then integrator pass", fmt(1e9 * apart / n),
                   fmt(1e9 * triad / n), fmt(apart / triad) + " (floor/anchor " + fmt(apart / fused) + ")", "-"});
      }
#ifdef PHYSLAB_HAVE_ODEINT
      {
        // Boost.Odeint's RK4 calling the same System::derivative: the ratio isolates the
        // integrator's own overhead (its stage arithmetic and temporaries).
        namespace odeint = boost::numeric::odeint;
        odeint::runge_kutta4<VecX, double, VecX, double, odeint::vector_space_algebra> stepper;
        VecX X = X0, Y = X0;
        auto rhs = [&](const VecX& x, VecX& dxdt, double) { sys->derivative(x, dxdt); };
        Integrator ours(Method::RK4);
        const auto [step, mine] = secondsPerCallSideBySide([&] { stepper.do_step(rhs, X, 0.0, 1e-4); },
                                                           [&] { ours.step(*sys, Y, 1e-4); }, min_seconds);
        table.add({std::to_string(n), "Boost.Odeint RK4", fmt(1e9 * step / n), fmt(1e9 * triad / n),
                   fmt(step / triad) + " (ours/odeint " + fmt(mine / step) + ")",
                   allocations([&] { stepper.do_step(rhs, X, 0.0, 1e-4); })});
      }
#endif
    }
    std::cout << "Lab 1 benchmark: gravity + drag, one step per call, best of 3 batches (anchor and Odeint: best of 5, alternating with ours)\n";
    table.print(std::cout);
    std::cout << "\nwrote " << table.saveMarkdown(options.out + "/lab01_bench.md") << "\n";
    neighbourBenchmark(options, min_seconds);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_01_particles: " << e.what() << "\n";
    return 1;
  }
}
