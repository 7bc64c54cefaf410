// Lab 5 benchmark. First, islands and sleeping (section 12, issue 40): a settled pile of 1024
// cubes (108 in a quick run) with sleeping on, its step against the same pile awake, against its
// own first 0.5 s, and against Bullet with its deactivation on (settledPile()); and a ball dropped
// on one of four sleeping towers against the same run without sleeping (ballDrop()). Then the box
// rain (boxRain(N, seed): ground plane, four fixed walls of a 2 x 2 m container, N boxes and
// spheres of 1 kg on a grid above it) at N = 100, 500, 2000, stepped at h = 1/60 s by our World
// (sequential and simultaneous impulses) and by Bullet's btDiscreteDynamicsWorld in the same run,
// then Newton's cradle in both. Last, Timewarp (section 9) against the synchronous World and the
// synchronous sub-stepping on the sparse scene of a fast ball through a row among N drifting
// spheres.
//
// What each side does per step, on the same bodies (shapes, masses, inertias, restitution,
// friction, initial positions, orientations and velocities, gravity):
// - PhysLab: World::step with the default Settings (printed): gravity, sort-and-sweep broad phase
//   plus every body against the ground plane, Lab 4's manifolds, classification, at most
//   Settings::iterations solver sweeps (the solvers stop early when no velocity changes by more
//   than Settings::tolerance), symplectic Euler, the position correction (Settings::position_correction
//   of the overlap beyond Settings::slop per step), diagnostics.
// - Bullet: stepSimulation(h, 0), i.e. exactly one internal step of h: gravity, btDbvtBroadphase,
//   its collision algorithms (btBoxBoxDetector for box-box, exact sphere-sphere and convex-plane,
//   GJK/EPA with Bullet's default 4 cm margin for sphere-box), btSequentialImpulseConstraintSolver
//   with m_numIterations = Settings::iterations (no early exit: m_leastSquaresResidualThreshold
//   stays 0), warm starting, split impulse and Baumgarte position correction (its defaults), and
//   the integration. Made to match our model where Bullet has a knob: two friction directions per
//   point (SOLVER_USE_2_FRICTION_DIRECTIONS; ours is a friction cone in the tangent plane), the
//   pair's restitution is the min of the two bodies' and its friction the geometric mean (our
//   World's rules; Bullet's default is the products), the restitution threshold is ours, and
//   sleeping is off (DISABLE_DEACTIVATION) so that settled bodies cost the same as in our World.
//
// Timing: every window builds a fresh world (not timed) and times the same number of steps from
// the same initial state; windows of the three engines alternate, one untimed run of each comes
// first (warm-up, and the run whose penetration and contacts are reported), and the fastest
// window counts. The largest penetration is the deepest contact found over the run, for Bullet
// the most negative getDistance() of its manifolds after each step: both are measured at the same
// point of the step (after collision detection, before the positions move). The deepest contact
// of the last step shows what each engine's position correction (Bullet's split impulse and
// Baumgarte term; ours moves and turns the bodies, Gauss-Seidel over the points) left behind,
// in the measured run and as the median of kShakenRuns runs shifted by 1 nm. Writes
// <out>/lab05_bench.md and the chart <out>/lab05_bench.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/plot.hpp"
#include "physlab/timewarp.hpp"
#include "physlab/world.hpp"

#include "../support/goals.hpp"
#ifdef PHYSLAB_HAVE_BULLET
#include "../support/bullet_world.hpp"
#endif

using namespace physlab;

