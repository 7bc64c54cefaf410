// The textbook contact scenes of contact_suite.hpp: bodies, what each measures, and the truth.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "physlab/contact_suite.hpp"
#include "physlab/error.hpp"
#include "physlab/rigid.hpp"

namespace physlab {

double Measure::score() const { return std::abs(value - expected) / tolerance; }

bool Measure::pass() const { return score() <= 1.0; }

namespace {

constexpr double kG = 9.81;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const Vec3 kBoxHalf(0.2, 0.2, 0.1);  // the drop box: 0.4 x 0.4 x 0.2 m, 1 kg
constexpr double kCube = 0.1;        // half edge of the cubes of stacks and ramps [m]
// Bodies that start at rest on others overlap by a hair, so that round-off cannot open a gap and
// lose the contact for a step (contacts exist only at depth >= 0)
constexpr double kTouch = kCube - 1e-6;

BodyState at(const Vec3& x, const Quat& q = Quat::Identity()) {
  BodyState s;
  s.x = x;
  s.q = q;
  return s;
}

Scene ground(double epsilon, double mu) {
  Scene scene;
  scene.bodies.push_back(BodyDescription::plane(Vec3::UnitZ(), 0.0, epsilon, mu));
  scene.states.push_back(BodyState{});
  return scene;
}

// acc = max(acc, x), where NaN (a state that stopped being finite) wins for good
void keepLargest(double& acc, double x) { acc = std::isnan(acc) || std::isnan(x) ? kNaN : std::max(acc, x); }

// Height of a body's lowest point above the plane through the origin with unit normal n [m].
double lowest(const BodyDescription& body, const BodyState& s, const Vec3& n = Vec3::UnitZ()) {
  if (const auto* sphere = std::get_if<Sphere>(&body.shape)) return n.dot(s.x) - sphere->radius;
  const Vec3 half = std::get<Box>(body.shape).half_extents;
  // The support of the box along -n: |R^T n| weighted by the half extents
  const Vec3 local = s.q.conjugate() * n;
  return n.dot(s.x) - local.cwiseAbs().dot(half);
}

// Angle between a body's z axis and the world's z axis [degrees].
double tilt(const BodyState& s) {
  const double c = std::clamp((s.q * Vec3::UnitZ()).z(), -1.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

// Kinetic plus potential energy of the moving bodies [J].
double energy(const Scene& scene, const std::vector<BodyState>& states) {
  double e = 0.0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const BodyDescription& body = scene.bodies[i];
    if (body.fixed) continue;
    const BodyState& s = states[i];
    const Mat3 R = s.q.toRotationMatrix();
    const Vec3 omega = R * body.inertia_body.inverse() * R.transpose() * s.L;
    e += 0.5 * s.P.squaredNorm() / body.mass + 0.5 * omega.dot(s.L) + body.mass * kG * s.x.z();
  }
  return e;
}

// The apex of the first rebound of a body's lowest point: falls, turns upwards, rises, turns down.
class Rebound {
 public:
  void observe(double height) {
    if (phase_ == Phase::Falling && height > last_ + kRise) phase_ = Phase::Rising;
    if (phase_ == Phase::Rising) {
      apex_ = std::max(apex_, height);
      if (height < apex_ - kRise) phase_ = Phase::Done;
    }
    last_ = height;
  }
  // The apex, or NaN when the body never rose again
  double apex() const { return phase_ == Phase::Falling ? kNaN : apex_; }

 private:
  enum class Phase { Falling, Rising, Done };
  static constexpr double kRise = 1e-6;  // a move smaller than this is rest, not a rebound [m]
  Phase phase_ = Phase::Falling;
  double last_ = std::numeric_limits<double>::infinity();
  double apex_ = -std::numeric_limits<double>::infinity();
};

// ----- drops -----------------------------------------------------------------------------------

// A body dropped from rest onto the ground: rebound apex over drop height is epsilon^2.
class Drop : public SuiteScene {
 public:
  Drop(std::string name, BodyDescription body, double height, double epsilon, bool box)
      : name_(std::move(name)), body_(std::move(body)), height_(height), epsilon_(epsilon), box_(box) {}
  std::string name() const override { return name_; }
  Scene scene() const override {
    Scene scene = ground(epsilon_, body_.mu);
    scene.bodies.push_back(body_);
    const double lift = box_ ? kBoxHalf.z() : std::get<Sphere>(body_.shape).radius;
    scene.states.push_back(at(Vec3(0.0, 0.0, height_ + lift)));
    return scene;
  }
  double duration() const override { return 2.0 * std::sqrt(2.0 * height_ / kG) + 0.5; }
  void observe(double, const std::vector<BodyState>& states) override {
    rebound_.observe(lowest(body_, states[1]));
    keepLargest(turn_, tilt(states[1]));
  }
  std::vector<Measure> measures() const override {
    std::vector<Measure> m{{"rebound / drop height", rebound_.apex() / height_, epsilon_ * epsilon_,
                            0.1 * epsilon_ * epsilon_,
                            "10 %: the impact happens inside a step; the time discretisation alone moves it a few per cent"}};
    if (box_) m.push_back({"largest tilt [deg]", turn_, 0.0, 1.0, "1 degree: a symmetric impact gives no torque"});
    return m;
  }

 private:
  std::string name_;
  BodyDescription body_;
  double height_, epsilon_;
  bool box_;
  Rebound rebound_;
  double turn_ = 0.0;
};

// A box dropped turned on two axes: no exact rebound, but it may never gain energy, and it rests.
class TiltedDrop : public SuiteScene {
 public:
  explicit TiltedDrop(double epsilon) : epsilon_(epsilon) {}
  std::string name() const override { return "tilted drop, e = " + std::to_string(epsilon_).substr(0, 3); }
  Scene scene() const override {
    Scene scene = ground(epsilon_, 0.5);
    scene.bodies.push_back(BodyDescription::box(1.0, kBoxHalf, epsilon_, 0.5));
    const Quat q = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitX())) * Quat(Eigen::AngleAxisd(0.2, Vec3::UnitY()));
    BodyState s = at(Vec3::Zero(), q);
    s.x.z() = 0.5 - lowest(scene.bodies[1], s);
    scene.states.push_back(s);
    return scene;
  }
  double duration() const override { return 4.0; }
  void observe(double t, const std::vector<BodyState>& states) override {
    const double e = energy(scene_, states);
    if (t == 0.0) start_ = e;
    keepLargest(gain_, (e - start_) / start_);
    speed_ = states[1].P.norm() / scene_.bodies[1].mass;
  }
  std::vector<Measure> measures() const override {
    return {{"largest energy gain / start", gain_, 0.0, 0.01,
             "1 %: pushing overlap apart lifts the box by the overlap, a fraction of a per cent of its energy"},
            {"speed after 4 s [m/s]", speed_, 0.0, 0.01, "0.01 m/s: the box must have come to rest"}};
  }

