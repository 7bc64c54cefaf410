// Lab 5 framework: the World's step, one call per phase of the lecture's pipeline, with input
// validation, diagnostics and per-phase timers. The response itself is the students' code.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <ostream>
#include <sstream>

#include "physlab/error.hpp"
#include "physlab/rigid.hpp"
#include "physlab/world.hpp"

namespace physlab {

namespace {

// Adds the seconds since `start` to `counter` when it goes out of scope.
class PhaseTimer {
 public:
  explicit PhaseTimer(double& counter) : counter_(counter), start_(std::chrono::steady_clock::now()) {}
  ~PhaseTimer() { counter_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  double& counter_;
  std::chrono::steady_clock::time_point start_;
};

bool isPlane(const BodyDescription& body) { return std::holds_alternative<Plane>(body.shape); }

// Continuous collision (section 10): a pair is fast when their points may move apart or together
// by more than their inner radii combined in a step (Lab 4's sampling bound). A slower pair,
// passing through each other, overlaps at some step before their centres pass, where the narrow
// phase finds it and pushes them back the way they came. A body is swept when its points may move
// more than its own inner radius: of a fast pair one body always may (the two travels add up to
// more than the two radii), and its sweep takes the pair
// The sweep stops this close to the body it would hit [m] (conservative advancement's tolerance)
constexpr double kSweepTolerance = 1e-4;
// ... and a stopped body moves on into it by this much, above the tolerance, so that the next
// step finds the contact and answers it (position correction removes the rest) [m]
constexpr double kSweepOverlap = 1e-3;

void validateBody(const BodyDescription& body, int i) {
  const std::string name = "body " + std::to_string(i);
  if (!(std::isfinite(body.epsilon) && body.epsilon >= 0.0 && body.epsilon <= 1.0)) {
    throw InvalidInput(name + " restitution epsilon must be in [0, 1], got " + std::to_string(body.epsilon));
  }
  requireNonNegative(body.mu, name + " friction mu");
  if (isPlane(body) && !body.fixed) throw InvalidInput(name + " is a plane and must be fixed");
  if (!body.fixed) {
    requirePositive(body.mass, name + " mass");
    RigidBody(body.mass, body.inertia_body);  // validates the inertia tensor (InvalidInput)
  }
}

void validateState(const BodyState& state, int i) {
  const std::string name = "body " + std::to_string(i) + " state";
  requireFinite(state.x, name + " position x");
  requireFinite(state.q.coeffs(), name + " orientation q");
  if (state.q.norm() == 0.0) throw InvalidInput(name + " orientation quaternion is zero");
  requireFinite(state.P, name + " linear momentum P");
  requireFinite(state.L, name + " angular momentum L");
}

void validateSettings(const Settings& s) {
  if (s.iterations < 1) throw InvalidInput("settings iterations must be at least 1");
  if (s.shock_response_iterations < 1) throw InvalidInput("settings shock_response_iterations must be at least 1");
  requireNonNegative(s.tolerance, "settings tolerance");
  requireNonNegative(s.restitution_threshold, "settings restitution threshold");
  requireFinite(s.gravity, "settings gravity");
  if (!(s.position_correction >= 0.0 && s.position_correction <= 1.0)) {
    throw InvalidInput("settings position correction must be in [0, 1], got " + std::to_string(s.position_correction));
  }
  requireNonNegative(s.slop, "settings slop");
  if (s.correction_sweeps < 1) {
    throw InvalidInput("settings correction sweeps must be at least 1, got " + std::to_string(s.correction_sweeps));
  }
  requirePositive(s.penalty_k, "settings penalty stiffness k");
  requireNonNegative(s.penalty_d, "settings penalty damping d");
  requireNonNegative(s.sleep_linear, "settings sleep_linear");
  requireNonNegative(s.sleep_angular, "settings sleep_angular");
  requireNonNegative(s.sleep_time, "settings sleep_time");
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Descriptions and settings

BodyDescription BodyDescription::sphere(double mass, double radius, double epsilon, double mu) {
  BodyDescription body;
  body.shape = Sphere(radius);
  body.mass = mass;
  body.inertia_body = sphereInertia(mass, radius);
  body.epsilon = epsilon;
  body.mu = mu;
  return body;
}

BodyDescription BodyDescription::box(double mass, const Vec3& half_extents, double epsilon, double mu) {
  BodyDescription body;
  body.shape = Box(half_extents);
  body.mass = mass;
  body.inertia_body = boxInertia(mass, 2.0 * half_extents);
  body.epsilon = epsilon;
  body.mu = mu;
  return body;
}

BodyDescription BodyDescription::plane(const Vec3& normal, double offset, double epsilon, double mu) {
  BodyDescription body;
  body.shape = Plane(normal, offset);
  body.epsilon = epsilon;
  body.mu = mu;
  body.fixed = true;
  return body;
}

BodyDescription BodyDescription::fixedBox(const Vec3& half_extents, double epsilon, double mu) {
  BodyDescription body = box(1.0, half_extents, epsilon, mu);
  body.fixed = true;
  return body;
}

const char* responseMethodName(ResponseMethod method) {
  switch (method) {
    case ResponseMethod::Sequential: return "sequential";
    case ResponseMethod::Simultaneous: return "simultaneous";
    case ResponseMethod::Penalty: return "penalty";
  }
  return "unknown";
}

std::string Settings::toString() const {
  std::ostringstream out;
  out << "method=" << responseMethodName(method) << " iterations=" << iterations << " tolerance=" << tolerance
      << " restitution_threshold=" << restitution_threshold << " warm_start=" << (warm_start ? "on" : "off")
      << " gravity=(" << gravity.x() << ", " << gravity.y() << ", " << gravity.z() << ")"
      << " penalty_k=" << penalty_k << " penalty_d=" << penalty_d
      << " broad_phase=" << (use_broad_phase ? "incremental tree" : "all pairs")
      << " position_correction=" << position_correction << " slop=" << slop
      << " correction_sweeps=" << correction_sweeps << " continuous=" << (continuous ? "on" : "off")
      << " shock_propagation=" << (shock_propagation ? "on" : "off");
  if (shock_propagation) out << " shock_response_iterations=" << shock_response_iterations;
  out << " islands=" << (islands ? "on" : "off") << " sleeping=" << (sleeping ? "on" : "off");
  if (sleeping) out << " sleep_linear=" << sleep_linear << " sleep_angular=" << sleep_angular << " sleep_time=" << sleep_time;
  return out.str();
}

std::ostream& operator<<(std::ostream& out, const Settings& settings) { return out << settings.toString(); }

// ---------------------------------------------------------------------------------------------
// World

World::World(Scene scene, Settings settings, std::shared_ptr<RestingContactSolver> resting)
    : bodies_(std::move(scene.bodies)),
      states_(std::move(scene.states)),
      settings_(settings),
      resting_solver_(std::move(resting)) {
  requireSize(static_cast<Index>(states_.size()), static_cast<Index>(bodies_.size()), "world states");
  validateSettings(settings_);
  // With shock propagation after it, the response stops sooner where the pass solves every point
  // again (islands resting on a fixed body, without a resting solver: with one, the pass leaves
  // the colliding points the impulses answered as they were)
  response_settings_ = settings_;
  if (shockPropagates() && !resting_solver_) {
    response_settings_.iterations = std::min(settings_.iterations, settings_.shock_response_iterations);
  }
  for (int i = 0; i < static_cast<int>(bodies_.size()); ++i) {
    validateBody(bodies_[i], i);
    validateState(states_[i], i);
    states_[i].q.normalize();
    if (bodies_[i].fixed) states_[i].P = states_[i].L = Vec3::Zero();
    (isPlane(bodies_[i]) ? planes_ : bounded_).push_back(i);
    inv_inertia_body_.push_back(bodies_[i].fixed ? Mat3(Mat3::Zero()) : Mat3(bodies_[i].inertia_body.inverse()));
    radius_.push_back(isPlane(bodies_[i]) ? 0.0 : boundingRadius(bodies_[i].shape));
    inner_.push_back(isPlane(bodies_[i]) ? 0.0 : innerRadius(bodies_[i].shape));
  }
  broad_phase_ = std::make_unique<IncrementalBroadPhase>();
  const std::size_t n = bodies_.size();
  parent_.resize(n);
  tree_size_.resize(n);
  island_of_.assign(n, -1);
  local_.assign(n, -1);
  still_time_.assign(n, 0.0);
  asleep_.assign(n, 0);
  sleep_label_.assign(n, -1);
}

BodyState BodyState::moving(const BodyDescription& body, const Vec3& x, const Quat& q, const Vec3& v,
                            const Vec3& omega) {
  requireFinite(x, "moving state position x");
  requireFinite(q.coeffs(), "moving state orientation q");
  if (q.norm() == 0.0) throw InvalidInput("moving state orientation quaternion is zero");
  requireFinite(v, "moving state velocity v");
  requireFinite(omega, "moving state angular velocity omega");
  BodyState state;
  state.x = x;
  state.q = q.normalized();
  if (!body.fixed) {
    const Mat3 R = state.q.toRotationMatrix();
    state.P = body.mass * v;
    state.L = R * body.inertia_body * R.transpose() * omega;
  }
  return state;
}

void World::requireBody(int i) const {
  if (i < 0 || i >= static_cast<int>(states_.size())) {
    throw InvalidInput("body index " + std::to_string(i) + " out of range: the world has " +
                       std::to_string(states_.size()) + " bodies");
  }
}

void World::setState(int i, const BodyState& state) {
  requireBody(i);
  validateState(state, i);
  states_[i] = state;
  states_[i].q.normalize();
  if (bodies_[i].fixed) states_[i].P = states_[i].L = Vec3::Zero();
  // A body put somewhere else, or set moving, is no longer still
  if (asleep_[i]) wake(i);
  still_time_[i] = 0.0;
}

bool World::asleep(int i) const {
  requireBody(i);
  return asleep_[i] != 0;
}

std::string World::describe() const {
  if (!resting_solver_) return settings_.toString();
  // Only the settings that act: the World's own, the impulse method's only when it answers the
  // colliding points (a bouncing solver answers every point), the position correction's only when
  // it is on; then the resting-contact solver's
  const Settings& s = settings_;
  std::ostringstream out;
  out << "gravity=(" << s.gravity.x() << ", " << s.gravity.y() << ", " << s.gravity.z() << ")"
      << " broad_phase=" << (s.use_broad_phase ? "incremental tree" : "all pairs")
      << " continuous=" << (s.continuous ? "on" : "off")
      << " shock_propagation=" << (s.shock_propagation ? "on" : "off") << " islands=" << (s.islands ? "on" : "off")
      << " sleeping=" << (s.sleeping ? "on" : "off");
  if (s.sleeping) {
    out << " sleep_linear=" << s.sleep_linear << " sleep_angular=" << s.sleep_angular << " sleep_time=" << s.sleep_time;
  }
  if (s.position_correction > 0.0) {
    out << " position_correction=" << s.position_correction << " slop=" << s.slop
        << " correction_sweeps=" << s.correction_sweeps;
  }
  if (resting_solver_->bounces()) {
    out << " every point (bounces too): ";
  } else {
    out << " method=" << responseMethodName(s.method) << " iterations=" << s.iterations
        << " restitution_threshold=" << s.restitution_threshold << " warm_start=" << (s.warm_start ? "on" : "off")
        << " colliding points: impulses, resting: ";
  }
  return out.str() + resting_solver_->describe();
}

Vec3 World::velocity(int i) const {
  requireBody(i);
  return bodies_[i].fixed ? Vec3::Zero() : Vec3(states_[i].P / bodies_[i].mass);
}

Vec3 World::angularVelocity(int i) const {
  requireBody(i);
  if (bodies_[i].fixed) return Vec3::Zero();
  const Mat3 R = states_[i].q.toRotationMatrix();
  return R * inv_inertia_body_[i] * R.transpose() * states_[i].L;
}

double World::depth(int i, int j) const {
  requireBody(i);
  requireBody(j);
  double deepest = 0.0;
  for (const Contact& c : contacts_) {
    if ((c.a == i && c.b == j) || (c.a == j && c.b == i)) deepest = std::max(deepest, c.depth);
  }
  return deepest;
}

void World::step(double h) {
  requirePositive(h, "step size h");
  // Candidate pairs whose bounding boxes overlap (not two asleep), plus every awake moving body
  // against every plane
  findCandidatePairs();
  // A sleeping island that an awake body touches wakes (sleeping on); the candidates are found
  // again with it awake, and it may touch another sleeping island in turn
  while (wakeTouchedIslands()) findCandidatePairs();
  // Contact manifolds of the candidates with an awake moving body, as contact points
  computeContacts();
  // v_rel at each point with the velocities that brought the bodies together: colliding,
  // resting or separating
  classifyContacts();
  // The moving bodies connected through contacts, each island solved on its own
  findIslands();
  // Gravity: v += g h on every moving body
  applyForces(h);
  // Impulses (or penalty forces) that stop the approach
  respond(h);
  // Positions and orientations with the new velocities
  integrate(h);
  // Overlap the velocities cannot remove: move and turn the bodies apart, point by point
  correctPositions(h);
  // Each body's time still; an island still long enough falls asleep (sleeping on)
  updateSleep(h);
  // Energies, momenta, penetration
  computeDiagnostics();
  time_ += h;
}

void World::applyForces(double h) {
  if (settings_.gravity.isZero()) return;  // a scene without gravity skips the phase
  PhaseTimer timer(times_.forces);
  const Vec3 dv = h * settings_.gravity;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i].fixed || asleep_[i]) continue;
    states_[i].P += bodies_[i].mass * dv;
    // The solver's copy of the velocities, loaded by classifyContacts(), gets the same change
    if (!contacts_.empty()) contact_bodies_[i].v += dv;
  }
}

void World::listSleepers() {
  sleepers_changed_ = false;
  listed_.clear();
  sleepers_.clear();
  for (const int i : bounded_) {
    if (asleep_[i]) {
      const BodyState& s = states_[i];
      sleepers_.push_back({aabb(bodies_[i].shape, Pose{s.x, s.q}), 0.0, i});
    } else {
      listed_.push_back(i);
    }
  }
  std::sort(sleepers_.begin(), sleepers_.end(), [](const SleeperBox& x, const SleeperBox& y) {
    return x.box.min.x() < y.box.min.x() || (x.box.min.x() == y.box.min.x() && x.body < y.body);
  });
  double reach = -std::numeric_limits<double>::infinity();
  for (SleeperBox& sleeper : sleepers_) sleeper.reach = reach = std::max(reach, sleeper.box.max.x());
  // Box k of the broad phase is another body now: it starts again from the listed bodies
  broad_phase_->clear();
}

template <class Visit>
void World::querySleepers(const Aabb& box, Visit&& visit) const {
  // The entries before the first whose running largest max x reaches box's min x all end short of
  // it; from there, those that start at or before box's max x
  auto it = std::partition_point(sleepers_.begin(), sleepers_.end(),
                                 [&](const SleeperBox& sleeper) { return sleeper.reach < box.min.x(); });
  for (; it != sleepers_.end() && it->box.min.x() <= box.max.x(); ++it) {
    if (overlaps(it->box, box)) visit(it->body);
  }
}

void World::findCandidatePairs() {
  PhaseTimer timer(times_.broad_phase);
  pairs_.clear();
  if (sleepers_changed_) listSleepers();
  if (settings_.use_broad_phase) {
    // The bodies not asleep go to the incremental tree; each awake moving one is looked up among
    // the sleepers' boxes, which stay where they are
    const int n = static_cast<int>(listed_.size());
    boxes_.resize(n);
    for (int k = 0; k < n; ++k) {
      const BodyState& s = states_[listed_[k]];
      boxes_[k] = aabb(bodies_[listed_[k]].shape, Pose{s.x, s.q});
    }
    if (n >= 2) {
      broad_phase_->findPairs(boxes_, found_);
      for (const BoxPair& pair : found_) pairs_.push_back({listed_[pair.first], listed_[pair.second]});
    }
    if (!sleepers_.empty()) {
      const std::size_t listed_pairs = pairs_.size();
      for (int k = 0; k < n; ++k) {
        const int body = listed_[k];
        if (bodies_[body].fixed) continue;
        querySleepers(boxes_[k],
                      [&](int sleeper) { pairs_.push_back({std::min(body, sleeper), std::max(body, sleeper)}); });
      }
      // In the order of the pairs of every bounded body, as without sleepers
      if (pairs_.size() > listed_pairs) std::sort(pairs_.begin(), pairs_.end());
    }
  } else {
    const int n = static_cast<int>(bounded_.size());
    for (int k = 0; k < n; ++k) {
      for (int l = k + 1; l < n; ++l) pairs_.push_back({bounded_[k], bounded_[l]});
    }
  }
  // Two fixed bodies never need a response
  pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(),
                              [&](const BoxPair& p) { return bodies_[p.first].fixed && bodies_[p.second].fixed; }),
               pairs_.end());
  // A sleeping body stands still on a plane that stands still: nothing to find
  for (int plane : planes_) {
    for (int body : bounded_) {
      if (awakeMoving(body)) pairs_.push_back({body, plane});
    }
  }
}