namespace {

constexpr double kStep = 1.0 / 60.0;
constexpr std::uint64_t kSeed = 5;
constexpr int kFirstMovingBody = 5;  // boxRain: the ground plane and four walls come first
// A pile is chaotic: shifting the bodies' start by a nanometre moves the deepest contact of the
// last step of the rain of 100 from 0.23 to 1.5 mm in our World (0.22 to 0.93 mm in Bullet), so
// that figure is also given as the median of this many runs, the first unshifted (shakenScene())
constexpr int kShakenRuns = 9;

// The median of the last step's deepest contact over kShakenRuns runs of `last` on the scene
// shifted by 1 nm (run 0 unshifted; `first` is its figure, already measured).
template <typename LastPenetration>
double shakenMedian(const Scene& scene, double first, const LastPenetration& last) {
  std::vector<double> values = {first};
  for (int run = 1; run < kShakenRuns; ++run) values.push_back(last(shakenScene(scene, static_cast<std::uint64_t>(run))));
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// What one engine did on one scene: the fastest window and what the untimed run measured.
struct RunResult {
  double seconds_per_step = INFINITY;  // fastest window
  double max_penetration = 0.0;        // deepest contact over the run [m]
  double last_penetration = 0.0;       // deepest contact of the last step: what correction left [m]
  double last_penetration_median = 0.0;  // its median over kShakenRuns runs shifted by 1 nm [m]
  double contacts_per_step = 0.0;      // mean contact points per step
  double sweeps_per_step = NAN;        // mean solver sweeps per step (ours)
  int outside_walls = 0;               // moving bodies whose centre ended beyond a wall's inner face
  int below_ground = 0;                // moving bodies whose centre ended below the ground
  bool finite = true;                  // every position finite at the end
  PhaseTimes phases;                   // per step, fastest window (ours)
};

// Where the moving bodies ended up: out over the walls (an overflowing pile may spill, so this
// is reported, not judged) or with their centre under the floor (they fell through it).
template <typename PositionOf>
void countEscapes(int bodies, const PositionOf& position, RunResult& r) {
  r.outside_walls = r.below_ground = 0;
  for (int i = kFirstMovingBody; i < bodies; ++i) {
    const Vec3 x = position(i);
    r.finite = r.finite && x.allFinite();
    if (std::abs(x.x()) > 1.0 || std::abs(x.y()) > 1.0) ++r.outside_walls;
    if (x.z() < 0.0) ++r.below_ground;
  }
}

// ----- PhysLab ---------------------------------------------------------------------------------

// The untimed run: penetration, contacts and sweeps of every step, and where the bodies end.
void measureOurs(const Scene& scene, const Settings& settings, int steps, RunResult& r) {
  World world(scene, settings);
  double contacts = 0.0, sweeps = 0.0;
  for (int n = 0; n < steps; ++n) {
    world.step(kStep);
    const Diagnostics& d = world.diagnostics();
    r.max_penetration = std::max(r.max_penetration, d.max_penetration);
    r.last_penetration = d.max_penetration;
    contacts += d.contacts;
    sweeps += d.iterations;
  }
  r.contacts_per_step = contacts / steps;
  r.sweeps_per_step = sweeps / steps;
  countEscapes(static_cast<int>(scene.bodies.size()), [&](int i) { return world.states()[i].x; }, r);
}

// Field by field, by name: PhaseTimes may gain phases (Lab 6's resting solver), which Lab 5's
// World leaves at zero.
PhaseTimes scaled(const PhaseTimes& t, double factor) {
  PhaseTimes s;
  s.forces = t.forces * factor;
  s.broad_phase = t.broad_phase * factor;
  s.narrow_phase = t.narrow_phase * factor;
  s.classify = t.classify * factor;
  s.respond = t.respond * factor;
  s.integrate = t.integrate * factor;
  s.correct = t.correct * factor;
  s.diagnostics = t.diagnostics * factor;
  return s;
}

// One timed window; keeps the phase times of the fastest window.
void timeOurs(const Scene& scene, const Settings& settings, int steps, RunResult& r) {
  World world(scene, settings);
  Stopwatch clock;
  for (int n = 0; n < steps; ++n) world.step(kStep);
  const double per_step = clock.seconds() / steps;
  if (per_step < r.seconds_per_step) {
    r.seconds_per_step = per_step;
    r.phases = scaled(world.times(), 1.0 / steps);
  }
}

// ----- Bullet ----------------------------------------------------------------------------------

#ifdef PHYSLAB_HAVE_BULLET
using bench::BulletWorld;

void measureBullet(const Scene& scene, const Settings& settings, int steps, RunResult& r) {
  BulletWorld world(scene, settings);
  double contacts = 0.0;
  for (int n = 0; n < steps; ++n) {
    world.step(kStep);
    const auto [deepest, points] = world.contacts();
    r.max_penetration = std::max(r.max_penetration, deepest);
    r.last_penetration = deepest;
    contacts += points;
  }
  r.contacts_per_step = contacts / steps;
  countEscapes(world.size(), [&](int i) { return world.position(i); }, r);
}

void timeBullet(const Scene& scene, const Settings& settings, int steps, RunResult& r) {
  BulletWorld world(scene, settings);
  Stopwatch clock;
  for (int n = 0; n < steps; ++n) world.step(kStep);
  r.seconds_per_step = std::min(r.seconds_per_step, clock.seconds() / steps);
}
#endif

// ----- Newton's cradle -------------------------------------------------------------------------

struct CradleResult {
  std::vector<double> v;  // final velocity along x of each ball [m/s]
  double energy_ratio = NAN;    // kinetic energy at the end / at the start
  double momentum_ratio = NAN;  // x momentum at the end / at the start
};

CradleResult summarise(std::vector<double> v, double v0) {
  CradleResult c;
  double energy = 0.0, momentum = 0.0;
  for (double vi : v) {
    energy += 0.5 * vi * vi;  // every ball is 1 kg
    momentum += vi;
  }
  c.energy_ratio = energy / (0.5 * v0 * v0);
  c.momentum_ratio = momentum / v0;
  c.v = std::move(v);
  return c;
}

CradleResult cradleOurs(int balls, double v0, int steps, ResponseMethod method) {
  Settings settings;
  settings.method = method;
  settings.gravity = Vec3::Zero();
  World world(newtonsCradle(balls, v0), settings);
  for (int n = 0; n < steps; ++n) world.step(kStep);
  std::vector<double> v;
  for (int i = 0; i < balls; ++i) v.push_back(world.velocity(i).x());
  return summarise(v, v0);
}

#ifdef PHYSLAB_HAVE_BULLET
CradleResult cradleBullet(int balls, double v0, int steps) {
  Settings settings;
  settings.gravity = Vec3::Zero();
  BulletWorld world(newtonsCradle(balls, v0), settings);
  for (int n = 0; n < steps; ++n) world.step(kStep);
  std::vector<double> v;
  for (int i = 0; i < balls; ++i) v.push_back(world.velocity(i).x());
  return summarise(v, v0);
}
#endif

std::string velocities(const std::vector<double>& v) {
  std::string s;
  for (double vi : v) s += (s.empty() ? "" : ", ") + fmt(std::abs(vi) < 5e-13 ? 0.0 : vi);
  return s;
}

// Continuous collision's cost (section 10; issue 37: at most 3 % more time where no body is
// fast): each scene stepped with Settings::continuous on and off, fresh each window, windows
// alternating, the fastest window counting. A stack of 10 cubes at rest for 3 s (its bodies are
// slow: one comparison each a step; a step is 0.1 ms, so 20 windows of it even in a quick run) and
// the box rain (falling boxes, some fast: swept, and stopped when they would hit; `windows` of
// the rain's steps). Returns the table and the stack's ratio on / off.
std::pair<Table, double> continuousBench(int windows, bool quick) {
  Scene stack;
  stack.bodies.push_back(BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.0, 0.5));
  stack.states.push_back(BodyState{});
  for (int i = 0; i < 10; ++i) {
    stack.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(0.1), 0.0, 0.5));
    BodyState s;
    s.x = Vec3(0.0, 0.0, (2 * i + 1) * (0.1 - 1e-6));
    stack.states.push_back(s);
  }
  Table table({"scene", "fast bodies", "ms per step, continuous on", "off", "on / off"});
  double stack_ratio = NAN;
  for (const auto& [name, scene] : {std::pair<std::string, Scene>{"stack of 10 cubes", stack},
                                    {"box rain of 500", boxRain(500, kSeed)}}) {
    Settings on, off;
    off.continuous = false;
    RunResult with, without;
    const bool rain = name != "stack of 10 cubes";
    const int steps = rain && quick ? 20 : 180;
    for (int w = 0; w < (rain ? windows : 20); ++w) {
      timeOurs(scene, on, steps, with);
      timeOurs(scene, off, steps, without);
    }
    const double ratio = with.seconds_per_step / without.seconds_per_step;
    if (name == "stack of 10 cubes") stack_ratio = ratio;
    table.add({name, name == "stack of 10 cubes" ? "none" : "some, while falling", fmt(1e3 * with.seconds_per_step),
               fmt(1e3 * without.seconds_per_step), fmt(ratio)});
  }
  return {table, stack_ratio};
}