 private:
  double epsilon_;
  Scene scene_ = scene();
  double start_ = 0.0, gain_ = 0.0, speed_ = kNaN;
};

// ----- friction ----------------------------------------------------------------------------------

// A cube at rest on a ramp tilted by theta, friction mu: sticks when tan theta < mu, else slides
// at a = g (sin theta - mu cos theta).
class Ramp : public SuiteScene {
 public:
  Ramp(double theta_deg, double mu) : theta_(theta_deg * M_PI / 180.0), theta_deg_(theta_deg), mu_(mu) {}
  std::string name() const override {
    return "ramp " + std::to_string(static_cast<int>(theta_deg_)) + " deg, mu = " + std::to_string(mu_).substr(0, 3);
  }
  Scene scene() const override {
    const Quat tilt(Eigen::AngleAxisd(-theta_, Vec3::UnitY()));
    Scene scene;
    scene.bodies.push_back(BodyDescription::plane(tilt * Vec3::UnitZ(), 0.0, 0.0, mu_));
    scene.states.push_back(BodyState{});
    scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(kCube), 0.0, mu_));
    scene.states.push_back(at(kTouch * (tilt * Vec3::UnitZ()), tilt));
    return scene;
  }
  double duration() const override { return 1.0; }
  void observe(double t, const std::vector<BodyState>& states) override {
    const Vec3 down_slope = Quat(Eigen::AngleAxisd(-theta_, Vec3::UnitY())) * -Vec3::UnitX();
    if (t == 0.0) start_ = states[1].x;
    travel_ = down_slope.dot(states[1].x - start_);
    time_ = t;
  }
  std::vector<Measure> measures() const override {
    if (std::tan(theta_) < mu_) {
      return {{"slid in 1 s [m]", travel_, 0.0, 0.002, "2 mm: the block must stick; settling into the slop moves it less"}};
    }
    const double a = kG * (std::sin(theta_) - mu_ * std::cos(theta_));
    return {{"acceleration [m/s^2]", 2.0 * travel_ / (time_ * time_), a, 0.05 * a,
             "5 %: symplectic Euler's distance is off by a step's worth, under 2 % in 1 s"}};
  }

 private:
  double theta_, theta_deg_, mu_;
  Vec3 start_ = Vec3::Zero();
  double travel_ = kNaN, time_ = 0.0;
};

