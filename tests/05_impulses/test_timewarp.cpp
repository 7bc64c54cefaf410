// Lab 5 graded tests of Timewarp (section 9): the impact time of two spheres against hand-solved
// quadratics, the rollback rule against a fixed-point oracle, the impulse at an impact, and the
// scheduler built on them: exact event times of a fast ball through a row, events against a
// synchronous event-driven oracle written here, conservation, no body behind one it met, rollbacks
// that stay inside a group of dependent bodies, degenerate and bad input.
#include <algorithm>
#include <cmath>
#include <limits>

#include "physlab/error.hpp"
#include "physlab/timewarp.hpp"
#include "support.hpp"

using namespace physlab;
using namespace physlab::test;
using Catch::Matchers::Contains;

namespace {

const double kNever = std::numeric_limits<double>::infinity();

// The rollback rule by fixed point, in any order: undo every event that has a body rolled back
// to before it, until nothing changes (the student's version is one pass in time order).
std::vector<double> rollbackOracle(const std::vector<TimewarpEvent>& events, int n, const std::vector<int>& seeds,
                                   double t_c) {
  std::vector<double> r(static_cast<std::size_t>(n), kNever);
  for (const int k : seeds) r[k] = t_c;
  for (bool changed = true; changed;) {
    changed = false;
    for (auto e = events.rbegin(); e != events.rend(); ++e) {
      if (!(e->t > r[e->a] || e->t > r[e->b])) continue;
      for (const int k : {e->a, e->b}) {
        if (e->t < r[k]) {
          r[k] = e->t;
          changed = true;
        }
      }
    }
  }
  return r;
}

// A synchronous event-driven oracle with its own quadratic and its own elastic formula: every
// body goes to the earliest impact of any pair, which is resolved along the line of centres.
std::vector<TimewarpEvent> eventOracle(const std::vector<TimewarpSphere>& spheres, std::vector<SphereState> states,
                                       double t_end) {
  std::vector<TimewarpEvent> events;
  const int n = static_cast<int>(spheres.size());
  double t = 0.0;
  while (true) {
    double best = kNever;
    int a = -1, b = -1;
    for (int p = 0; p < n; ++p) {
      for (int q = p + 1; q < n; ++q) {
        const Vec3 d = states[p].x - states[q].x, w = states[p].v - states[q].v;
        const double R = spheres[p].radius + spheres[q].radius, dw = d.dot(w);
        const double disc = dw * dw - w.squaredNorm() * (d.squaredNorm() - R * R);
        if (dw >= 0.0 || disc <= 0.0) continue;
        const double s = std::max(0.0, (-dw - std::sqrt(disc)) / w.squaredNorm());
        if (t + s < best) {
          best = t + s;
          a = p;
          b = q;
        }
      }
    }
    if (a < 0 || best > t_end) break;
    for (SphereState& s : states) s.x += (best - t) * s.v;
    t = best;
    const Vec3 n_hat = (states[a].x - states[b].x).normalized();
    const double m_a = spheres[a].mass, m_b = spheres[b].mass, v_rel = n_hat.dot(states[a].v - states[b].v);
    const double j = -2.0 * v_rel / (1.0 / m_a + 1.0 / m_b);
    states[a].v += (j / m_a) * n_hat;
    states[b].v -= (j / m_b) * n_hat;
    events.push_back({t, a, b, j});
  }
  return events;
}

// `count` elastic spheres of random mass and radius, apart from each other, in a cube of side 2 m,
// moving at up to 2 m/s (no gravity).
void randomGas(int count, const Vec3& offset, std::vector<TimewarpSphere>& spheres, std::vector<SphereState>& states) {
  for (int placed = 0; placed < count;) {
    TimewarpSphere sphere{uniform(0.5, 2.0), uniform(0.1, 0.25), 1.0};
    SphereState state;
    state.x = offset + randomVec3(1.0);
    state.v = randomVec3(2.0);
    bool apart = true;
    for (std::size_t k = 0; k < spheres.size(); ++k) {
      apart = apart && (states[k].x - state.x).norm() > spheres[k].radius + sphere.radius + 0.05;
    }
    if (!apart) continue;
    spheres.push_back(sphere);
    states.push_back(state);
    ++placed;
  }
}

Vec3 momentumOf(const TimewarpWorld& world, const std::vector<TimewarpSphere>& spheres) {
  Vec3 P = Vec3::Zero();
  for (int i = 0; i < world.size(); ++i) P += spheres[i].mass * world.state(i).v;
  return P;
}

double energyOf(const TimewarpWorld& world, const std::vector<TimewarpSphere>& spheres) {
  double E = 0.0;
  for (int i = 0; i < world.size(); ++i) E += 0.5 * spheres[i].mass * world.state(i).v.squaredNorm();
  return E;
}

// Two slow spheres (1, 2) that meet at t = 0.5 s and a ball (0) at 2.1 m/s that hits sphere 1 at
// 0.8 / (2.1 - 0.1) = 0.4 s, all of radius 0.1 m, along y = `y`.
void chainScene(double y, std::vector<TimewarpSphere>& spheres, std::vector<SphereState>& states) {
  const double vs[] = {2.1, 0.1, -0.1}, xs[] = {0.0, 1.0, 1.3};
  for (int k = 0; k < 3; ++k) {
    spheres.push_back(TimewarpSphere{1.0, 0.1, 1.0});
    SphereState s;
    s.x = Vec3(xs[k], y, 0.0);
    s.v = Vec3(vs[k], 0.0, 0.0);
    states.push_back(s);
  }
}

}  // namespace