void World::computeContacts() {
  if (pairs_.empty() && contacts_.empty()) return;  // nothing can touch: skip the phase
  PhaseTimer timer(times_.narrow_phase);
  // Keep the last step's impulses by (A, B, feature id) for warm starting
  last_impulses_.clear();
  last_pairs_.clear();
  for (const Contact& c : contacts_) {
    const std::uint64_t key = pairKey(c.a, c.b);
    const int k = static_cast<int>(last_impulses_.size());
    if (last_pairs_.empty() || last_pairs_.back().key != key) last_pairs_.push_back({key, k, k});
    ++last_pairs_.back().end;
    last_impulses_.push_back({c.id, c.p, c.j, c.j_t});
  }
  // The contacts a woken island had when it fell asleep warm start it (a pair may come twice:
  // lastImpulse() searches every run of its key)
  if (!sleeping_contacts_.empty()) {
    for (const Contact& c : sleeping_contacts_) {
      if (asleep_[c.a] || asleep_[c.b]) continue;
      const std::uint64_t key = pairKey(c.a, c.b);
      const int k = static_cast<int>(last_impulses_.size());
      if (last_pairs_.empty() || last_pairs_.back().key != key) last_pairs_.push_back({key, k, k});
      ++last_pairs_.back().end;
      last_impulses_.push_back({c.id, c.p, c.j, c.j_t});
    }
    sleeping_contacts_.erase(std::remove_if(sleeping_contacts_.begin(), sleeping_contacts_.end(),
                                            [&](const Contact& c) { return !asleep_[c.a] && !asleep_[c.b]; }),
                             sleeping_contacts_.end());
  }
  std::sort(last_pairs_.begin(), last_pairs_.end(), [](const LastPair& x, const LastPair& y) { return x.key < y.key; });
  contacts_.clear();
  for (const BoxPair& pair : pairs_) {
    const int a = pair.first, b = pair.second;
    // Neither moves (asleep or fixed): nothing to find
    if (!awakeMoving(a) && !awakeMoving(b)) continue;
    const Manifold m = collide(bodies_[a].shape, Pose{states_[a].x, states_[a].q}, bodies_[b].shape,
                               Pose{states_[b].x, states_[b].q});
    for (int k = 0; k < m.count; ++k) {
      Contact c;
      c.a = a;
      c.b = b;
      c.p = m.points[k].position;
      c.n = m.normal;
      c.depth = m.points[k].depth;
      c.id = m.points[k].id;
      // The less bouncy body sets the pair's restitution; friction is the geometric mean
      c.epsilon = std::min(bodies_[a].epsilon, bodies_[b].epsilon);
      c.mu = std::sqrt(bodies_[a].mu * bodies_[b].mu);
      contacts_.push_back(c);
    }
  }
}