// A sphere thrown along the ground without spin: friction turns sliding into rolling at 5/7 v0
// (angular momentum about the contact point is conserved), and energy only falls.
class RollingBall : public SuiteScene {
 public:
  std::string name() const override { return "thrown ball, mu = 0.3"; }
  Scene scene() const override {
    Scene scene = ground(0.0, 0.3);
    scene.bodies.push_back(BodyDescription::sphere(1.0, 0.1, 0.0, 0.3));
    scene.states.push_back(BodyState::moving(scene.bodies[1], Vec3(0.0, 0.0, 0.1 - 1e-6), Quat::Identity(),
                                             Vec3(kV0, 0.0, 0.0), Vec3::Zero()));
    return scene;
  }
  double duration() const override { return 2.0; }
  void observe(double t, const std::vector<BodyState>& states) override {
    const double e = energy(scene_, states);
    if (t == 0.0) start_ = e;
    keepLargest(gain_, (e - start_) / start_);
    speed_ = states[1].P.x();
  }
  std::vector<Measure> measures() const override {
    return {{"final speed / (5/7 v0)", speed_ / (5.0 / 7.0 * kV0), 1.0, 0.02,
             "2 %: rolling is exact once reached; the last sliding step overshoots by at most mu g h / v"},
            {"largest energy gain / start", gain_, 0.0, 1e-3, "0.1 %: friction only removes energy"}};
  }

 private:
  static constexpr double kV0 = 2.0;
  Scene scene_ = scene();
  double start_ = 0.0, gain_ = 0.0, speed_ = kNaN;
};

// ----- weight ------------------------------------------------------------------------------------

// n cubes stacked on the ground for 10 s: they stand still, and sink no more than the overlap
// an engine keeps.
class Stack : public SuiteScene {
 public:
  explicit Stack(int n) : n_(n) {}
  std::string name() const override { return "stack of " + std::to_string(n_) + " cubes"; }
  Scene scene() const override {
    Scene scene = ground(0.0, 0.5);
    for (int i = 0; i < n_; ++i) {
      scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(kCube), 0.0, 0.5));
      scene.states.push_back(at(Vec3(0.0, 0.0, (2 * i + 1) * kTouch)));
    }
    return scene;
  }
  double duration() const override { return 10.0; }
  // Round-off decides where a swaying stack sways to (see runSuiteSceneShaken())
  int runs() const override { return 9; }
  void observe(double, const std::vector<BodyState>& states) override {
    for (int i = 1; i <= n_; ++i) keepLargest(drift_, states[i].x.head<2>().norm());
    sink_ = (2 * n_ - 1) * kCube - states[n_].x.z();
  }
  std::vector<Measure> measures() const override {
    return {{"top cube sunk [m]", sink_, 0.0, 0.005, "5 mm over 10 contacts: half a millimetre of overlap each"},
            {"largest sideways drift [m]", drift_, 0.0, 0.001,
             "1 mm over 10 s: nothing pushes a stack sideways, it stands still (exact solvers hold it to 1e-8 m); "
             "one that sways moves by centimetres, one that topples by metres"}};
  }

 private:
  int n_;
  double sink_ = kNaN, drift_ = 0.0;
};