TEST_CASE("timewarp: the impact time of two spheres is the smaller root of the quadratic", "[lab05][pts=2][sec=9]") {
  const Vec3 o = Vec3::Zero();
  // Head on, by hand: a gap of 1 - 0.3 = 0.7 m closed at 3 m/s. One division: round-off only.
  CHECK(sphereImpactTime(o, Vec3(2, 0, 0), 0.1, Vec3(1, 0, 0), Vec3(-1, 0, 0), 0.2) == Approx(0.7 / 3.0).epsilon(1e-14));
  // Off centre by 0.3 with radii 0.25 each: (3s - 1)^2 + 0.09 = 0.25, so 3s - 1 = -0.4, s = 0.2
  // (the later root 0.4667 is the exit). A square root and a division: round-off only.
  CHECK(sphereImpactTime(o, Vec3(3, 0, 0), 0.25, Vec3(1, 0.3, 0), o, 0.25) == Approx(0.2).epsilon(1e-14));
  // Off centre by 0.6: a miss. Off by exactly 0.5 = r_a + r_b: a graze (double root), no impact.
  CHECK(sphereImpactTime(o, Vec3(3, 0, 0), 0.25, Vec3(1, 0.6, 0), o, 0.25) == kNever);
  CHECK(sphereImpactTime(o, Vec3(3, 0, 0), 0.25, Vec3(1, 0.5, 0), o, 0.25) == kNever);
  // Moving apart, side by side, at relative rest: never
  CHECK(sphereImpactTime(o, Vec3(-1, 0, 0), 0.1, Vec3(1, 0, 0), o, 0.1) == kNever);
  CHECK(sphereImpactTime(o, Vec3(0, 1, 0), 0.1, Vec3(1, 0, 0), o, 0.1) == kNever);
  CHECK(sphereImpactTime(o, Vec3(1, 1, 1), 0.1, Vec3(1, 0, 0), Vec3(1, 1, 1), 0.1) == kNever);
  // Touching exactly (0.5 = 0.25 + 0.25): approaching is an impact now, separating is none
  CHECK(sphereImpactTime(o, Vec3(1, 0, 0), 0.25, Vec3(0.5, 0, 0), o, 0.25) == 0.0);
  CHECK(sphereImpactTime(o, Vec3(-1, 0, 0), 0.25, Vec3(0.5, 0, 0), o, 0.25) == kNever);
  // Overlapping and approaching: now
  CHECK(sphereImpactTime(o, Vec3(1, 0, 0), 0.25, Vec3(0.3, 0, 0), o, 0.25) == 0.0);
  // The order of the two spheres does not matter: exactly, d and w only change sign
  CHECK(sphereImpactTime(Vec3(1, 0.3, 0), o, 0.25, o, Vec3(3, 0, 0), 0.25) == Approx(0.2).epsilon(1e-14));

  // Random pairs aimed near each other: at s the centres are r_a + r_b apart, before it farther
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 x_a = randomVec3(2.0), x_b = randomVec3(2.0), v_b = randomVec3(1.0);
    const double r_a = uniform(0.1, 0.5), r_b = uniform(0.1, 0.5);
    if ((x_a - x_b).norm() <= r_a + r_b) continue;
    const Vec3 v_a = v_b + (x_b - x_a + randomVec3(0.4)) * uniform(0.5, 3.0);
    const double s = sphereImpactTime(x_a, v_a, r_a, x_b, v_b, r_b);
    const Vec3 d = x_a - x_b, w = v_a - v_b;
    if (s == kNever) {
      // No real root while approaching: the distance along the way never reaches r_a + r_b
      // (sampled finely; a relative 1e-9 for a graze within round-off)
      for (int k = 0; k <= 1000; ++k) CHECK((d + w * (k * 0.01)).norm() >= (r_a + r_b) * (1.0 - 1e-9));
      continue;
    }
    // The root satisfies the quadratic: round-off relative to the distances (at most ~10 m)
    CHECK((d + w * s).norm() == Approx(r_a + r_b).margin(1e-12 * (1.0 + d.norm())));
    CHECK(s > 0.0);
    CHECK((d + w * (0.5 * s)).norm() > r_a + r_b);
  }
}