void World::loadContactBodies() {
  contact_bodies_.resize(bodies_.size());
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    ContactBody& cb = contact_bodies_[i];
    cb.x = states_[i].x;
    // A sleeping body stands still as a fixed one: a solver that moves every body (the soft
    // step) leaves it where it is
    if (bodies_[i].fixed || asleep_[i]) {
      cb.v = cb.omega = Vec3::Zero();
      cb.inv_mass = 0.0;
      cb.I_inv_world = Mat3::Zero();
    } else {
      const Mat3 R = states_[i].q.toRotationMatrix();
      cb.inv_mass = 1.0 / bodies_[i].mass;
      cb.I_inv_world = R * inv_inertia_body_[i] * R.transpose();
      cb.v = states_[i].P * cb.inv_mass;
      cb.omega = cb.I_inv_world * states_[i].L;
    }
  }
}

void World::storeContactBodies() {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i].fixed || asleep_[i]) continue;
    const Mat3 R = states_[i].q.toRotationMatrix();
    states_[i].P = bodies_[i].mass * contact_bodies_[i].v;
    states_[i].L = R * bodies_[i].inertia_body * R.transpose() * contact_bodies_[i].omega;
  }
}

void World::classifyContacts() {
  if (contacts_.empty()) return;
  PhaseTimer timer(times_.classify);
  loadContactBodies();
  // A pair's points come together: its runs of last step's impulses are looked up once
  std::uint64_t key = 0;
  std::pair<const LastPair*, const LastPair*> runs{nullptr, nullptr};
  for (Contact& c : contacts_) {
    // v_rel = n . (pdot_A - pdot_B), computed here so the framework never depends on student code
    const ContactBody &A = contact_bodies_[c.a], &B = contact_bodies_[c.b];
    const Vec3 pdot_a = A.v + A.omega.cross(c.p - A.x), pdot_b = B.v + B.omega.cross(c.p - B.x);
    c.v_rel_minus = c.n.dot(pdot_a - pdot_b);
    if (c.v_rel_minus < -settings_.restitution_threshold) {
      c.kind = ContactKind::Colliding;
    } else if (c.v_rel_minus <= settings_.restitution_threshold) {
      c.kind = ContactKind::Resting;
    } else {
      c.kind = ContactKind::Separating;
    }
    c.j = 0.0;
    c.j_t = Vec3::Zero();
    // Warm start: the impulse solvers, or the resting-contact solver, begin from last step's impulses
    const bool warm = !resting_solver_ ? settings_.method != ResponseMethod::Penalty
                                        : resting_solver_->bounces() || c.kind != ContactKind::Colliding;
    if (settings_.warm_start && warm) {
      if (runs.first == nullptr || pairKey(c.a, c.b) != key) {
        key = pairKey(c.a, c.b);
        runs = lastRuns(key);
      }
      if (const LastImpulse* last = lastImpulse(c, runs)) {
        c.j = last->j;
        c.j_t = last->j_t;
      }
    }
  }
}