// Timewarp against synchronous stepping on the sparse scene: fastBallThroughRow(5, 0.3 m, 4 m/s,
// N - 6 drifting spheres), run to 0.6 s (the last impact is at 0.5 s). Three ways, each timed on
// a fresh copy, windows alternating, the fastest of `windows` counting: Timewarp (max step 0.5 s,
// max travel 0.05 m); synchronous sub-stepping at h = 0.5 s (every body to every impact, every
// pair re-checked); the Lab 5 World at h = 1 ms (sequential impulses, no gravity: a fixed step
// must be as short as the impact-time error it may make). The errors are against the exact
// impact times (0.8 + 0.3 k) / 4 s; the World's impact k is when sphere k + 1 first moves.
Table timewarpBench(const std::vector<int>& sizes, int windows) {
  constexpr int kRow = 5;
  const double duration = 0.6, h_world = 1e-3;
  const auto exact = [](int k) { return (0.8 + 0.3 * k) / 4.0; };
  Table table({"N", "method", "ms per run", "time / Timewarp's", "largest impact-time error [s]", "pair checks",
               "body states advanced", "rollbacks (bodies)"});
  for (const int n : sizes) {
    std::vector<TimewarpSphere> spheres;
    std::vector<SphereState> states;
    fastBallThroughRow(kRow, 0.3, 4.0, n - 1 - kRow, 5u, spheres, states);
    Scene scene;
    for (std::size_t i = 0; i < spheres.size(); ++i) {
      scene.bodies.push_back(BodyDescription::sphere(spheres[i].mass, spheres[i].radius, spheres[i].epsilon, 0.0));
      scene.states.push_back(BodyState::moving(scene.bodies.back(), states[i].x, Quat::Identity(), states[i].v, Vec3::Zero()));
    }
    Settings world_settings;
    world_settings.gravity = Vec3::Zero();
    TimewarpSettings warp_settings;
    warp_settings.max_step = 0.5;
    warp_settings.max_travel = 0.05;
    const auto eventError = [&](const std::vector<TimewarpEvent>& events) {
      double error = 0.0;
      for (int k = 0; k < kRow; ++k) {
        double t = NAN;
        for (const TimewarpEvent& e : events) {
          if (e.a == k && e.b == k + 1) t = e.t;
        }
        error = std::max(error, std::abs(t - exact(k)));
      }
      return error;
    };
    double best[3] = {INFINITY, INFINITY, INFINITY}, error[3] = {0, 0, 0};
    long checks[3] = {0, 0, 0}, advanced[3] = {0, 0, 0};
    std::string rollbacks;
    for (int w = 0; w <= windows; ++w) {  // window 0 warms up
      Stopwatch clock;
      TimewarpWorld warp(spheres, states, warp_settings);
      warp.run(duration);
      const double t_warp = clock.seconds();
      clock.restart();
      std::vector<TimewarpEvent> events;
      SynchronousStats sync;
      runSynchronousToi(spheres, states, Vec3::Zero(), 0.5, duration, events, sync);
      const double t_sync = clock.seconds();
      clock.restart();
      World world(scene, world_settings);
      std::vector<double> seen(kRow, NAN);
      for (long step = 0; step < std::lround(duration / h_world); ++step) {
        world.step(h_world);
        for (int k = 0; k < kRow; ++k) {
          if (std::isnan(seen[k]) && world.velocity(k + 1).x() > 1e-9) seen[k] = world.time();
        }
      }
      const double t_world = clock.seconds();
      if (w == 0) {
        error[0] = eventError(warp.events());
        error[1] = eventError(events);
        for (int k = 0; k < kRow; ++k) error[2] = std::max(error[2], std::abs(seen[k] - exact(k)));
        checks[0] = warp.stats().pair_checks;
        advanced[0] = warp.stats().steps;
        checks[1] = sync.pair_checks;
        advanced[1] = sync.body_updates;
        advanced[2] = static_cast<long>(spheres.size()) * std::lround(duration / h_world);
        rollbacks = std::to_string(warp.stats().rollbacks) + " (" + std::to_string(warp.stats().bodies_rolled_back) + ")";
        continue;
      }
      best[0] = std::min(best[0], t_warp);
      best[1] = std::min(best[1], t_sync);
      best[2] = std::min(best[2], t_world);
    }
    const std::string names[3] = {"Timewarp (largest step 0.5 s)", "synchronous, TOI sub-steps (h = 0.5 s)",
                                  "Lab 5 World, fixed step (h = 1 ms)"};
    for (int m = 0; m < 3; ++m) {
      table.add({std::to_string(n), names[m], fmt(1e3 * best[m]), fmt(best[m] / best[0]), fmt(error[m], 2),
                 m == 2 ? "incremental tree" : std::to_string(checks[m]), std::to_string(advanced[m]), m == 0 ? rollbacks : "-"});
    }
    std::cout << "Timewarp, N = " << n << ": best of " << windows << " windows done\n";
  }
  return table;
}

