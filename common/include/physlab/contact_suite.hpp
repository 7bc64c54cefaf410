/// \file contact_suite.hpp
/// \brief Textbook contact scenes with the physical truth each must reproduce (Labs 5 and 6).
///
/// Each scene is a small experiment of the kind a mechanics textbook solves by hand: a box dropped
/// flat must rebound to \f$\epsilon^2\f$ of its drop height without turning, a block on a ramp must
/// stick below the friction angle \f$\arctan\mu\f$ and slide at \f$g(\sin\theta - \mu\cos\theta)\f$
/// above it, a ball thrown without spin must end rolling at \f$\frac57 v_0\f$, a stack must stand.
/// A scene only looks at body states (positions, orientations, momenta) after each step, so the
/// same scene runs in any engine: the tests run it in Lab 5's and Lab 6's World, the benchmark in
/// Bullet and ODE too, all at \f$h = 1/60\f$ s with the same geometry and parameters.
///
/// A scene reports one or more Measure: a value, what physics says it should be, and a tolerance
/// with its reason. The ground is the plane \f$z \le 0\f$ (tilted for the ramps), gravity is
/// \f$(0, 0, -9.81)\f$ m/s\f$^2\f$.
#pragma once

#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "physlab/world.hpp"

namespace physlab {

/// The step every suite scene runs at [s].
constexpr double kSuiteStep = 1.0 / 60.0;

/// One measured quantity of a suite scene against its physical truth.
struct Measure {
  std::string name;       ///< what is measured, e.g. "rebound / drop height"
  double value = 0.0;     ///< what the engine did
  double expected = 0.0;  ///< what physics says
  double tolerance = 0.0; ///< the largest \f$|value - expected|\f$ that passes, > 0
  std::string why;        ///< the tolerance's reason, one line
  /// \f$|value - expected| / tolerance\f$: at most 1 passes (not finite: failed).
  double score() const;
  /// score() <= 1.
  bool pass() const;
};

/// A textbook scene: its bodies, how long it runs, and what it measures after each step.
class SuiteScene {
 public:
  virtual ~SuiteScene() = default;
  /// Short name, e.g. "flat drop, e = 0.5".
  virtual std::string name() const = 0;
  /// The bodies and their initial states.
  virtual Scene scene() const = 0;
  /// Simulated time the scene runs [s].
  virtual double duration() const = 0;
  /// Called with the time [s] and every body's state after each step (before the first step with
  /// t = 0 and the initial states).
  virtual void observe(double t, const std::vector<BodyState>& states) = 0;
  /// What was measured, against the truth.
  virtual std::vector<Measure> measures() const = 0;
  /// How many runs a fair figure takes: 1 where round-off cannot move the measures; a chaotic
  /// scene (the stack) is reported as the median of this many runs of runSuiteSceneShaken().
  virtual int runs() const { return 1; }
};

/// An engine the suite runs in: steps its copy of a Scene and reports every body's state (fixed
/// bodies included, in the Scene's order) as a BodyState. World is one; the benchmark wraps Bullet
/// and ODE.
class SuiteEngine {
 public:
  virtual ~SuiteEngine() = default;
  /// One step of h [s].
  virtual void step(double h) = 0;
  /// Every body's state now.
  virtual std::vector<BodyState> states() const = 0;
};

/// The whole suite, fresh (no observations yet), in a fixed order.
std::vector<std::unique_ptr<SuiteScene>> contactSuite();
/// The scenes of contactSuite() whose names start with one of `prefixes`, in the suite's order.
std::vector<std::unique_ptr<SuiteScene>> contactSuite(std::initializer_list<const char*> prefixes);

/// Runs `scene` in `engine` (made from scene.scene()) for scene.duration() at kSuiteStep and
/// returns its measures. States that stop being finite fail the measures that read them (a value
/// that is not finite never passes).
std::vector<Measure> runSuiteScene(SuiteScene& scene, SuiteEngine& engine);
/// A measure over several runs of one scene: the median run's value and the largest.
struct SpreadMeasure {
  Measure median;  ///< the measure with the median of the runs' values (not finite if any run's was not)
  double largest = 0.0;  ///< the largest of the runs' values (not finite if any run's was not)
};

/// Makes a fresh engine for a Scene (for runSuiteSceneShaken()).
using SuiteEngineMaker = std::function<std::unique_ptr<SuiteEngine>(const Scene&)>;

/// Runs the suite scene called `name` `runs` times, each in a fresh engine from `make`: first as
/// it is, then with every moving body's start shifted by up to `shift` [m] in x and y (uniform,
/// seeded 1, 2, ...), and returns each measure's median and largest value over the runs.
///
/// Why: a tall stack is chaotic. Shifting its cubes by a nanometre, or computing the same
/// impulses in another order, moves where its top sways to by centimetres (Lab 5's World, 2000
/// shifts of the 10-cube stack: largest drift from 0.1 to 15 cm, median 5.0 cm). One run is one
/// draw; the median of several is a property of the engine. Throws InvalidInput for an unknown
/// name, runs < 1, a shift that is negative or not finite, or a maker that returns no engine.
std::vector<SpreadMeasure> runSuiteSceneShaken(const std::string& name, const SuiteEngineMaker& make, int runs = 9,
                                               double shift = 1e-9);

/// A World as a SuiteEngine.
class WorldEngine : public SuiteEngine {
 public:
  explicit WorldEngine(World world) : world_(std::move(world)) {}  ///< takes the World over
  void step(double h) override { world_.step(h); }                   ///< World::step()
  std::vector<BodyState> states() const override { return world_.states(); }  ///< World::states()
  const World& world() const { return world_; }  ///< the World, e.g. for World::describe()

 private:
  World world_;
};

}  // namespace physlab