std::pair<const World::LastPair*, const World::LastPair*> World::lastRuns(std::uint64_t key) const {
  const auto [first, last] = std::equal_range(last_pairs_.begin(), last_pairs_.end(), LastPair{key, 0, 0},
                                              [](const LastPair& x, const LastPair& y) { return x.key < y.key; });
  return {last_pairs_.data() + (first - last_pairs_.begin()), last_pairs_.data() + (last - last_pairs_.begin())};
}

const World::LastImpulse* World::lastImpulse(const Contact& c, std::pair<const LastPair*, const LastPair*> runs) const {
  // A point farther than this from every last point of its pair is new [m]
  constexpr double kSamePoint = 0.01;
  const LastImpulse* nearest = nullptr;
  double best = kSamePoint * kSamePoint;
  for (const LastPair* pair = runs.first; pair != runs.second; ++pair) {
    for (int k = pair->begin; k < pair->end; ++k) {
      const LastImpulse& last = last_impulses_[static_cast<std::size_t>(k)];
      if (last.id == c.id) return &last;
      const double distance = (last.p - c.p).squaredNorm();
      if (distance <= best) {
        best = distance;
        nearest = &last;
      }
    }
  }
  return nearest;
}

void World::respond(double h) {
  diagnostics_.iterations = 0;
  diagnostics_.levels = 0;
  if (contacts_.empty()) return;
  {
    PhaseTimer timer(times_.respond);
    // Without a resting-contact solver the impulses answer every point; with one, only the
    // colliding points, and the solver takes the others (or every point, when it bounces itself)
    chosen_.clear();
    if (!(resting_solver_ && resting_solver_->bounces())) {
      for (int k = 0; k < static_cast<int>(contacts_.size()); ++k) {
        if (!resting_solver_ || contacts_[k].kind == ContactKind::Colliding) chosen_.push_back(k);
      }
    }
    if (!chosen_.empty()) {
      if (settings_.method == ResponseMethod::Penalty) {
        applyPenaltyForces(chosen_, h);
      } else {
        groupByIsland(chosen_);
        diagnostics_.iterations = solveIslands(contact_bodies_, Solver::Response, true, h);
      }
    }
  }
  solveRestingContacts(h);
  if (shockPropagates()) {
    PhaseTimer timer(times_.respond);
    propagateShock(h);
  }
  PhaseTimer timer(times_.respond);
  storeContactBodies();
}