// ----- Islands and sleeping (section 12, issue 40) ---------------------------------------------

constexpr double kCube = 0.1;   // half edge of the piles' cubes [m]
constexpr double kGap = 0.02;   // between neighbouring columns, and each cube's drop [m]

// The ground plane and a cols x cols grid of columns of `layers` cubes (1 kg, 0.2 m edge, mu 0.5,
// epsilon `epsilon`), the columns 2 cm apart, each cube 2 cm above the one below, dropped from rest
// at x0 along x: they land and come to rest within a second.
void addColumns(Scene& scene, int cols, int layers, double x0, double epsilon) {
  for (int i = 0; i < cols; ++i) {
    for (int j = 0; j < cols; ++j) {
      for (int k = 0; k < layers; ++k) {
        scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(kCube), epsilon, 0.5));
        BodyState s;
        s.x = Vec3(x0 + (2 * kCube + kGap) * i, (2 * kCube + kGap) * j, kCube + kGap + (2 * kCube + kGap) * k);
        scene.states.push_back(s);
      }
    }
  }
}

Scene groundOnly() {
  Scene scene;
  scene.bodies.push_back(BodyDescription::plane(Vec3::UnitZ(), 0.0, 0.0, 0.5));
  scene.states.push_back(BodyState{});
  return scene;
}

int awakeCount(const World& world) {
  int awake = 0;
  for (int i = 0; i < static_cast<int>(world.bodies().size()); ++i) awake += !world.bodies()[i].fixed && !world.asleep(i);
  return awake;
}

struct SettledPile {
  int boxes = 0;
  double settle_seconds = NAN;              // simulated time until every box slept (ours)
  double asleep_ms = INFINITY, awake_ms = INFINITY, bullet_ms = NAN;  // fastest window, per step
  double moving_ms = INFINITY;              // the first 0.5 s from the drop (falling and landing), sleeping on
  PhaseTimes asleep_phases;                 // ours asleep, per step over every window
  int bullet_asleep = 0;                    // boxes Bullet had put to sleep when timed
  double bullet_settle_seconds = NAN;       // simulated time until Bullet slept them all (from our settled pile)
  Table table{{"scene", "engine", "ms per step", "boxes asleep", "time / ours awake", "time / Bullet's"}};
};

// The settled pile: cols x cols columns of `layers` cubes dropped with sleeping on until every box
// sleeps; then that pile's step, timed in three worlds stepped side by side, windows alternating,
// the fastest counting: ours sleeping (the same World, on), ours awake (a World with sleeping off
// built from the settled states) and Bullet with its deactivation on, built from the same states
// and stepped until it has put every box to sleep (or for 5 s) before its windows.
SettledPile settledPile(int cols, int layers, int windows, int steps) {
  SettledPile p;
  Scene scene = groundOnly();
  addColumns(scene, cols, layers, 0.0, 0.0);
  p.boxes = cols * cols * layers;
  Settings sleeping;
  sleeping.sleeping = true;
  World asleep(scene, sleeping);
  const int most = static_cast<int>(std::lround(10.0 / kStep));
  for (int n = 0; n < most && asleep.diagnostics().asleep < p.boxes; ++n) asleep.step(kStep);
  if (asleep.diagnostics().asleep == p.boxes) p.settle_seconds = asleep.time();
  Scene settled = scene;
  settled.states = asleep.states();
  World awake(settled, Settings{});
  for (int n = 0; n < steps; ++n) awake.step(kStep);  // warm-up
#ifdef PHYSLAB_HAVE_BULLET
  bench::BulletWorld bullet(settled, Settings{}, true);
  p.bullet_ms = INFINITY;
  for (int n = 0; n < static_cast<int>(std::lround(5.0 / kStep)) && bullet.asleep() < p.boxes; ++n) {
    bullet.step(kStep);
    if (bullet.asleep() == p.boxes) p.bullet_settle_seconds = (n + 1) * kStep;
  }
#endif
  const auto window = [steps](const auto& step) {
    Stopwatch clock;
    for (int n = 0; n < steps; ++n) step();
    return 1e3 * clock.seconds() / steps;
  };
  asleep.resetTimers();
  const int moving_steps = std::min(steps, static_cast<int>(std::lround(0.5 / kStep)));
  for (int w = 0; w < windows; ++w) {
    {
      World moving(scene, sleeping);
      Stopwatch clock;
      for (int n = 0; n < moving_steps; ++n) moving.step(kStep);
      p.moving_ms = std::min(p.moving_ms, 1e3 * clock.seconds() / moving_steps);
    }
    p.asleep_ms = std::min(p.asleep_ms, window([&] { asleep.step(kStep); }));
    p.awake_ms = std::min(p.awake_ms, window([&] { awake.step(kStep); }));
#ifdef PHYSLAB_HAVE_BULLET
    p.bullet_ms = std::min(p.bullet_ms, window([&] { bullet.step(kStep); }));
#endif
  }
  p.asleep_phases = scaled(asleep.times(), 1.0 / (windows * steps));
#ifdef PHYSLAB_HAVE_BULLET
  p.bullet_asleep = bullet.asleep();
#endif
  const std::string name = "settled pile of " + std::to_string(p.boxes) + " boxes";
  const auto ratio = [](double a, double b) { return std::isfinite(a) && std::isfinite(b) ? fmt(a / b) : std::string("-"); };
  p.table.add({name, "PhysLab sequential, sleeping on", fmt(p.asleep_ms), std::to_string(asleep.diagnostics().asleep),
               ratio(p.asleep_ms, p.awake_ms), ratio(p.asleep_ms, p.bullet_ms)});
  p.table.add({name, "PhysLab sequential, sleeping off", fmt(p.awake_ms), "0", "1", ratio(p.awake_ms, p.bullet_ms)});
  p.table.add({name + ", while dropping (first " + fmt(moving_steps * kStep) + " s)", "PhysLab sequential, sleeping on",
               fmt(p.moving_ms), "0", ratio(p.moving_ms, p.awake_ms), "-"});
#ifdef PHYSLAB_HAVE_BULLET
  p.table.add({name, bench::bulletName() + ", deactivation on (Bullet's defaults)", fmt(p.bullet_ms),
               std::to_string(p.bullet_asleep), ratio(p.bullet_ms, p.awake_ms), "1"});
#else
  p.table.add({name, "Bullet", "not installed", "-", "-", "-"});
#endif
  return p;
}