TEST_CASE("timewarp: the rollback rule takes the pair and every body that met a rolled-back body since", "[lab05][pts=2][sec=9]") {
  // By hand: seeds 0 and 1 at t_c = 0.3. (0.2, 1-2) is before t_c: it stands, 2 keeps its state.
  // (0.5, 2-3) involves no rolled-back body: stands. (0.6, 0-4): 0 is back at 0.3, so 4 goes back
  // to 0.6. (0.7, 3-4): 4 is back at 0.6, so 3 goes back to 0.7.
  const std::vector<TimewarpEvent> events = {{0.2, 1, 2, 1.0}, {0.5, 2, 3, 1.0}, {0.6, 0, 4, 1.0}, {0.7, 3, 4, 1.0}};
  const std::vector<double> r = rollbackTimes(events, 6, {0, 1}, 0.3);
  REQUIRE(r.size() == 6);
  CHECK(r[0] == 0.3);
  CHECK(r[1] == 0.3);
  CHECK(r[2] == kNever);
  CHECK(r[3] == 0.7);
  CHECK(r[4] == 0.6);
  CHECK(r[5] == kNever);  // never met anybody
  // An event exactly at the rollback time stands: 2 keeps its state
  const std::vector<double> at = rollbackTimes({{0.3, 1, 2, 1.0}}, 3, {1}, 0.3);
  CHECK(at[2] == kNever);
  // Equal event times after t_c: 0-1 at 0.4 is undone and takes 1 back to 0.4, where 1-2 (at
  // exactly 1's rollback time) stands; listed the other way round, 1-2 comes first and stands too
  CHECK(rollbackTimes({{0.4, 0, 1, 1.0}, {0.4, 1, 2, 1.0}}, 3, {0}, 0.1) == std::vector<double>{0.1, 0.4, kNever});
  CHECK(rollbackTimes({{0.4, 1, 2, 1.0}, {0.4, 0, 1, 1.0}}, 3, {0}, 0.1) == std::vector<double>{0.1, 0.4, kNever});
  // No events: only the seeds; no bodies at all: nothing
  CHECK(rollbackTimes({}, 3, {2}, 1.5) == std::vector<double>{kNever, kNever, 1.5});
  CHECK(rollbackTimes({}, 0, {}, 0.0).empty());

  // Random histories against the fixed-point oracle
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 2 + static_cast<int>(uniform(0.0, 10.0));
    std::vector<TimewarpEvent> random_events;
    double t = 0.0;
    for (int e = 0; e < 3 * n; ++e) {
      t += uniform(0.0, 0.1);
      const int a = static_cast<int>(uniform(0.0, n)), b = (a + 1 + static_cast<int>(uniform(0.0, n - 1))) % n;
      random_events.push_back({t, std::min(a, b), std::max(a, b), 1.0});
    }
    const int seed_a = static_cast<int>(uniform(0.0, n)), seed_b = (seed_a + 1) % n;
    const double t_c = uniform(0.0, t);
    CHECK(rollbackTimes(random_events, n, {seed_a, seed_b}, t_c) == rollbackOracle(random_events, n, {seed_a, seed_b}, t_c));
  }
}