int World::findRoot(int i) {
  // Path halving: every other body on the way points to its grandparent
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];
    i = parent_[i];
  }
  return i;
}

void World::findIslands() {
  diagnostics_.islands = diagnostics_.largest_island = 0;
  if (!settings_.islands && !settings_.sleeping) {
    // The scene, as one system, rests on a fixed body when any contact has one
    carried_ = std::any_of(contacts_.begin(), contacts_.end(),
                           [&](const Contact& c) { return bodies_[c.a].fixed || bodies_[c.b].fixed; });
    if (!contacts_.empty()) diagnostics_.islands = 1;
    diagnostics_.largest_island = static_cast<int>(contacts_.size());
    return;
  }
  // Union-find over the awake moving bodies: a contact between two of them joins their trees,
  // the smaller under the larger root (fixed bodies carry anything and join nothing)
  const int n = static_cast<int>(bodies_.size());
  for (int i = 0; i < n; ++i) {
    parent_[i] = i;
    tree_size_[i] = 1;
  }
  for (const Contact& c : contacts_) {
    if (bodies_[c.a].fixed || bodies_[c.b].fixed) continue;
    int a = findRoot(c.a), b = findRoot(c.b);
    if (a == b) continue;
    if (tree_size_[a] < tree_size_[b]) std::swap(a, b);
    parent_[b] = a;
    tree_size_[a] += tree_size_[b];
  }
  // Each root numbers its island, a body touching nothing included; every body takes its root's
  island_total_ = 0;
  for (int i = 0; i < n; ++i) {
    if (awakeMoving(i) && findRoot(i) == i) island_of_[i] = island_total_++;
  }
  for (int i = 0; i < n; ++i) {
    if (awakeMoving(i)) island_of_[i] = island_of_[findRoot(i)];
  }
  // Each contact belongs to the island of its moving body (a of the two when both move)
  contact_island_.resize(contacts_.size());
  island_count_.assign(static_cast<std::size_t>(island_total_), 0);
  island_carried_.assign(static_cast<std::size_t>(island_total_), 0);
  carried_ = false;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const Contact& c = contacts_[k];
    contact_island_[k] = island_of_[bodies_[c.a].fixed ? c.b : c.a];
    ++island_count_[static_cast<std::size_t>(contact_island_[k])];
    // An island with a contact on a fixed body rests on it: every body of it has a level
    if (bodies_[c.a].fixed || bodies_[c.b].fixed) island_carried_[static_cast<std::size_t>(contact_island_[k])] = carried_ = true;
  }
  for (const int count : island_count_) {
    if (count > 0) ++diagnostics_.islands;
    diagnostics_.largest_island = std::max(diagnostics_.largest_island, count);
  }
  if (!settings_.islands && !contacts_.empty()) {
    diagnostics_.islands = 1;
    diagnostics_.largest_island = static_cast<int>(contacts_.size());
  }
}

void World::groupByIsland(const std::vector<int>& chosen) {
  group_.resize(chosen.size());
  if (!settings_.islands) {
    std::copy(chosen.begin(), chosen.end(), group_.begin());
    group_start_.assign({0, static_cast<int>(chosen.size())});
    return;
  }
  // Counting sort by island: stable, so each island keeps its contacts in the scene's order
  group_start_.assign(static_cast<std::size_t>(island_total_) + 1, 0);
  for (const int k : chosen) ++group_start_[static_cast<std::size_t>(contact_island_[k]) + 1];
  for (int g = 0; g < island_total_; ++g) group_start_[g + 1] += group_start_[g];
  group_next_.assign(group_start_.begin(), group_start_.end() - 1);
  for (const int k : chosen) group_[group_next_[contact_island_[k]]++] = k;
}

int World::solveIslands(std::vector<ContactBody>& bodies, Solver solver, bool keep_impulses, double h) {
  int most = 0;
  for (std::size_t g = 0; g + 1 < group_start_.size(); ++g) {
    if (group_start_[g] == group_start_[g + 1]) continue;
    // The island's bodies (a fixed body once per island that touches it) and its contacts, numbered locally
    island_members_.clear();
    island_bodies_.clear();
    island_contacts_.clear();
    const auto localIndex = [&](int i) {
      if (local_[i] < 0) {
        local_[i] = static_cast<int>(island_members_.size());
        island_members_.push_back(i);
        island_bodies_.push_back(bodies[i]);
      }
      return local_[i];
    };
    for (int k = group_start_[g]; k < group_start_[g + 1]; ++k) {
      island_contacts_.push_back(contacts_[group_[k]]);
      Contact& c = island_contacts_.back();
      c.a = localIndex(c.a);
      c.b = localIndex(c.b);
    }
    int taken = 0;
    if (solver != Solver::Resting) {
      // The response stops sooner on an island the shock propagation solves again (one resting on
      // a fixed body); elsewhere, and for the propagation's own solves, every setting as given
      const bool carried = settings_.islands ? island_carried_[g] != 0 : carried_;
      const Settings& with = solver == Solver::Response && carried ? response_settings_ : settings_;
      taken = settings_.method == ResponseMethod::Simultaneous ? solveSimultaneous(island_bodies_, island_contacts_, with)
                                                               : solveSequential(island_bodies_, island_contacts_, with);
    } else {
      const std::size_t count = island_members_.size();
      island_descriptions_.resize(count);
      island_states_.resize(count);
      for (std::size_t l = 0; l < count; ++l) {
        island_descriptions_[l] = bodies_[island_members_[l]];
        island_states_[l] = states_[island_members_[l]];
      }
      island_points_.resize(island_contacts_.size());
      std::iota(island_points_.begin(), island_points_.end(), 0);
      taken = resting_solver_->solve(island_bodies_, island_contacts_, island_points_, island_descriptions_,
                                     island_states_, settings_.gravity, h);
    }
    most = std::max(most, taken);
    // Back to the World: the velocities (solvers change nothing else of a body), the impulses when kept
    for (std::size_t l = 0; l < island_members_.size(); ++l) {
      const int i = island_members_[l];
      bodies[i].v = island_bodies_[l].v;
      bodies[i].omega = island_bodies_[l].omega;
      local_[i] = -1;
    }
    if (keep_impulses) {
      for (int k = group_start_[g]; k < group_start_[g + 1]; ++k) {
        Contact& c = contacts_[group_[k]];
        const int a = c.a, b = c.b;
        c = island_contacts_[static_cast<std::size_t>(k - group_start_[g])];
        c.a = a;
        c.b = b;
      }
    }
  }
  return most;
}