// A ball dropped on one sleeping pile among several: `piles` towers of 5 cubes (epsilon 0.5) 1 m
// apart, and a ball (1 kg, radius 0.1 m, epsilon 0.5) resting on the ground 3 m away, all asleep
// after 3 s; the ball is then put 0.5 m above the top of tower `hit` and falls on it for 2 s. The
// same run with sleeping off (same steps, same setState) is the reference.
struct BallDrop {
  int pile_bodies = 5;
  int most_awake = 0;       // moving bodies awake at once after the drop, sleeping on
  int asleep_before = 0;    // bodies asleep when the ball was dropped
  double rebound[2] = {NAN, NAN};  // rebound / drop height, sleeping on and off
  double apart = 0.0;       // largest distance between a body's final positions in the two runs [m]
};

BallDrop ballDrop(int piles) {
  constexpr int kTower = 5, kHit = 1;
  constexpr double kEpsilon = 0.5, kDrop = 0.5;
  Scene scene = groundOnly();
  for (int p = 0; p < piles; ++p) addColumns(scene, 1, kTower, 1.0 * p, kEpsilon);
  scene.bodies.push_back(BodyDescription::sphere(1.0, 0.1, kEpsilon, 0.5));
  BodyState rest;
  rest.x = Vec3(-3.0, 0.0, 0.1);
  scene.states.push_back(rest);
  const int ball = static_cast<int>(scene.bodies.size()) - 1;
  const int top = 1 + kHit * kTower + kTower - 1;
  BallDrop d;
  std::vector<BodyState> end[2];
  for (int run = 0; run < 2; ++run) {
    Settings settings;
    settings.sleeping = run == 0;
    World world(scene, settings);
    for (int n = 0; n < 180; ++n) world.step(kStep);
    if (run == 0) d.asleep_before = world.diagnostics().asleep;
    const double contact = world.states()[top].x.z() + kCube + 0.1;  // the ball's centre touching the top
    world.setState(ball, BodyState::moving(world.bodies()[ball], Vec3(1.0 * kHit, 0.0, contact + kDrop),
                                           Quat::Identity(), Vec3::Zero(), Vec3::Zero()));
    double apex = -INFINITY;
    bool rising = false;
    for (int n = 0; n < 120; ++n) {
      world.step(kStep);
      if (run == 0) d.most_awake = std::max(d.most_awake, awakeCount(world));
      rising = rising || world.velocity(ball).z() > 0.0;
      if (rising) apex = std::max(apex, world.states()[ball].x.z());
    }
    d.rebound[run] = (apex - contact) / kDrop;
    end[run] = world.states();
  }
  for (std::size_t i = 0; i < end[0].size(); ++i) d.apart = std::max(d.apart, (end[0][i].x - end[1][i].x).norm());
  return d;
}

std::string percent(double part, double whole) { return fmt(100.0 * part / whole, 2) + "%"; }

}  // namespace

int main(int argc, char** argv) {
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv, "Lab 5 benchmark: the box rain and Newton's cradle, PhysLab's World against Bullet.");
    const std::vector<int> sizes = options.quick ? std::vector<int>{100, 500} : std::vector<int>{100, 500, 2000};
    const int windows = options.quick ? 2 : 5;

    // Islands and sleeping (issue 40), first: their goal lines print as soon as they are measured
#ifdef PHYSLAB_HAVE_BULLET
    bench::useOurPairRules();
#endif
    const SettledPile pile = options.quick ? settledPile(6, 3, 3, 20) : settledPile(16, 4, 5, 60);
    const BallDrop drop = ballDrop(4);
    std::cout << "Lab 5 benchmark: a settled pile, sleeping on and off, beside Bullet with its deactivation, h = 1/60 s\n";
    pile.table.print(std::cout);
    std::cout << "ours: every box asleep after " << fmt(pile.settle_seconds) << " s; Bullet, from our settled pile: "
#ifdef PHYSLAB_HAVE_BULLET
              << (std::isnan(pile.bullet_settle_seconds) ? std::to_string(pile.bullet_asleep) + " boxes asleep after 5 s"
                                                          : "every box asleep after " + fmt(pile.bullet_settle_seconds) + " s")