TEST_CASE("timewarp: an impact keeps momentum, reverses the normal velocity by epsilon, and leaves separating spheres alone", "[lab05][pts=1][sec=9]") {
  // By hand, every run: equal masses head on, elastic, swap velocities (j = 2 m |v|)
  Vec3 v_a(-1.0, 0.0, 0.0), v_b(2.0, 0.0, 0.0);
  CHECK(resolveSphereImpact(Vec3(1, 0, 0), v_a, 1.0, Vec3(0.8, 0, 0), v_b, 1.0, 0.1, 1.0) == Approx(3.0).epsilon(1e-15));
  CHECK(v_a.isApprox(Vec3(2, 0, 0), 1e-15));  // a few operations on small integers: round-off only
  CHECK(v_b.isApprox(Vec3(-1, 0, 0), 1e-15));
  // Separating: nothing changes, exactly, and j = 0
  const Vec3 leaving_a = v_a, leaving_b = v_b;
  CHECK(resolveSphereImpact(Vec3(1, 0, 0), v_a, 1.0, Vec3(0.8, 0, 0), v_b, 1.0, 0.1, 1.0) == 0.0);
  CHECK(v_a == leaving_a);
  CHECK(v_b == leaving_b);

  for (int trial = 0; trial < 100; ++trial) {
    const double m_a = uniform(0.2, 5.0), m_b = uniform(0.2, 5.0), r_b = uniform(0.1, 0.5);
    const double epsilon = trial == 0 ? 1.0 : uniform(0.0, 1.0);
    const Vec3 x_b = randomVec3(1.0), n = randomVec3(1.0).normalized(), x_a = x_b + (r_b + uniform(0.1, 0.5)) * n;
    Vec3 va = randomVec3(2.0), vb = randomVec3(2.0);
    if (n.dot(va - vb) > 0.0) std::swap(va, vb);
    const Vec3 P0 = m_a * va + m_b * vb;
    const double v_rel = n.dot(va - vb), E0 = 0.5 * m_a * va.squaredNorm() + 0.5 * m_b * vb.squaredNorm();
    const Vec3 tangent_before = (va - vb) - v_rel * n;
    const double j = resolveSphereImpact(x_a, va, m_a, x_b, vb, m_b, r_b, epsilon);
    // Momentum: an equal and opposite impulse, round-off relative to the momenta (at most ~30 kg m/s)
    CHECK((m_a * va + m_b * vb - P0).norm() <= 1e-13 * (1.0 + P0.norm() + j));
    // The relative normal velocity is -epsilon times before, the tangential part unchanged (round-off)
    CHECK(n.dot(va - vb) == Approx(-epsilon * v_rel).margin(1e-13));
    CHECK(((va - vb) - n.dot(va - vb) * n - tangent_before).norm() <= 1e-13);
    // Energy: kept when elastic, never gained (round-off relative to E)
    const double E1 = 0.5 * m_a * va.squaredNorm() + 0.5 * m_b * vb.squaredNorm();
    if (epsilon == 1.0) CHECK(E1 == Approx(E0).epsilon(1e-13));
    CHECK(E1 <= E0 * (1.0 + 1e-13));
  }
}