void World::findLevels() {
  // The contact graph, each body's neighbours together (counting sort by body)
  const int n = static_cast<int>(bodies_.size());
  first_.assign(static_cast<std::size_t>(n) + 2, 0);
  for (const Contact& c : contacts_) {
    ++first_[static_cast<std::size_t>(c.a) + 2];
    ++first_[static_cast<std::size_t>(c.b) + 2];
  }
  for (int i = 2; i < n + 2; ++i) first_[i] += first_[i - 1];
  neighbours_.resize(2 * contacts_.size());
  for (const Contact& c : contacts_) {
    neighbours_[first_[static_cast<std::size_t>(c.a) + 1]++] = c.b;
    neighbours_[first_[static_cast<std::size_t>(c.b) + 1]++] = c.a;
  }
  // Breadth first from the fixed bodies: a body's level is one more than the lowest it touches
  level_.assign(static_cast<std::size_t>(n), -1);
  queue_.clear();
  for (int i = 0; i < n; ++i) {
    if (bodies_[i].fixed && first_[i + 1] > first_[i]) {
      level_[i] = 0;
      queue_.push_back(i);
    }
  }
  for (std::size_t next = 0; next < queue_.size(); ++next) {
    const int i = queue_[next];
    for (int k = first_[i]; k < first_[i + 1]; ++k) {
      const int j = neighbours_[k];
      if (level_[j] < 0 && !bodies_[j].fixed) {
        level_[j] = level_[i] + 1;
        queue_.push_back(j);
      }
    }
  }
  // The breadth-first order (queue_) lists the bodies by level; a contact belongs to the higher of its
  // bodies' levels (one of level 0 and one not carried: none)
  const int top = queue_.empty() ? 0 : level_[queue_.back()];
  body_level_start_.assign(static_cast<std::size_t>(top) + 2, 0);
  for (const int i : queue_) ++body_level_start_[static_cast<std::size_t>(level_[i]) + 1];
  contact_level_start_.assign(static_cast<std::size_t>(top) + 2, 0);
  for (const Contact& c : contacts_) {
    if (level_[c.a] >= 0 && level_[c.b] >= 0) ++contact_level_start_[std::max(level_[c.a], level_[c.b]) + 1];
  }
  for (int l = 1; l <= top + 1; ++l) {
    body_level_start_[l] += body_level_start_[l - 1];
    contact_level_start_[l] += contact_level_start_[l - 1];
  }
  contacts_by_level_.resize(static_cast<std::size_t>(contact_level_start_[top + 1]));
  level_points_.assign(contact_level_start_.begin(), contact_level_start_.end());
  for (int k = 0; k < static_cast<int>(contacts_.size()); ++k) {
    const Contact& c = contacts_[k];
    if (level_[c.a] >= 0 && level_[c.b] >= 0) contacts_by_level_[level_points_[std::max(level_[c.a], level_[c.b])]++] = k;
  }
}

void World::propagateShock(double h) {
  findLevels();
  const int top = static_cast<int>(body_level_start_.size()) - 2;
  held_ = contact_bodies_;
  for (int level = 1; level <= top; ++level) {
    // The level below is held still from here on: no impulse changes its velocities
    for (int k = body_level_start_[level - 1]; k < body_level_start_[level]; ++k) {
      ContactBody& held = held_[queue_[k]];
      held.inv_mass = 0.0;
      held.I_inv_world = Mat3::Zero();
    }
    // This level's points, their impulses taken back: the solver starts from them (warm) and
    // applies them again, so that it continues the response with the levels below held
    level_points_.clear();
    for (int k = contact_level_start_[level]; k < contact_level_start_[level + 1]; ++k) {
      const int index = contacts_by_level_[k];
      const Contact& c = contacts_[index];
      // Points the impulses answered stay answered, when a resting solver takes the others
      if (resting_solver_ && !resting_solver_->bounces() && c.kind == ContactKind::Colliding) continue;
      const Vec3 J = c.j * c.n + c.j_t;
      ContactBody &A = held_[c.a], &B = held_[c.b];
      A.v -= A.inv_mass * J;
      A.omega -= A.I_inv_world * (c.p - A.x).cross(J);
      B.v += B.inv_mass * J;
      B.omega += B.I_inv_world * (c.p - B.x).cross(J);
      level_points_.push_back(index);
    }
    if (level_points_.empty()) continue;
    ++diagnostics_.levels;
    // Island by island, on copies: a held body does not feel what the level's solve changes, so
    // its answer is no impulse the bodies exchanged, and the contacts keep the response's
    // impulses (what warm starts the next step)
    groupByIsland(level_points_);
    diagnostics_.iterations += solveIslands(held_, resting_solver_ ? Solver::Resting : Solver::Impulses, false, h);
  }
  // The held bodies' velocities never changed: every velocity is the propagated one
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    contact_bodies_[i].v = held_[i].v;
    contact_bodies_[i].omega = held_[i].omega;
  }
}

void World::solveRestingContacts(double h) {
  if (!resting_solver_) return;
  resting_.clear();
  // Separating points go too: the solver leaves a point alone when nothing pushes it together,
  // and a point that separates slowly (as overlap is pushed out) still needs its support
  const bool every = resting_solver_->bounces();
  for (int k = 0; k < static_cast<int>(contacts_.size()); ++k) {
    if (every || contacts_[k].kind != ContactKind::Colliding) resting_.push_back(k);
  }
  if (resting_.empty()) return;  // nothing rests: the solver is not run
  PhaseTimer timer(times_.resting);
  // A sub-stepping solver moves every body in its one solve: the scene is one system
  if (resting_solver_->substeps()) {
    diagnostics_.iterations +=
        resting_solver_->solve(contact_bodies_, contacts_, resting_, bodies_, states_, settings_.gravity, h);
    return;
  }
  groupByIsland(resting_);
  diagnostics_.iterations += solveIslands(contact_bodies_, Solver::Resting, true, h);
}

void World::applyPenaltyForces(const std::vector<int>& chosen, double h) {
  // A force F over the step is the impulse F h, applied at the contact point
  for (const int k : chosen) {
    Contact& c = contacts_[k];
    const Vec3 F = penaltyForce(c.depth, c.v_rel_minus, c.n, settings_.penalty_k, settings_.penalty_d);
    c.j = F.norm() * h;
    applyImpulse(contact_bodies_[c.a], contact_bodies_[c.b], c.p, F * h);
  }
}