// A cube 100 times heavier resting on a light one: the light cube must carry it.
class HeavyOnLight : public SuiteScene {
 public:
  std::string name() const override { return "heavy on light, 100:1"; }
  Scene scene() const override {
    Scene scene = ground(0.0, 0.5);
    scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(kCube), 0.0, 0.5));
    scene.states.push_back(at(Vec3(0.0, 0.0, kTouch)));
    scene.bodies.push_back(BodyDescription::box(100.0, Vec3::Constant(kCube), 0.0, 0.5));
    scene.states.push_back(at(Vec3(0.0, 0.0, 3.0 * kTouch)));
    return scene;
  }
  double duration() const override { return 3.0; }
  void observe(double, const std::vector<BodyState>& states) override {
    overlap_ = 2.0 * kCube - (states[2].x.z() - states[1].x.z());
    drift_ = (states[2].x - states[1].x).head<2>().norm();
  }
  std::vector<Measure> measures() const override {
    return {{"heavy into light [m]", overlap_, 0.0, 0.005, "5 mm: a few slops; sinking through is metres"},
            {"sideways drift [m]", drift_, 0.0, 0.01, "1 cm: nothing pushes sideways"}};
  }

 private:
  double overlap_ = kNaN, drift_ = kNaN;
};

// A heavy box on a light cube at 1000:1 for 5 s, centred on it (a small cube on a large one, a
// wide plate on a small cube): the light cube must carry it, neither sunk into nor squeezed out.
class HeavyRatio : public SuiteScene {
 public:
  HeavyRatio(std::string name, const Vec3& top, const Vec3& bottom) : name_(std::move(name)), top_(top), bottom_(bottom) {}
  std::string name() const override { return name_; }
  Scene scene() const override {
    Scene scene = ground(0.0, 0.5);
    scene.bodies.push_back(BodyDescription::box(1.0, bottom_, 0.0, 0.5));
    scene.states.push_back(at(Vec3(0.0, 0.0, bottom_.z() - 1e-6)));
    scene.bodies.push_back(BodyDescription::box(1000.0, top_, 0.0, 0.5));
    scene.states.push_back(at(Vec3(0.0, 0.0, 2.0 * bottom_.z() + top_.z() - 2e-6)));
    return scene;
  }
  double duration() const override { return 5.0; }
  void observe(double, const std::vector<BodyState>& states) override {
    keepLargest(overlap_, top_.z() + bottom_.z() - (states[2].x.z() - states[1].x.z()));
    keepLargest(drift_, (states[2].x - states[1].x).head<2>().norm());
  }
  std::vector<Measure> measures() const override {
    return {{"heavy into light, deepest [m]", overlap_, 0.0, 0.005,
             "5 mm: a few slops; a light cube that cannot carry 1000 times its weight is sunk through (its height)"},
            {"sideways drift [m]", drift_, 0.0, 0.01, "1 cm: nothing pushes sideways; a cube squeezed out moves by its width"}};
  }

 private:
  std::string name_;
  Vec3 top_, bottom_;
  double overlap_ = -std::numeric_limits<double>::infinity(), drift_ = 0.0;
};

// A 100 kg box on a 3-2-1 pyramid of 1 kg cubes (rows 1 mm apart sideways) for 5 s: it stays on
// top and the pyramid stands.
class HeavyOnPyramid : public SuiteScene {
 public:
  std::string name() const override { return "heavy on pyramid, 100:1"; }
  Scene scene() const override {
    Scene scene = ground(0.0, 0.5);
    for (int row = 0; row < 3; ++row) {
      for (int k = 0; k <= 2 - row; ++k) {
        scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(kCube), 0.0, 0.5));
        const double x = (k - 0.5 * (2 - row)) * kPitch;
        scene.states.push_back(at(Vec3(x, 0.0, (2 * row + 1) * kTouch)));
      }
    }
    scene.bodies.push_back(BodyDescription::box(100.0, Vec3::Constant(kCube), 0.0, 0.5));
    scene.states.push_back(at(Vec3(0.0, 0.0, 7 * kTouch)));
    return scene;
  }
  double duration() const override { return 5.0; }
  void observe(double, const std::vector<BodyState>& states) override {
    if (start_.empty()) start_ = states;  // t = 0: the start
    keepLargest(sunk_, start_[kHeavy].x.z() - states[kHeavy].x.z());
    for (int i = 1; i <= kHeavy; ++i) keepLargest(drift_, (states[i].x - start_[i].x).head<2>().norm());
  }
  std::vector<Measure> measures() const override {
    return {{"heavy box sunk, deepest [m]", sunk_, 0.0, 0.005,
             "5 mm: a few slops over three contacts; a pyramid that gives way drops it by a cube (0.2 m)"},
            {"largest sideways drift [m]", drift_, 0.0, 0.01, "1 cm: the pyramid stands; one pushed apart moves by its width"}};
  }

 private:
  static constexpr int kHeavy = 7;           // the heavy box's index (ground, then 6 cubes)
  static constexpr double kPitch = 2.0 * kCube + 1e-3;  // centre to centre in a row [m]
  std::vector<BodyState> start_;
  double sunk_ = -std::numeric_limits<double>::infinity(), drift_ = 0.0;
};