TEST_CASE("timewarp: a fast ball through a row hits each sphere at the hand-computed time", "[lab05][pts=2][sec=9]") {
  // Ball at 4 m/s, row spheres 0.3 m apart (gap), equal masses, elastic: the ball hits sphere 1
  // after 0.8 m, 0.2 s; each sphere stops and passes 4 m/s on across the next gap, 0.075 s later.
  for (const int background : {0, 30}) {
    std::vector<TimewarpSphere> spheres;
    std::vector<SphereState> states;
    fastBallThroughRow(5, 0.3, 4.0, background, 7u + static_cast<unsigned>(uniform(0.0, 1000.0)), spheres, states);
    TimewarpSettings settings;
    settings.max_step = 1.0;
    settings.max_travel = 0.05;
    INFO("a ball at 4 m/s through a row of 5 spheres 0.3 m apart, " << background
         << " background spheres, max_step 1 s, max_travel 0.05 m: expected 5 events, the first at 0.2 s");
    TimewarpWorld world(spheres, states, settings);
    world.run(1.0);
    const std::vector<TimewarpEvent>& events = world.events();
    REQUIRE(events.size() == 5);
    for (int k = 0; k < 5; ++k) {
      CAPTURE(background, k);
      CHECK(events[k].a == k);
      CHECK(events[k].b == k + 1);
      // A closed-form root per event, each from states moved by a few flights: round-off only
      CHECK(events[k].t == Approx((0.8 + 0.3 * k) / 4.0).epsilon(1e-12));
      CHECK(events[k].j == Approx(4.0).epsilon(1e-12));  // an equal-mass swap: j = m v0
    }
    // The ball and the first four stop; the last leaves at v0 from x = 1 + 4 (0.5) at t = 0.5 s
    for (int k = 0; k < 5; ++k) CHECK(world.state(k).v.norm() <= 1e-12);
    CHECK(world.state(5).v.isApprox(Vec3(4, 0, 0), 1e-12));
    CHECK(world.state(5).x.isApprox(Vec3(3.0 + 4.0 * 0.5, 0, 0), 1e-12));
    // The row ran ahead (its clocks stepped by 1 s) and was rolled back once per sphere at least
    CHECK(world.stats().rollbacks >= 5);
    // The background drifts untouched: exactly its free flight, to round-off of one product
    for (int k = 6; k < world.size(); ++k) CHECK(world.state(k).x.isApprox(states[k].x + states[k].v, 1e-14));
  }
}

TEST_CASE("timewarp: events are resolved in time order, match an event-driven oracle, and keep momentum and energy", "[lab05][pts=2][sec=9]") {
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<TimewarpSphere> spheres;
    std::vector<SphereState> states;
    randomGas(6, Vec3::Zero(), spheres, states);
    TimewarpSettings settings;
    settings.max_step = uniform(0.05, 0.5);
    settings.max_travel = uniform(0.02, 0.2);
    INFO("trial " << trial << ": a gas of 6 spheres, max_step " << settings.max_step << " s, max_travel "
         << settings.max_travel << " m, run to 1 s");
    TimewarpWorld world(spheres, states, settings);
    const Vec3 P0 = momentumOf(world, spheres);
    const double E0 = energyOf(world, spheres);
    world.run(1.0);
    const std::vector<TimewarpEvent> expected = eventOracle(spheres, states, 1.0);
    const std::vector<TimewarpEvent>& events = world.events();
    CAPTURE(trial, expected.size());
    REQUIRE(events.size() == expected.size());
    for (std::size_t k = 0; k < events.size(); ++k) {
      if (k > 0) CHECK(events[k].t >= events[k - 1].t);
      CHECK(events[k].a == expected[k].a);
      CHECK(events[k].b == expected[k].b);
      // Each event's time comes from states carried through the earlier ones: round-off grows
      // by the ratio of distance to radius per event (~10), so 1e-9 s over a handful of events
      CHECK(events[k].t == Approx(expected[k].t).margin(1e-9));
    }
    // Elastic: momentum and kinetic energy kept, round-off per event relative to their size
    // (at most ~10 kg m/s and ~20 J): 1e-12 times (1 + events)
    const double bound = 1e-12 * (1.0 + static_cast<double>(events.size()));
    CHECK((momentumOf(world, spheres) - P0).norm() <= bound * (1.0 + P0.norm()));
    CHECK(std::abs(energyOf(world, spheres) - E0) <= bound * (1.0 + E0));
    CHECK(world.largestLag() == 0.0);
  }
}