#else
              << "not installed"
#endif
              << "\nours asleep, per step: broad phase " << fmt(1e3 * pile.asleep_phases.broad_phase) << " ms, narrow phase "
              << fmt(1e3 * pile.asleep_phases.narrow_phase) << " ms, respond " << fmt(1e3 * pile.asleep_phases.respond)
              << " ms, integrate " << fmt(1e3 * pile.asleep_phases.integrate) << " ms; sleeping against moving: "
              << fmt(pile.asleep_ms / pile.moving_ms) << "\n";
    Table drop_table({"what", "sleeping on", "sleeping off", "tolerance"});
    drop_table.add({"bodies asleep when the ball is dropped", std::to_string(drop.asleep_before), "-", "-"});
    drop_table.add({"most moving bodies awake at once after the drop", std::to_string(drop.most_awake), "-",
                    "<= " + std::to_string(drop.pile_bodies + 1) + " (the pile and the ball)"});
    drop_table.add({"ball's rebound / drop height", fmt(drop.rebound[0]), fmt(drop.rebound[1]), "0.025 (10 % of epsilon^2)"});
    drop_table.add({"largest distance between the two runs' final positions [m]", fmt(drop.apart), "-", "0.01"});
    std::cout << "\nLab 5 benchmark: a ball dropped on one of 4 sleeping towers of 5 cubes, 2 s, against the same run without sleeping\n";
    drop_table.print(std::cout);
    {
      const std::string at = "settled pile of " + std::to_string(pile.boxes) + " boxes, ";
      const std::string quick_verdict = "measured by a full run only (a quick run settles " + std::to_string(pile.boxes) + " boxes)";
      const double share = pile.asleep_ms / pile.awake_ms;
      std::cout << bench::goalLine(at + "sleeping against awake", fmt(share), "0.05",
                                   options.quick ? quick_verdict : share <= 0.05 ? "met" : "not met")
                << "\n";
      const double against = pile.asleep_ms / pile.bullet_ms;
      std::cout << bench::goalLine(at + "sleeping against Bullet with deactivation",
                                   std::isnan(against) ? fmt(pile.asleep_ms) + " ms" : fmt(against),
                                   std::isnan(against) ? "Bullet's (not installed in this run)" : "1",
                                   options.quick ? quick_verdict : against <= 1.0 ? "met" : "not met")
                << "\n";
      bench::printGoal("ball dropped on one of 4 sleeping towers, most bodies awake at once", std::to_string(drop.most_awake),
                       "<= " + std::to_string(drop.pile_bodies + 1) + " (that tower and the ball)",
                       drop.most_awake <= drop.pile_bodies + 1);
      bench::printGoal("ball dropped on one of 4 sleeping towers, same bounce as without sleeping (rebound ratio; final positions)",
                       fmt(std::abs(drop.rebound[0] - drop.rebound[1])) + "; " + fmt(drop.apart) + " m", "<= 0.025; <= 0.01 m",
                       std::abs(drop.rebound[0] - drop.rebound[1]) <= 0.025 && drop.apart <= 0.01);
    }
    // 3 s of rain at N <= 500 (the last bodies land at about 1.6 s); 1.5 s at N = 2000, where a
    // step costs up to 50 ms and the column (50 m high) is still falling
    const auto stepsFor = [&](int n) { return options.quick ? 20 : (n <= 500 ? 180 : 90); };

#ifdef PHYSLAB_HAVE_BULLET
    const std::string bullet = bench::bulletName();
#endif
    Settings sequential, simultaneous;
    sequential.method = ResponseMethod::Sequential;
    simultaneous.method = ResponseMethod::Simultaneous;
    std::cout << "PhysLab settings: " << sequential << "\n  and: " << simultaneous << "\n";

    struct Engine {
      std::string name, label;
      std::vector<RunResult> at;  // one per size
    };
    std::vector<Engine> engines = {{"PhysLab sequential", "PhysLab sequential", {}},
                                   {"PhysLab simultaneous", "PhysLab simultaneous", {}}};
#ifdef PHYSLAB_HAVE_BULLET
    engines.push_back({bullet + " sequential impulse", "Bullet btSequentialImpulseConstraintSolver", {}});