// Spheres of 5 cm radius fired at `speed` at fixed 20 cm boxes, one per lane (lanes 1 m apart, so
// that no sphere meets another), starting at several distances and offsets so that a step can end
// anywhere along the shot: none may pass through its box.
class FastSphere : public SuiteScene {
 public:
  explicit FastSphere(double speed) : speed_(speed) {}
  std::string name() const override { return "fast sphere, " + std::to_string(static_cast<int>(speed_)) + " m/s"; }
  Scene scene() const override {
    Scene scene = ground(0.5, 0.5);
    for (int lane = 0; lane < kLanes; ++lane) {
      scene.bodies.push_back(BodyDescription::fixedBox(Vec3::Constant(kCube), 0.5, 0.5));
      scene.states.push_back(at(Vec3(0.0, lane * kLaneWidth, kHeight)));
    }
    for (int lane = 0; lane < kLanes; ++lane) {
      const BodyDescription sphere = BodyDescription::sphere(0.1, kRadius, 0.5, 0.5);
      const Vec3 x(-1.0 - 0.013 * lane, lane * kLaneWidth + 0.02 * (lane % 5) - 0.04, kHeight);
      scene.bodies.push_back(sphere);
      scene.states.push_back(BodyState::moving(sphere, x, Quat::Identity(), Vec3(speed_, 0.0, 0.0), Vec3::Zero()));
    }
    return scene;
  }
  double duration() const override { return 0.5; }
  void observe(double, const std::vector<BodyState>& states) override {
    through_ = 0;
    for (int lane = 0; lane < kLanes; ++lane) {
      if (!(states[1 + kLanes + lane].x.x() < 0.0)) ++through_;
    }
  }
  std::vector<Measure> measures() const override {
    return {{"spheres through their box", static_cast<double>(through_), 0.0, 0.5,
             "none: a sphere that hits the box's face bounces back; one that tunnels ends beyond it"}};
  }

 private:
  static constexpr int kLanes = 12;
  static constexpr double kLaneWidth = 1.0, kRadius = 0.025, kHeight = 1.0;
  double speed_;
  int through_ = kLanes;
};

// Two equal cubes on ice meeting face to face at 1 m/s each with e = 0.5: they part at e times
// the approach speed, without turning, with their momentum (zero) kept.
class FaceOn : public SuiteScene {
 public:
  std::string name() const override { return "face-on impact, e = 0.5"; }
  Scene scene() const override {
    Scene scene = ground(0.0, 0.0);
    for (const double side : {-1.0, 1.0}) {
      const BodyDescription cube = BodyDescription::box(1.0, Vec3::Constant(kCube), kEpsilon, 0.0);
      scene.bodies.push_back(cube);
      scene.states.push_back(BodyState::moving(cube, Vec3(0.3 * side, 0.0, kTouch), Quat::Identity(),
                                               Vec3(-kSpeed * side, 0.0, 0.0), Vec3::Zero()));
    }
    return scene;
  }
  double duration() const override { return 1.0; }
  void observe(double, const std::vector<BodyState>& states) override {
    parting_ = (states[2].P.x() - states[1].P.x()) / (2.0 * kSpeed);
    keepLargest(turn_, std::max(turned(states[1]), turned(states[2])));
    keepLargest(momentum_, (states[1].P + states[2].P).head<2>().norm());
  }
  std::vector<Measure> measures() const override {
    return {{"parting / approach speed", parting_, kEpsilon, 0.02 * kEpsilon,
             "2 %: the impact is head on, Newton's law of restitution gives it exactly"},
            {"largest turn [deg]", turn_, 0.0, 1.0, "1 degree: the impulses of a face meet the centres, no torque"},
            {"momentum, largest [kg m/s]", momentum_, 0.0, 1e-3, "1e-3: equal and opposite impulses keep it zero"}};
  }

 private:
  static constexpr double kSpeed = 1.0, kEpsilon = 0.5;
  // The angle a body turned from its start (the identity) [degrees]
  static double turned(const BodyState& s) { return 2.0 * std::acos(std::min(1.0, std::abs(s.q.w()))) * 180.0 / M_PI; }
  double parting_ = kNaN, turn_ = 0.0, momentum_ = 0.0;
};