TEST_CASE("timewarp: a rollback takes only the bodies that depend on the colliding pair", "[lab05][pts=2][sec=9]") {
  // Two copies of the chain scene, 10 m apart: bodies 0-2 and 3-5 never meet
  std::vector<TimewarpSphere> spheres;
  std::vector<SphereState> states;
  chainScene(0.0, spheres, states);
  chainScene(10.0, spheres, states);
  TimewarpSettings settings;
  settings.max_step = 1.0;
  settings.max_travel = 0.1;  // the slow spheres step 1 s at a time, the ball 0.048 s
  INFO("the chain scene twice, 10 m apart (bodies 0-2 and 3-5), max_step 1 s, max_travel 0.1 m, run to 2 s");
  TimewarpWorld world(spheres, states, settings);
  world.run(2.0);
  // By hand, in each group (offset 0 or 3), the rollbacks in the order they happen:
  // 1. sphere 2 steps [0, 1] s and meets sphere 1, which has run to 1 s, at 0.5 s: 1 goes back to 0.5;
  // 2. the ball, stepping behind them, hits sphere 1 at 0.8 / (2.1 - 0.1) = 0.4 s: 1 goes back to
  //    0.4 s, and 2, which met 1 at 0.5 s, goes back to 0.5 s with that impact undone (the ball
  //    keeps its state: it met nobody). The ball and 1 swap velocities: 0.1 and 2.1 m/s;
  // 3. sphere 1 (x = 1.04) reaches 2 (x = 1.3 - 0.04 = 1.26) over the gap 0.02 m at 2.2 m/s, at
  //    0.4 + 0.02 / 2.2 s, in 2's past (0.5 s): 2 goes back; they swap: -0.1 and 2.1 m/s;
  // 4. sphere 1 (now at -0.1 m/s) meets the ball (0.1 m/s), which has run ahead to 1.4 s, over
  //    the gap 0.2 / 11 m closed at 0.2 m/s, at 0.5 s: the ball goes back to 0.5 s; they swap.
  const double t3 = 0.4 + 0.02 / 2.2;
  struct Expected {
    double t_c;
    int a, b;
    std::vector<int> bodies;
    std::vector<double> times;
  };
  const std::vector<Expected> expected = {
      {0.5, 1, 2, {1}, {0.5}}, {0.4, 0, 1, {1, 2}, {0.4, 0.5}}, {t3, 1, 2, {2}, {t3}}, {0.5, 0, 1, {0}, {0.5}}};
  for (const int offset : {0, 3}) {
    CAPTURE(offset);
    std::vector<TimewarpRollback> group;
    for (const TimewarpRollback& rb : world.rollbacks()) {
      if (rb.a / 3 == offset / 3) group.push_back(rb);
    }
    REQUIRE(group.size() == expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      CAPTURE(k);
      CHECK(group[k].a == expected[k].a + offset);
      CHECK(group[k].b == expected[k].b + offset);
      // Closed-form roots from states carried through a few flights: round-off only
      CHECK(group[k].t_c == Approx(expected[k].t_c).epsilon(1e-12));
      REQUIRE(group[k].bodies.size() == expected[k].bodies.size());
      for (std::size_t m = 0; m < expected[k].bodies.size(); ++m) {
        CHECK(group[k].bodies[m] == expected[k].bodies[m] + offset);
        CHECK(group[k].times[m] == Approx(expected[k].times[m]).epsilon(1e-12));
      }
    }
    // Two elastic swaps later: the ball at -0.1, sphere 1 at 0.1 and sphere 2 at 2.1 m/s (round-off)
    CHECK(world.state(offset).v.isApprox(Vec3(-0.1, 0, 0), 1e-12));
    CHECK(world.state(offset + 1).v.isApprox(Vec3(0.1, 0, 0), 1e-12));
    CHECK(world.state(offset + 2).v.isApprox(Vec3(2.1, 0, 0), 1e-12));
  }
  // Every rollback stays in the group of its pair
  for (const TimewarpRollback& rb : world.rollbacks()) {
    CHECK(rb.b / 3 == rb.a / 3);
    for (const int k : rb.bodies) CHECK(k / 3 == rb.a / 3);
  }

  // Random: two gases 20 m apart; no rollback crosses from one to the other
  std::vector<TimewarpSphere> gas;
  std::vector<SphereState> gas_states;
  randomGas(6, Vec3::Zero(), gas, gas_states);
  randomGas(6, Vec3(20.0, 0.0, 0.0), gas, gas_states);
  TimewarpWorld two(gas, gas_states, settings);
  two.run(1.0);
  for (const TimewarpRollback& rb : two.rollbacks()) {
    for (const int k : rb.bodies) CHECK(k / 6 == rb.a / 6);
  }
  CHECK(two.largestLag() == 0.0);
  CHECK(world.largestLag() == 0.0);
}