#endif

    for (const int n : sizes) {
      const Scene scene = boxRain(n, kSeed);
      const int steps = stepsFor(n);
      std::vector<RunResult> r(engines.size());
      measureOurs(scene, sequential, steps, r[0]);
      measureOurs(scene, simultaneous, steps, r[1]);
      for (int e = 0; e < 2; ++e) {
        const Settings& settings = e == 0 ? sequential : simultaneous;
        r[e].last_penetration_median = shakenMedian(scene, r[e].last_penetration, [&](const Scene& shaken) {
          RunResult once;
          measureOurs(shaken, settings, steps, once);
          return once.last_penetration;
        });
      }
#ifdef PHYSLAB_HAVE_BULLET
      measureBullet(scene, sequential, steps, r[2]);
      r[2].last_penetration_median = shakenMedian(scene, r[2].last_penetration, [&](const Scene& shaken) {
        RunResult once;
        measureBullet(shaken, sequential, steps, once);
        return once.last_penetration;
      });
#endif
      for (int w = 0; w < windows; ++w) {
        timeOurs(scene, sequential, steps, r[0]);
        timeOurs(scene, simultaneous, steps, r[1]);
#ifdef PHYSLAB_HAVE_BULLET
        timeBullet(scene, sequential, steps, r[2]);
#endif
      }
      for (std::size_t e = 0; e < engines.size(); ++e) engines[e].at.push_back(r[e]);
      std::cout << "N = " << n << ": " << steps << " steps, best of " << windows << " windows done\n";
    }

    // The main table: speed and penetration per engine and size, with the time ratio to Bullet.
    Table table({"N", "engine", "ms per step", "steps per second", "time / Bullet's", "max penetration [mm]",
                 "in the last step [mm]", "last step, median of " + std::to_string(kShakenRuns) + " [mm]", "contact points per step", "solver sweeps per step", "outside walls / below ground at end"});
    const Engine* bullet_engine = engines.size() > 2 ? &engines.back() : nullptr;  // when built with Bullet
    for (std::size_t s = 0; s < sizes.size(); ++s) {
      for (const Engine& e : engines) {
        const RunResult& r = e.at[s];
        const double bullet_seconds = bullet_engine ? bullet_engine->at[s].seconds_per_step : NAN;
        table.add({std::to_string(sizes[s]), e.name, fmt(1e3 * r.seconds_per_step), fmt(1.0 / r.seconds_per_step),
                   std::isfinite(bullet_seconds) ? fmt(r.seconds_per_step / bullet_seconds) : "-",
                   fmt(1e3 * r.max_penetration), fmt(1e3 * r.last_penetration), fmt(1e3 * r.last_penetration_median),
                   fmt(r.contacts_per_step),
                   std::isfinite(r.sweeps_per_step) ? fmt(r.sweeps_per_step) : "up to " + std::to_string(sequential.iterations),
                   r.finite ? std::to_string(r.outside_walls) + " / " + std::to_string(r.below_ground) : "NOT FINITE"});
      }
    }
#ifndef PHYSLAB_HAVE_BULLET
    table.add({"-", "Bullet", "not installed", "-", "-", "-", "-", "-", "-", "-", "-"});
#endif

    // Where our step's time goes: ms per step in each phase of World::step, fastest window.
    Table phases({"N", "method", "forces", "broad phase", "narrow phase", "classify", "respond", "integrate",
                  "correct", "diagnostics", "sum of phases [ms]", "respond share"});
    for (std::size_t s = 0; s < sizes.size(); ++s) {
      for (std::size_t e = 0; e < 2; ++e) {
        const PhaseTimes& p = engines[e].at[s].phases;
        const double sum =
            p.forces + p.broad_phase + p.narrow_phase + p.classify + p.respond + p.integrate + p.correct + p.diagnostics;
        phases.add({std::to_string(sizes[s]), responseMethodName(e == 0 ? ResponseMethod::Sequential : ResponseMethod::Simultaneous),
                    fmt(1e3 * p.forces), fmt(1e3 * p.broad_phase), fmt(1e3 * p.narrow_phase), fmt(1e3 * p.classify),
                    fmt(1e3 * p.respond), fmt(1e3 * p.integrate), fmt(1e3 * p.correct), fmt(1e3 * p.diagnostics),
                    fmt(1e3 * sum),
                    percent(p.respond, sum)});
      }
    }

    // Newton's cradle: zero gravity, epsilon = 1, the first ball at v0, one second at 1/60 s.
    const double v0 = 1.0;
    const int cradle_steps = 60;
    Table cradle({"balls", "engine", "final velocities along x [m/s]", "kinetic energy end / start",
                  "momentum end / start"});
    for (const int balls : {3, 5}) {
      const auto row = [&](const std::string& name, const CradleResult& c) {
        cradle.add({std::to_string(balls), name, velocities(c.v), fmt(c.energy_ratio, 4), fmt(c.momentum_ratio, 4)});
      };
      row("PhysLab sequential", cradleOurs(balls, v0, cradle_steps, ResponseMethod::Sequential));
      row("PhysLab simultaneous", cradleOurs(balls, v0, cradle_steps, ResponseMethod::Simultaneous));
#ifdef PHYSLAB_HAVE_BULLET
      row(bullet + " sequential impulse", cradleBullet(balls, v0, cradle_steps));
#endif
    }

    // Timewarp against synchronous stepping on the sparse scene
    const Table timewarp = timewarpBench(options.quick ? std::vector<int>{100} : std::vector<int>{100, 1000}, windows);

    // Continuous collision's cost
    const auto [continuous, continuous_ratio] = continuousBench(windows, options.quick);

    // The chart: ms per step against N, log-log.
    Chart chart(options.quick ? "Box rain at h = 1/60 s: cost of a step (first 20 steps)"
                                : "Box rain at h = 1/60 s: cost of a step (3 s of rain; 1.5 s at N = 2000)",
                "number of bodies N", "time per step [ms]");
    chart.logX().logY();
    for (std::size_t e = 0; e < engines.size(); ++e) {
      Series series{engines[e].label, {}, {}, "linespoints pt 7"};
      for (std::size_t s = 0; s < sizes.size(); ++s) {
        series.x.push_back(sizes[s]);
        series.y.push_back(1e3 * engines[e].at[s].seconds_per_step);
      }
      chart.add(series);
    }
    const std::vector<std::string> chart_paths = chart.save(options.out + "/lab05_bench");

#ifdef PHYSLAB_HAVE_BULLET
    for (std::size_t s = 0; s < sizes.size(); ++s) {
      for (std::size_t e = 0; e < 2; ++e) {
        const RunResult &ours = engines[e].at[s], &peer = engines[2].at[s];
        std::cout << "N = " << sizes[s] << ", " << engines[e].name << " time / Bullet time: "
                  << fmt(ours.seconds_per_step / peer.seconds_per_step) << ", max penetration ours / Bullet's: "
                  << fmt(ours.max_penetration / peer.max_penetration) << "\n";
      }
    }