// A cube placed 5 cm into the ground: pushed out, without being thrown into the air.
class OverlapRecovery : public SuiteScene {
 public:
  std::string name() const override { return "overlap recovery, 5 cm"; }
  Scene scene() const override {
    Scene scene = ground(0.0, 0.5);
    scene.bodies.push_back(BodyDescription::box(1.0, Vec3::Constant(kCube), 0.0, 0.5));
    scene.states.push_back(at(Vec3(0.0, 0.0, kCube - 0.05)));
    return scene;
  }
  double duration() const override { return 2.0; }
  void observe(double, const std::vector<BodyState>& states) override {
    const double bottom = lowest(scene_.bodies[1], states[1]);
    keepLargest(jump_, bottom);
    left_ = -bottom;
  }
  std::vector<Measure> measures() const override {
    return {{"highest jump [m]", jump_, 0.0, 0.01, "1 cm: removing overlap must not throw the cube"},
            {"overlap after 2 s [m]", left_, 0.0, 0.005, "5 mm: the overlap is removed, up to the slop"}};
  }

 private:
  Scene scene_ = scene();
  double jump_ = -std::numeric_limits<double>::infinity(), left_ = kNaN;
};

// A row of dominoes, the first leaning: each starts falling (tilts past 20 degrees) after the one
// before it, one at a time.
class Dominoes : public SuiteScene {
 public:
  std::string name() const override { return "dominoes, 8 in a row"; }
  Scene scene() const override {
    Scene scene = ground(0.0, 0.5);
    for (int i = 0; i < kCount; ++i) {
      scene.bodies.push_back(BodyDescription::box(0.1, kHalf, 0.0, 0.5));
      // The first leans 10 degrees towards the others, on its edge
      BodyState s = at(Vec3(kSpacing * i, 0.0, 0.0), Quat(Eigen::AngleAxisd(i == 0 ? 0.175 : 0.0, Vec3::UnitY())));
      s.x.z() = -lowest(scene.bodies.back(), s) - 1e-6;
      scene.states.push_back(s);
    }
    return scene;
  }
  double duration() const override { return 3.0; }
  void observe(double t, const std::vector<BodyState>& states) override {
    for (int i = 0; i < kCount; ++i) {
      if (fell_[i] < 0.0 && tilt(states[i + 1]) > 20.0) fell_[i] = t;
    }
  }
  std::vector<Measure> measures() const override {
    // A domino that never fell, or fell no later than the one before it, is out of order
    int wrong = 0;
    for (int i = 0; i < kCount; ++i) {
      if (fell_[i] < 0.0 || (i > 0 && fell_[i] <= fell_[i - 1])) ++wrong;
    }
    return {{"dominoes out of order", static_cast<double>(wrong), 0.0, 0.5,
             "none: each is pushed by the one before, so it falls a step later at least"}};
  }

 private:
  static constexpr int kCount = 8;
  static constexpr double kSpacing = 0.12;  // centre to centre [m]
  inline static const Vec3 kHalf{0.01, 0.05, 0.1};
  double fell_[kCount] = {-1.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0, -1.0};
};

}  // namespace

