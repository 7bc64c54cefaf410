// Lab 5, section 9 (framework): the Timewarp scheduler, its synchronous baseline and the sparse
// scene. The student writes the impact time, the rollback rule and the impulse (labs/timewarp.cpp).
#include "physlab/timewarp.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <random>
#include <string>
#include <utility>

#include "physlab/error.hpp"

namespace physlab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void validateScene(const std::vector<TimewarpSphere>& spheres, const std::vector<SphereState>& states) {
  if (spheres.size() != states.size()) {
    throw InvalidInput("timewarp scene has " + std::to_string(spheres.size()) + " spheres but " +
                       std::to_string(states.size()) + " states");
  }
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const std::string name = "timewarp sphere " + std::to_string(i);
    requirePositive(spheres[i].mass, name + " mass");
    requirePositive(spheres[i].radius, name + " radius");
    requireInRange(spheres[i].epsilon, 0.0, 1.0, name + " restitution epsilon");
    requireFinite(states[i].x, name + " position x");
    requireFinite(states[i].v, name + " velocity v");
    requireFinite(Vec3(states[i].t, 0.0, 0.0), name + " time t");
    if (states[i].t != states.front().t) {
      throw InvalidInput(name + " time t must equal body 0's (every body starts at the same time)");
    }
  }
}

// The entry of a history: a saved state and the body it met there (-1: the start).
int lastAtOrBefore(const std::vector<SphereState>& history, double t) {
  const auto it = std::upper_bound(history.begin(), history.end(), t,
                                   [](double value, const SphereState& s) { return value < s.t; });
  return static_cast<int>(it - history.begin()) - 1;
}

}  // namespace

SphereState ballistic(const SphereState& state, const Vec3& gravity, double t) {
  const double s = t - state.t;
  SphereState out;
  out.t = t;
  out.x = state.x + s * state.v + (0.5 * s * s) * gravity;
  out.v = state.v + s * gravity;
  return out;
}

TimewarpWorld::TimewarpWorld(std::vector<TimewarpSphere> spheres, std::vector<SphereState> states,
                             TimewarpSettings settings)
    : spheres_(std::move(spheres)), settings_(settings) {
  validateScene(spheres_, states);
  requireFinite(settings_.gravity, "timewarp settings gravity");
  requirePositive(settings_.max_step, "timewarp settings max_step");
  requirePositive(settings_.max_travel, "timewarp settings max_travel");
  time_ = states.empty() ? 0.0 : states.front().t;
  for (const SphereState& s : states) {
    history_.push_back({s});
    partner_.push_back({-1});
    local_.push_back(s.t);
  }
}

SphereState TimewarpWorld::state(int i) const {
  if (i < 0 || i >= size()) throw InvalidInput("timewarp body index " + std::to_string(i) + " is not a body");
  return stateAt(i, local_[i]);
}

SphereState TimewarpWorld::stateAt(int i, double t) const {
  if (i < 0 || i >= size()) throw InvalidInput("timewarp body index " + std::to_string(i) + " is not a body");
  const int k = std::max(0, lastAtOrBefore(history_[i], t));
  return ballistic(history_[i][k], settings_.gravity, t);
}

void TimewarpWorld::run(double t_end) {
  if (!(std::isfinite(t_end) && t_end >= time_)) {
    throw InvalidInput("timewarp run end time t_end must be finite and not before the current time " +
                       std::to_string(time_) + ", got " + std::to_string(t_end));
  }
  // Smallest local time first, ties by index; entries whose time a body has left are stale
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int i = 0; i < size(); ++i) queue.push({local_[i], i});
  while (!queue.empty()) {
    const auto [t, i] = queue.top();
    queue.pop();
    if (t != local_[i] || t >= t_end) continue;
    stepBody(i, t_end);
    if (observer_) observer_(*this);
    // The stepped body always goes back in (an impact at the very start of its step leaves its
    // clock where it was), and so does every body whose clock a rollback moved
    for (const int k : moved_) queue.push({local_[k], k});
  }
  time_ = t_end;
}