TEST_CASE("timewarp: no body is ever behind one it has met", "[lab05][pts=1][sec=9]") {
  // A dense gas with long optimistic steps: many rollbacks, each of which must take back every
  // body whose collision used a rolled-back state (else that body keeps a collision with a body
  // now behind it)
  long rollbacks = 0;
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<TimewarpSphere> spheres;
    std::vector<SphereState> states;
    randomGas(20, Vec3::Zero(), spheres, states);
    TimewarpSettings settings;
    settings.max_step = 1.0;
    settings.max_travel = uniform(0.5, 2.0);
    INFO("trial " << trial << ": a dense gas of 20 spheres, max_step 1 s, max_travel " << settings.max_travel << " m, run to 2 s");
    TimewarpWorld world(spheres, states, settings);
    world.run(2.0);
    rollbacks += world.stats().rollbacks;
    CHECK(world.largestLag() == 0.0);
    for (int k = 0; k < world.size(); ++k) CHECK(world.state(k).t == 2.0);
  }
  CHECK(rollbacks > 0);  // else the scenes would not test the rule
  // Fixed: the chain scene, where the ball's impact takes sphere 2 back through sphere 1
  std::vector<TimewarpSphere> spheres;
  std::vector<SphereState> states;
  chainScene(0.0, spheres, states);
  TimewarpSettings settings;
  settings.max_step = 1.0;
  settings.max_travel = 0.1;
  TimewarpWorld world(spheres, states, settings);
  world.run(2.0);
  CHECK(world.largestLag() == 0.0);
}

TEST_CASE("timewarp: degenerate scenes: none, one, touching and separating, equal times", "[lab05][pts=1][sec=9]") {
  // Zero bodies: nothing to do, the clock still reaches t_end
  TimewarpWorld empty({}, {});
  empty.run(1.0);
  CHECK(empty.time() == 1.0);
  CHECK(empty.events().empty());
  // One body under gravity: exactly its free flight (round-off of a few products)
  TimewarpSettings falling;
  falling.gravity = Vec3(0.0, 0.0, -9.81);
  SphereState start;
  start.x = randomVec3(1.0);
  start.v = randomVec3(2.0);
  TimewarpWorld one({TimewarpSphere{}}, {start}, falling);
  one.run(1.5);
  CHECK(one.state(0).x.isApprox(start.x + 1.5 * start.v + 0.5 * 2.25 * falling.gravity, 1e-12));
  // Touching at t = 0 and separating: no collision, both fly free
  SphereState left, right;
  left.v = Vec3(-1, 0, 0);
  right.x = Vec3(0.2, 0, 0);
  right.v = Vec3(1, 0, 0);
  {
    INFO("two 1 kg spheres of radius 0.1 m at x = 0 and 0.2 m (touching), separating at 1 m/s each: "
         "expected no event, sphere 1 at x = 1.2 m after 1 s");
    TimewarpWorld apart({TimewarpSphere{}, TimewarpSphere{}}, {left, right});
    apart.run(1.0);
    CHECK(apart.events().empty());
    CHECK(apart.state(1).x.isApprox(Vec3(1.2, 0, 0), 1e-15));
  }
  // Touching at t = 0 and approaching: a collision at exactly 0
  left.v = Vec3(1, 0, 0);
  right.v = Vec3(-1, 0, 0);
  {
    INFO("two 1 kg spheres of radius 0.1 m at x = 0 and 0.2 m (touching), approaching at 1 m/s each: "
         "expected one event, at t = 0");
    TimewarpWorld touching({TimewarpSphere{}, TimewarpSphere{}}, {left, right});
    touching.run(1.0);
    REQUIRE(touching.events().size() == 1);
    CHECK(touching.events()[0].t == 0.0);
  }
  // Two pairs that collide at the same time, 0.4 s (gap 0.4 m closed at 1 m/s), with the second
  // pair listed first: both resolved, equal times
  std::vector<SphereState> four(4);
  four[0].x = Vec3(0, 5, 0);
  four[0].v = Vec3(0.5, 0, 0);
  four[1].x = Vec3(0.6, 5, 0);
  four[1].v = Vec3(-0.5, 0, 0);
  four[2].x = Vec3(0, 0, 0);
  four[2].v = Vec3(1, 0, 0);
  four[3].x = Vec3(0.6, 0, 0);
  INFO("two pairs of spheres of radius 0.1 m, 0.6 m apart, closing at 1 m/s: expected two events, both at t = 0.4 s");
  TimewarpWorld pairs(std::vector<TimewarpSphere>(4), four);
  pairs.run(1.0);
  REQUIRE(pairs.events().size() == 2);
  // Gap over speed in binary: round-off only
  CHECK(pairs.events()[0].t == Approx(0.4).epsilon(1e-14));
  CHECK(pairs.events()[1].t == Approx(0.4).epsilon(1e-14));
  CHECK(pairs.state(3).v.isApprox(Vec3(1, 0, 0), 1e-14));
  CHECK(pairs.state(0).v.isApprox(Vec3(-0.5, 0, 0), 1e-14));
  // Running to the current time does nothing
  pairs.run(1.0);
  CHECK(pairs.events().size() == 2);
}