void World::integrate(double h) {
  PhaseTimer timer(times_.integrate);
  // A sub-stepping resting solver has moved the bodies already
  if (resting_solver_ && resting_solver_->placeBodies(states_)) return;
  // How long each body moves: h, or for a fast body until just into the first body it would hit
  // (every sweep from the states at the start of the step, before anyone moves)
  advance_.assign(bodies_.size(), h);
  if (settings_.continuous) {
    motions_.resize(bodies_.size());
    largest_travel_ = 0.0;
    for (const int i : bounded_) {
      const BodyState& s = states_[i];
      motions_[i] = !awakeMoving(i) ? Motion{}
                                     : Motion{s.P / bodies_[i].mass, s.L.isZero() ? Vec3::Zero() : angularVelocity(i)};
      largest_travel_ = std::max(largest_travel_, h * (motions_[i].v.norm() + motions_[i].omega.norm() * radius_[i]));
    }
    for (const int i : bounded_) {
      if (awakeMoving(i)) advance_[i] = sweptStep(i, h);
    }
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i].fixed || asleep_[i]) continue;
    // Symplectic Euler: the new velocities move the body over the step
    BodyState& s = states_[i];
    const double t = advance_[i];
    s.x += t * s.P / bodies_[i].mass;
    if (!s.L.isZero()) s.q = exponentialUpdate(s.q, angularVelocity(static_cast<int>(i)), t).normalized();
  }
}

bool World::touching(int i, int j) const {
  for (const Contact& c : contacts_) {
    if ((c.a == i && c.b == j) || (c.a == j && c.b == i)) return true;
  }
  return false;
}

double World::sweptStep(int i, double h) {
  const Motion& motion = motions_[i];
  const double rho = radius_[i];
  const double speed = motion.v.norm() + motion.omega.norm() * rho;
  if (!(speed * h > inner_[i])) return h;
  // The bodies the sweep may reach (planes: none can be passed): with the broad phase, those
  // whose box at the step's start is within the largest travel of any body of the box the sweep
  // covers; without it, every body
  const BodyState& s = states_[i];
  reachable_.clear();
  if (settings_.use_broad_phase && bounded_.size() >= 2) {
    const Vec3 reach = Vec3::Constant(rho + h * motion.omega.norm() * rho + largest_travel_);
    const Vec3 end = s.x + h * motion.v;
    const Aabb swept{s.x.cwiseMin(end) - reach, s.x.cwiseMax(end) + reach};
    if (listed_.size() >= 2) broad_phase_->query(swept, [&](int id) { reachable_.push_back(listed_[id]); });
    querySleepers(swept, [&](int j) { reachable_.push_back(j); });
  } else {
    reachable_ = bounded_;
  }
  // The times of impact against each
  hits_.clear();
  const Pose pose{s.x, s.q};
  for (const int j : reachable_) {
    if (j == i) continue;
    const Motion& other = motions_[j];
    // Slow against this one (bodies falling together): the narrow phase finds any overlap of theirs
    const double turning = h * (motion.omega.norm() * rho + other.omega.norm() * radius_[j]);
    const Vec3 d = h * (motion.v - other.v);
    if (!(d.norm() + turning > inner_[i] + inner_[j])) continue;
    // Out of reach: the other centre, seen from this one moving relative to it, stays farther from
    // the swept segment than both bounding radii and the turning of both
    const BodyState& o = states_[j];
    const Vec3 c = o.x - s.x;
    const double along = d.squaredNorm() > 0.0 ? std::clamp(c.dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    const double reach = rho + radius_[j] + turning;
    if ((c - along * d).squaredNorm() > reach * reach) continue;
    const ToiResult toi =
        toiConservativeAdvancement(bodies_[i].shape, pose, motion, bodies_[j].shape, Pose{o.x, o.q}, other, h, kSweepTolerance);
    if (!toi.hit) continue;
    if (toi.time > 0.0 || touching(i, j)) {
      hits_.push_back(toi.time);
      continue;
    }
    // A hit at 0 on a pair the narrow phase found apart: within the sweep's tolerance, but no
    // contact, so no impulse answers it this step. The gap closes no sooner than gap / (approach
    // bound), conservative advancement's own bound: that is the hit (none when they part)
    const DistanceResult gap = distance(bodies_[i].shape, pose, bodies_[j].shape, Pose{o.x, o.q});
    const Vec3 n = gap.point_a - gap.point_b;
    if (gap.overlap || !(n.squaredNorm() > 0.0)) continue;
    const double approach = approachSpeedBound(bodies_[i].shape, motion, bodies_[j].shape, other, n.normalized());
    if (approach > 0.0) hits_.push_back(std::clamp(gap.distance / approach, std::numeric_limits<double>::min(), h));
  }
  // Nothing in the way: the whole step, without asking
  return hits_.empty() ? h : continuousAdvance(hits_, h, speed, kSweepOverlap);
}

void World::correctPositions(double h) {
  // Penalty springs push overlapping bodies apart themselves
  if (settings_.position_correction == 0.0 || settings_.method == ResponseMethod::Penalty) return;
  if (contacts_.empty()) return;
  PhaseTimer timer(times_.correct);
  // Each point's separation after this step's motion, to first order: -depth + h n . (u_A - u_B),
  // u the velocity of each body's point at p. It is to reach -slop - (1 - beta)(overlap - slop):
  // beta of the overlap beyond the slop goes this step. A pair the velocities already part
  // needs no push. Masses, inertias and velocities are the solver's copies (its answer).
  const double beta = settings_.position_correction, slop = settings_.slop;
  correction_.clear();
  for (const Contact& c : contacts_) {
    CorrectionPoint point;
    point.a = c.a;
    point.b = c.b;
    point.n = c.n;
    point.r_a = c.p - states_[c.a].x;
    point.r_b = c.p - states_[c.b].x;
    point.turn_a = point.turn_b = Vec3::Zero();
    double k = 0.0;
    Vec3 u = Vec3::Zero();
    if (!bodies_[c.a].fixed) {
      const ContactBody& A = contact_bodies_[c.a];
      point.turn_a = A.I_inv_world * point.r_a.cross(c.n);
      k += A.inv_mass + point.r_a.cross(c.n).dot(point.turn_a);
      u += A.v + A.omega.cross(point.r_a);
    }
    if (!bodies_[c.b].fixed) {
      const ContactBody& B = contact_bodies_[c.b];
      point.turn_b = B.I_inv_world * point.r_b.cross(c.n);
      k += B.inv_mass + point.r_b.cross(c.n).dot(point.turn_b);
      u -= B.v + B.omega.cross(point.r_b);
    }
    if (k == 0.0) continue;
    point.inv_k = 1.0 / k;
    point.pushed = 0.0;
    point.separation = -c.depth + h * c.n.dot(u);
    point.target = -slop - (1.0 - beta) * std::max(0.0, -point.separation - slop);
    if (point.separation < point.target) correction_.push_back(point);
  }
  if (correction_.empty()) return;
  // Gauss-Seidel over the points, forward then backward (one way only tilts a light box under a
  // heavy one a little further each step): each push along n, never a pull, moves and turns both
  // bodies, and the next points see the separation those moves left
  shift_.assign(bodies_.size(), Vec3::Zero());
  turn_.assign(bodies_.size(), Vec3::Zero());
  const std::size_t count = correction_.size();
  for (int sweep = 0; sweep < settings_.correction_sweeps; ++sweep) {
    for (std::size_t k = 0; k < count; ++k) {
      CorrectionPoint& point = correction_[sweep % 2 == 0 ? k : count - 1 - k];
      const double separation =
          point.separation + point.n.dot(shift_[point.a] + turn_[point.a].cross(point.r_a) - shift_[point.b] -
                                         turn_[point.b].cross(point.r_b));
      // The total push stays >= 0 (never a pull); a point an earlier push overdid gives some back
      const double total = std::max(0.0, point.pushed + (point.target - separation) * point.inv_k);
      const double push = total - point.pushed;
      point.pushed = total;
      if (push == 0.0) continue;
      if (!bodies_[point.a].fixed) {
        shift_[point.a] += (push * contact_bodies_[point.a].inv_mass) * point.n;
        turn_[point.a] += push * point.turn_a;
      }
      if (!bodies_[point.b].fixed) {
        shift_[point.b] -= (push * contact_bodies_[point.b].inv_mass) * point.n;
        turn_[point.b] -= push * point.turn_b;
      }
    }
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i].fixed) continue;
    states_[i].x += shift_[i];
    // A turn is a rotation vector: the orientation turned by it over unit time
    if (!turn_[i].isZero()) states_[i].q = exponentialUpdate(states_[i].q, turn_[i], 1.0).normalized();
  }
}