void TimewarpWorld::stepBody(int i, double t_end) {
  ++stats_.steps;
  moved_.assign(1, i);
  const double t0 = local_[i];
  const SphereState s_i = stateAt(i, t0);
  // The body's own step: at most max_step, and short enough to move at most max_travel
  double h = settings_.max_step;
  const double speed = s_i.v.norm();
  if (speed * h > settings_.max_travel) h = settings_.max_travel / speed;
  const double t1 = std::min(t0 + h, t_end);

  // The earliest impact with any body over the window both have computed
  double t_c = kInf;
  int partner = -1;
  for (int j = 0; j < size(); ++j) {
    if (j == i) continue;
    const double hi = std::min(t1, local_[j]);
    if (hi < t0) continue;
    const std::vector<SphereState>& hist = history_[j];
    int k = lastAtOrBefore(hist, t0);
    double s = t0;
    while (true) {
      const double next = k + 1 < static_cast<int>(hist.size()) ? hist[k + 1].t : kInf;
      const double e = std::min(next, hi);
      // At the step's start body i is where it is (no flight to compute): most windows have one piece
      const SphereState a = s == t0 ? s_i : ballistic(s_i, settings_.gravity, s);
      const SphereState b = ballistic(hist[k], settings_.gravity, s);
      ++stats_.pair_checks;
      const double dt = sphereImpactTime(a.x, a.v, spheres_[i].radius, b.x, b.v, spheres_[j].radius);
      if (s + dt <= e) {
        if (s + dt < t_c) {
          t_c = s + dt;
          partner = j;
        }
        break;
      }
      if (next >= hi) break;
      s = next;
      k = lastAtOrBefore(hist, s);
    }
  }
  if (partner < 0) {
    local_[i] = t1;
    return;
  }

  // Roll back the partner (when it ran past t_c) and every body that met a rolled-back body since
  ++stats_.events;
  const std::vector<double> r = rollbackTimes(events_, size(), {i, partner}, t_c);
  rollBack(r, t_c, i, partner);
  local_[i] = t_c;
  local_[partner] = t_c;
  moved_.push_back(partner);

  // Resolve the impact at t_c with the lower index as A
  const int a = std::min(i, partner), b = std::max(i, partner);
  SphereState s_a = stateAt(a, t_c), s_b = stateAt(b, t_c);
  const double epsilon = std::min(spheres_[a].epsilon, spheres_[b].epsilon);
  const double j = resolveSphereImpact(s_a.x, s_a.v, spheres_[a].mass, s_b.x, s_b.v, spheres_[b].mass,
                                       spheres_[b].radius, epsilon);
  // An impact the student's functions found but did not push apart would be found again at once,
  // for ever: refuse it by name instead of hanging
  const double v_rel_after = (s_a.x - s_b.x).normalized().dot(s_a.v - s_b.v);
  if ((!(j > 0.0) && t_c == t0) || v_rel_after < -1e-9 * (1.0 + s_a.v.norm() + s_b.v.norm())) {
    throw NumericalFailure("timewarp: spheres " + std::to_string(a) + " and " + std::to_string(b) + " at t = " +
                           std::to_string(t_c) + ": sphereImpactTime() found an impact that resolveSphereImpact() (j = " +
                           std::to_string(j) + ", v_rel after = " + std::to_string(v_rel_after) +
                           ") did not push apart; the scheduler would find it again for ever");
  }
  if (j > 0.0) {
    history_[a].push_back(s_a);
    partner_[a].push_back(b);
    history_[b].push_back(s_b);
    partner_[b].push_back(a);
    const TimewarpEvent event{t_c, a, b, j};
    const auto at = std::upper_bound(events_.begin(), events_.end(), t_c,
                                     [](double value, const TimewarpEvent& ev) { return value < ev.t; });
    events_.insert(at, event);
  }
  checkLag();
}

void TimewarpWorld::rollBack(const std::vector<double>& r, double t_c, int i, int partner) {
  TimewarpRollback record;
  record.t_c = t_c;
  record.a = std::min(i, partner);
  record.b = std::max(i, partner);
  // Undo every event after the rollback time of one of its bodies, in the log and the histories
  const auto undone = [&r](double t, int a, int b) { return t > r[a] || t > r[b]; };
  const std::size_t kept_before = events_.size();
  events_.erase(std::remove_if(events_.begin(), events_.end(),
                               [&undone](const TimewarpEvent& ev) { return undone(ev.t, ev.a, ev.b); }),
                events_.end());
  stats_.events_undone += static_cast<long>(kept_before - events_.size());
  for (int k = 0; k < size(); ++k) {
    if (std::isinf(r[k])) continue;
    std::vector<SphereState>& hist = history_[k];
    std::vector<int>& with = partner_[k];
    std::size_t keep = 1;  // the start always stays
    for (std::size_t e = 1; e < hist.size(); ++e) {
      if (undone(hist[e].t, k, with[e])) continue;
      hist[keep] = hist[e];
      with[keep] = with[e];
      ++keep;
    }
    // A body rolls back when its clock goes back or a collision of its past is undone
    if (r[k] < local_[k] || keep < hist.size()) {
      record.bodies.push_back(k);
      record.times.push_back(std::min(local_[k], r[k]));
    }
    hist.resize(keep);
    with.resize(keep);
    if (r[k] < local_[k]) {
      local_[k] = r[k];
      moved_.push_back(k);
    }
  }
  if (!record.bodies.empty()) {
    ++stats_.rollbacks;
    stats_.bodies_rolled_back += static_cast<long>(record.bodies.size());
    rollbacks_.push_back(std::move(record));
  }
}