TEST_CASE("timewarp: bad input is refused, naming it", "[lab05][pts=1][sec=9]") {
  const Vec3 o = Vec3::Zero(), nan(std::nan(""), 0.0, 0.0);
  CHECK_THROWS_WITH(sphereImpactTime(o, o, -0.1, Vec3(1, 0, 0), o, 0.1), Contains("radius r_a"));
  CHECK_THROWS_WITH(sphereImpactTime(o, o, 0.1, Vec3(1, 0, 0), o, 0.0), Contains("radius r_b"));
  CHECK_THROWS_WITH(sphereImpactTime(o, nan, 0.1, Vec3(1, 0, 0), o, 0.1), Contains("velocity v_a"));
  CHECK_THROWS_WITH(sphereImpactTime(o, o, 0.1, nan, o, 0.1), Contains("position x_b"));
  CHECK_THROWS_WITH(rollbackTimes({}, -1, {}, 0.0), Contains("body_count"));
  CHECK_THROWS_WITH(rollbackTimes({}, 2, {2}, 0.0), Contains("seed 0"));
  CHECK_THROWS_WITH(rollbackTimes({}, 2, {0}, std::nan("")), Contains("t_c"));
  CHECK_THROWS_WITH(rollbackTimes({{0.5, 0, 1, 1.0}, {0.2, 0, 1, 1.0}}, 2, {0}, 0.1), Contains("event 1"));
  CHECK_THROWS_WITH(rollbackTimes({{0.5, 0, 3, 1.0}}, 2, {0}, 0.1), Contains("event 0"));
  CHECK_THROWS_WITH(rollbackTimes({{std::nan(""), 0, 1, 1.0}}, 2, {0}, 0.1), Contains("event 0"));
  Vec3 v_a(1, 0, 0), v_b = o;
  CHECK_THROWS_WITH(resolveSphereImpact(o, v_a, 0.0, Vec3(0.2, 0, 0), v_b, 1.0, 0.1, 1.0), Contains("mass m_a"));
  CHECK_THROWS_WITH(resolveSphereImpact(o, v_a, 1.0, o, v_b, 1.0, 0.1, 1.0), Contains("centres"));
  CHECK_THROWS_WITH(resolveSphereImpact(o, v_a, 1.0, Vec3(0.2, 0, 0), v_b, 1.0, 0.1, 1.5), Contains("epsilon"));
  CHECK(v_a == Vec3(1, 0, 0));  // nothing changed by a refused impact
  // The scheduler: a negative radius, a NaN velocity, an end time before now
  SphereState s;
  CHECK_THROWS_WITH(TimewarpWorld({TimewarpSphere{1.0, -0.1, 1.0}}, {s}), Contains("sphere 0 radius"));
  s.v = nan;
  CHECK_THROWS_WITH(TimewarpWorld({TimewarpSphere{}}, {s}), Contains("sphere 0 velocity"));
  std::vector<TimewarpSphere> spheres;
  std::vector<SphereState> states;
  fastBallThroughRow(3, 0.1, 2.0, 0, 1u, spheres, states);
  INFO("a valid scene (a ball at 2 m/s through a row of 3 spheres 0.1 m apart), run to 0.5 s, then to 0.25 s and NaN");
  TimewarpWorld world(spheres, states);
  world.run(0.5);
  CHECK_THROWS_WITH(world.run(0.25), Contains("t_end"));
  CHECK_THROWS_WITH(world.run(std::nan("")), Contains("t_end"));
  CHECK(world.time() == 0.5);
}