bool World::wakeTouchedIslands() {
  if (!settings_.sleeping) return false;
  PhaseTimer timer(times_.narrow_phase);
  bool woke = false;
  for (const BoxPair& pair : pairs_) {
    const int sleeper = asleep_[pair.first] ? pair.first : pair.second;
    const int other = sleeper == pair.first ? pair.second : pair.first;
    if (!asleep_[sleeper] || !awakeMoving(other)) continue;
    // Touching, not only near: an awake body resting beside a sleeping pile leaves it asleep
    const Manifold m = collide(bodies_[sleeper].shape, Pose{states_[sleeper].x, states_[sleeper].q},
                               bodies_[other].shape, Pose{states_[other].x, states_[other].q});
    if (m.count > 0) {
      wake(sleeper);
      woke = true;
    }
  }
  return woke;
}

void World::wake(int i) {
  // Every body of its island carries the island's label; waking is rare, a pass over the bodies is cheap
  const int label = sleep_label_[i];
  sleepers_changed_ = true;
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    if (asleep_[k] && sleep_label_[k] == label) {
      asleep_[k] = 0;
      still_time_[k] = 0.0;
    }
  }
}

void World::updateSleep(double h) {
  if (!settings_.sleeping) return;
  // Each awake body's time still (the students' rule), and each island's shortest
  island_still_.assign(static_cast<std::size_t>(island_total_), std::numeric_limits<double>::infinity());
  const int n = static_cast<int>(bodies_.size());
  for (int i = 0; i < n; ++i) {
    if (!awakeMoving(i)) continue;
    still_time_[i] =
        sleepTimer(velocity(i), angularVelocity(i), still_time_[i], h, settings_.sleep_linear, settings_.sleep_angular);
    double& island = island_still_[static_cast<std::size_t>(island_of_[i])];
    island = std::min(island, still_time_[i]);
  }
  // An island whose every body has been still long enough falls asleep at rest, labelled by its root
  bool fell = false;
  for (int i = 0; i < n; ++i) {
    if (!awakeMoving(i) || island_still_[static_cast<std::size_t>(island_of_[i])] < settings_.sleep_time) continue;
    asleep_[i] = 1;
    sleep_label_[i] = findRoot(i);
    states_[i].P = states_[i].L = Vec3::Zero();
    fell = true;
  }
  // Its contacts (every contact of this step had an awake body) warm start it when it wakes
  if (!fell) return;
  sleepers_changed_ = true;
  for (const Contact& c : contacts_) {
    if (asleep_[c.a] || asleep_[c.b]) sleeping_contacts_.push_back(c);
  }
}

void World::computeDiagnostics() {
  PhaseTimer timer(times_.diagnostics);
  Diagnostics& d = diagnostics_;
  d.kinetic_energy = d.potential_energy = 0.0;
  d.linear_momentum = d.angular_momentum = Vec3::Zero();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i].fixed) continue;
    const BodyState& s = states_[i];
    const Vec3 omega = angularVelocity(static_cast<int>(i));
    d.kinetic_energy += 0.5 * s.P.squaredNorm() / bodies_[i].mass + 0.5 * omega.dot(s.L);
    d.potential_energy -= bodies_[i].mass * settings_.gravity.dot(s.x);
    d.linear_momentum += s.P;
    d.angular_momentum += s.x.cross(s.P) + s.L;
  }
  d.contacts = static_cast<int>(contacts_.size());
  d.asleep = static_cast<int>(std::count(asleep_.begin(), asleep_.end(), 1));
  d.colliding = d.resting = 0;
  d.max_penetration = 0.0;
  for (const Contact& c : contacts_) {
    d.max_penetration = std::max(d.max_penetration, c.depth);
    if (c.kind == ContactKind::Colliding) ++d.colliding;
    if (c.kind == ContactKind::Resting) ++d.resting;
  }
}

}  // namespace physlab