void TimewarpWorld::checkLag() {
  // A body that used another's state at time t (they met there) needs that body at t or later
  for (int k = 0; k < size(); ++k) {
    for (std::size_t e = 1; e < history_[k].size(); ++e) {
      largest_lag_ = std::max(largest_lag_, history_[k][e].t - local_[partner_[k][e]]);
    }
  }
}

std::vector<SphereState> runSynchronousToi(const std::vector<TimewarpSphere>& spheres, std::vector<SphereState> states,
                                           const Vec3& gravity, double h, double t_end,
                                           std::vector<TimewarpEvent>& events, SynchronousStats& stats) {
  validateScene(spheres, states);
  requireFinite(gravity, "synchronous gravity");
  requirePositive(h, "synchronous step h");
  const double t_start = states.empty() ? 0.0 : states.front().t;
  if (!(std::isfinite(t_end) && t_end >= t_start)) {
    throw InvalidInput("synchronous end time t_end must be finite and not before the start time");
  }
  events.clear();
  const int n = static_cast<int>(spheres.size());
  const auto advanceAll = [&](double t) {
    for (SphereState& s : states) s = ballistic(s, gravity, t);
    stats.body_updates += n;
  };
  double t = t_start;
  while (t < t_end) {
    const double step_end = std::min(t + h, t_end);
    ++stats.steps;
    // Sub-step from impact to impact: every body goes to each one
    while (true) {
      double t_c = kInf;
      int a = -1, b = -1;
      for (int p = 0; p < n; ++p) {
        for (int q = p + 1; q < n; ++q) {
          ++stats.pair_checks;
          const double dt = sphereImpactTime(states[p].x, states[p].v, spheres[p].radius, states[q].x, states[q].v,
                                             spheres[q].radius);
          if (t + dt <= step_end && t + dt < t_c) {
            t_c = t + dt;
            a = p;
            b = q;
          }
        }
      }
      if (a < 0) break;
      advanceAll(t_c);
      t = t_c;
      const double epsilon = std::min(spheres[a].epsilon, spheres[b].epsilon);
      const double j = resolveSphereImpact(states[a].x, states[a].v, spheres[a].mass, states[b].x, states[b].v,
                                           spheres[b].mass, spheres[b].radius, epsilon);
      ++stats.events;
      if (j > 0.0) events.push_back({t_c, a, b, j});
    }
    advanceAll(step_end);
    t = step_end;
  }
  return states;
}

void fastBallThroughRow(int row, double gap, double v0, int background, unsigned seed,
                        std::vector<TimewarpSphere>& spheres, std::vector<SphereState>& states) {
  if (row < 0) throw InvalidInput("fastBallThroughRow row must be non-negative, got " + std::to_string(row));
  if (background < 0) {
    throw InvalidInput("fastBallThroughRow background must be non-negative, got " + std::to_string(background));
  }
  requireNonNegative(gap, "fastBallThroughRow gap");
  requirePositive(v0, "fastBallThroughRow speed v0");
  const double r = 0.1;
  spheres.assign(static_cast<std::size_t>(1 + row + background), TimewarpSphere{1.0, r, 1.0});
  states.assign(spheres.size(), SphereState{});
  states[0].v = Vec3(v0, 0.0, 0.0);
  for (int k = 1; k <= row; ++k) states[k].x = Vec3(1.0 + (k - 1) * (2.0 * r + gap), 0.0, 0.0);
  // Background: 2.5 m apart from y = 3 m on, at most 0.1 m/s, so that in 10 s each moves at most
  // 1 m and no two come within 2 r (2.5 - 2 > 0.2) nor near the row (3 - 1 > 0.2)
  std::mt19937 engine(seed);
  std::uniform_real_distribution<double> speed(-0.1 / std::sqrt(3.0), 0.1 / std::sqrt(3.0));
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(background))));
  for (int k = 0; k < background; ++k) {
    SphereState& s = states[1 + row + k];
    s.x = Vec3(2.5 * (k % side), 3.0 + 2.5 * (k / side), 0.0);
    s.v = Vec3(speed(engine), speed(engine), speed(engine));
  }
}

}  // namespace physlab