std::vector<std::unique_ptr<SuiteScene>> contactSuite() {
  std::vector<std::unique_ptr<SuiteScene>> suite;
  for (const double e : {0.5, 0.9}) {
    suite.push_back(std::make_unique<Drop>("flat drop, e = " + std::to_string(e).substr(0, 3),
                                           BodyDescription::box(1.0, kBoxHalf, e, 0.5), 0.5, e, true));
  }
  // Hitting at 0.9 m/s: a bounce far below the speed one step of gravity adds at 60 Hz, times six
  const double slow = 0.9 * 0.9 / (2.0 * kG);
  suite.push_back(std::make_unique<Drop>("slow flat drop, e = 0.9", BodyDescription::box(1.0, kBoxHalf, 0.9, 0.5),
                                         slow, 0.9, true));
  suite.push_back(std::make_unique<Drop>("slow ball, e = 0.9", BodyDescription::sphere(1.0, 0.1, 0.9, 0.5), slow,
                                         0.9, false));
  suite.push_back(std::make_unique<Drop>("ball, e = 0.5", BodyDescription::sphere(1.0, 0.1, 0.5, 0.5), 1.0, 0.5,
                                         false));
  suite.push_back(std::make_unique<TiltedDrop>(0.5));
  suite.push_back(std::make_unique<Ramp>(24.0, 0.5));
  suite.push_back(std::make_unique<Ramp>(35.0, 0.5));
  suite.push_back(std::make_unique<RollingBall>());
  suite.push_back(std::make_unique<Stack>(10));
  suite.push_back(std::make_unique<HeavyOnLight>());
  suite.push_back(std::make_unique<HeavyRatio>("cube on cube, 1000:1", Vec3::Constant(0.5 * kCube),
                                               Vec3::Constant(kCube)));
  suite.push_back(std::make_unique<HeavyRatio>("plate on cube, 1000:1", Vec3(0.5, 0.5, 0.02), Vec3::Constant(0.5 * kCube)));
  suite.push_back(std::make_unique<HeavyOnPyramid>());
  suite.push_back(std::make_unique<OverlapRecovery>());
  suite.push_back(std::make_unique<Dominoes>());
  for (const double speed : {10.0, 40.0, 100.0}) suite.push_back(std::make_unique<FastSphere>(speed));
  suite.push_back(std::make_unique<FaceOn>());
  return suite;
}

std::vector<std::unique_ptr<SuiteScene>> contactSuite(std::initializer_list<const char*> prefixes) {
  std::vector<std::unique_ptr<SuiteScene>> picked;
  for (std::unique_ptr<SuiteScene>& scene : contactSuite()) {
    const std::string name = scene->name();
    const bool wanted = std::any_of(prefixes.begin(), prefixes.end(),
                                    [&](const char* prefix) { return name.rfind(prefix, 0) == 0; });
    if (wanted) picked.push_back(std::move(scene));
  }
  return picked;
}

std::vector<Measure> runSuiteScene(SuiteScene& scene, SuiteEngine& engine) {
  const int steps = static_cast<int>(std::lround(scene.duration() / kSuiteStep));
  scene.observe(0.0, engine.states());
  for (int k = 1; k <= steps; ++k) {
    engine.step(kSuiteStep);
    scene.observe(k * kSuiteStep, engine.states());
  }
  return scene.measures();
}

std::vector<SpreadMeasure> runSuiteSceneShaken(const std::string& name, const SuiteEngineMaker& make, int runs,
                                               double shift) {
  if (runs < 1) throw InvalidInput("runSuiteSceneShaken needs at least 1 run, got " + std::to_string(runs));
  if (!(shift >= 0.0 && std::isfinite(shift))) {
    throw InvalidInput("runSuiteSceneShaken shift must be finite and >= 0, got " + std::to_string(shift));
  }
  // values[m][r]: measure m of run r; NaN sorts last, so a median or largest that reaches it fails
  std::vector<Measure> first;
  std::vector<std::vector<double>> values;
  for (int run = 0; run < runs; ++run) {
    std::unique_ptr<SuiteScene> scene;
    for (std::unique_ptr<SuiteScene>& candidate : contactSuite()) {
      if (candidate->name() == name) scene = std::move(candidate);
    }
    if (!scene) throw InvalidInput("runSuiteSceneShaken: no suite scene is called '" + name + "'");
    std::unique_ptr<SuiteEngine> made = make(shakenScene(scene->scene(), static_cast<std::uint64_t>(run), shift));
    if (!made) throw InvalidInput("runSuiteSceneShaken: the engine maker returned no engine");
    const std::vector<Measure> measures = runSuiteScene(*scene, *made);
    if (run == 0) {
      first = measures;
      values.resize(measures.size());
    }
    for (std::size_t m = 0; m < measures.size(); ++m) values[m].push_back(measures[m].value);
  }
  std::vector<SpreadMeasure> spread;
  for (std::size_t m = 0; m < first.size(); ++m) {
    std::vector<double>& v = values[m];
    std::sort(v.begin(), v.end(), [](double x, double y) { return !std::isnan(x) && (std::isnan(y) || x < y); });
    SpreadMeasure s;
    s.median = first[m];
    const std::size_t mid = v.size() / 2;
    s.median.value = v.size() % 2 == 1 ? v[mid] : 0.5 * (v[mid - 1] + v[mid]);
    s.largest = v.back();
    spread.push_back(s);
  }
  return spread;
}

}  // namespace physlab