#endif
    std::cout << "Lab 5 benchmark: box rain, h = 1/60 s, best of " << windows << " windows\n";
    table.print(std::cout);
    std::cout << "\nLab 5 benchmark: PhysLab's phases, ms per step (fastest window)\n";
    phases.print(std::cout);
    std::cout << "\nLab 5 benchmark: Newton's cradle, no gravity, epsilon = 1, v0 = " << fmt(v0) << " m/s, "
              << cradle_steps << " steps of 1/60 s\n";
    cradle.print(std::cout);
    std::cout << "\nLab 5 benchmark: Timewarp against synchronous stepping, ball through a row among N spheres, 0.6 s\n";
    timewarp.print(std::cout);
    std::cout << "\nLab 5 benchmark: continuous collision on and off, sequential impulses, h = 1/60 s\n";
    continuous.print(std::cout);

    // One Markdown file: the main table, then the phases and the cradle.
    const std::string path = table.saveMarkdown(options.out + "/lab05_bench.md");
    const std::string phases_path = phases.saveMarkdown(options.out + "/lab05_bench_phases.md");
    const std::string cradle_path = cradle.saveMarkdown(options.out + "/lab05_bench_cradle.md");
    const std::string timewarp_path = timewarp.saveMarkdown(options.out + "/lab05_bench_timewarp.md");
    const std::string continuous_path = continuous.saveMarkdown(options.out + "/lab05_bench_continuous.md");
    {
      std::ifstream phases_file(phases_path), cradle_file(cradle_path), timewarp_file(timewarp_path),
          continuous_file(continuous_path);
      std::ofstream out(path, std::ios::app);
      out << "\nPhysLab's phases, ms per step (fastest window).\n\n" << phases_file.rdbuf();
      out << "\nNewton's cradle: no gravity, epsilon = 1, v0 = " << fmt(v0) << " m/s, " << cradle_steps
          << " steps of 1/60 s.\n\n" << cradle_file.rdbuf();
      out << "\nTimewarp against synchronous stepping: a ball at 4 m/s through a row of 5 among N spheres, 0.6 s.\n\n"
          << timewarp_file.rdbuf();
      out << "\nContinuous collision on and off: sequential impulses, h = 1/60 s.\n\n" << continuous_file.rdbuf();
    }
    const std::string pile_path = pile.table.saveMarkdown(options.out + "/lab05_bench_pile.md");
    const std::string drop_path = drop_table.saveMarkdown(options.out + "/lab05_bench_drop.md");
    {
      std::ifstream pile_file(pile_path), drop_file(drop_path);
      std::ofstream out(path, std::ios::app);
      out << "\nA settled pile, sleeping on and off, beside Bullet with its deactivation (fastest of "
          << (options.quick ? 3 : 5) << " windows; ours asleep after " << fmt(pile.settle_seconds) << " s).\n\n"
          << pile_file.rdbuf();
      out << "\nA ball dropped on one of 4 sleeping towers of 5 cubes, 2 s, against the same run without sleeping.\n\n"
          << drop_file.rdbuf();
    }
    std::remove(pile_path.c_str());
    std::remove(drop_path.c_str());
    std::remove(continuous_path.c_str());
    std::remove(timewarp_path.c_str());
    std::remove(phases_path.c_str());
    std::remove(cradle_path.c_str());
    std::cout << "wrote " << path << "\n";
    for (const std::string& p : chart_paths) std::cout << "wrote " << p << "\n";

    // The goals (issue 23): sequential impulses on the rain of 100 and 500 bodies at or below
    // Bullet's time, leaving at most Bullet's penetration in the last step. A quick run stops
    // after 20 steps, before the rain lands: its figures say nothing of the goals.
    // Issue 37: continuous collision costs at most 3 % where no body is fast, against the same
    // scene without it, in this run
    bench::printGoal("continuous collision on a stack of 10 cubes (no fast body), time on / off", fmt(continuous_ratio),
                     "<= 1.03", continuous_ratio <= 1.03);
    if (options.quick) std::cout << "goals: measured by a full run only (a quick run stops before the rain lands)\n";
    for (std::size_t s = 0; s < sizes.size() && !options.quick; ++s) {
      if (sizes[s] != 100 && sizes[s] != 500) continue;
      const RunResult& ours = engines[0].at[s];
      const std::string at = "box rain of " + std::to_string(sizes[s]) + " bodies, sequential impulses, ";
#ifdef PHYSLAB_HAVE_BULLET
      const RunResult& peer = engines[2].at[s];
      bench::printGoal(at + "ms per step", fmt(1e3 * ours.seconds_per_step),
                       fmt(1e3 * peer.seconds_per_step) + " (Bullet's)", ours.seconds_per_step <= peer.seconds_per_step);
      bench::printGoal(at + "penetration in the last step, median of " + std::to_string(kShakenRuns) +
                           " runs shifted by 1 nm [mm]",
                       fmt(1e3 * ours.last_penetration_median), fmt(1e3 * peer.last_penetration_median) + " (Bullet's)",
                       ours.last_penetration_median <= peer.last_penetration_median);
#else
      bench::printGoal(at + "ms per step", fmt(1e3 * ours.seconds_per_step), "Bullet's (not installed in this run)", false);
      bench::printGoal(at + "penetration in the last step, median of " + std::to_string(kShakenRuns) +
                           " runs shifted by 1 nm [mm]",
                       fmt(1e3 * ours.last_penetration_median), "Bullet's (not installed in this run)", false);
#endif
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_05_impulses: " << e.what() << "\n";
    return 1;
  }
}
