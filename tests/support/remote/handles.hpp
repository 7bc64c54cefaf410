// Objects that cross the wire as code, not data (docs/grading.md, "Where submitted code runs").
//
// Lab 1's student functions take a System, or a ParticleSystem whose forces may be of any kind,
// including classes the tests define: the worker cannot rebuild those. So the checker *lends*
// them: it keeps a table of the objects it handed over during the current outermost call, and
// sends a handle (the object's index in that table) with what never changes (sizes, name). The
// worker builds a stand-in (RemoteSystem, RemoteForce) whose virtual methods send a Callback
// (handle, method, arguments) and wait for its Answer; the checker runs the real object's public
// method, so that it counts (System::velocityRate counts force evaluations) and may itself call
// student functions (a nested request, served by the worker while it waits). A callback reaches
// only what the checker lent during the current call: any other handle, an unknown method or
// arguments that do not read back are a WireError, and the test fails.
//
// The lab's own forces (UniformGravity, ..., Boids) and CurlNoise hold constant public
// parameters: they cross as data, their constructors' arguments (Parameters), both as the object
// of a member function and inside a ParticleSystem, which crosses as its masses and forces.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "physlab/curl_noise.hpp"
#include "physlab/neighbours.hpp"
#include "physlab/particles.hpp"
#include "physlab/scenes.hpp"
#include "physlab/system.hpp"
#include "remote.hpp"
#include "state.hpp"
#include "wire.hpp"

namespace physlab::remote {

/// The methods a callback may name.
enum class Method : std::uint8_t {
  PositionRate = 0,  ///< System::positionRate(X) -> qdot
  VelocityRate,      ///< System::velocityRate(X) -> pdot (counts a force evaluation)
  Jacobian,          ///< System::jacobian(X) -> J
  Project,           ///< System::project(X), X back
  Accumulate,        ///< Force::accumulate(s, F), F back
  Potential,         ///< Force::potential(s) -> U
  AddJacobians,      ///< Force::addJacobians(s, dF_dx, dF_dv) -> bool, both back
};

// ---- checker side ---------------------------------------------------------------------------------

/// Lends `system` (or `force`, acting on a system of `particles` particles) until the outermost
/// call in progress ends; returns its handle.
std::uint32_t lend(const System& system);
std::uint32_t lend(const Force& force, Index particles);
/// Forgets every handle (exchange(), when its outermost call ends).
void forgetHandles();
/// Runs the callback that `in` holds on the object it names and writes its answer as respond()
/// does. Throws WireError for a handle not lent during this call, an unknown method, or arguments
/// that do not read back exactly.
void answerCallback(Reader& in, Writer& out);

// ---- the lab's classes that cross as their constructors' arguments --------------------------------

template <class T>
struct Parameters;
template <>
struct Parameters<UniformGravity> {
  static std::tuple<Vec3> of(const UniformGravity& f) { return {f.g}; }
};
template <>
struct Parameters<NBodyGravity> {
  static std::tuple<double, double> of(const NBodyGravity& f) { return {f.G, f.softening}; }
};
template <>
struct Parameters<ViscousDrag> {
  static std::tuple<double> of(const ViscousDrag& f) { return {f.d}; }
};
template <>
struct Parameters<DampedSpring> {
  static std::tuple<Index, Index, double, double, double> of(const DampedSpring& f) {
    return {f.a, f.b, f.rest, f.ks, f.kd};
  }
};
template <>
struct Parameters<LennardJones> {
  static std::tuple<double, double> of(const LennardJones& f) { return {f.epsilon, f.sigma}; }
};
template <>
struct Parameters<CutoffLennardJones> {
  static std::tuple<double, double, double> of(const CutoffLennardJones& f) { return {f.epsilon, f.sigma, f.cutoff}; }
};
template <>
struct Parameters<Boids> {
  static std::tuple<double, double, double, double> of(const Boids& f) {
    return {f.radius, f.separation, f.alignment, f.cohesion};
  }
};
template <>
struct Parameters<HarmonicOscillator> {
  static std::tuple<double> of(const HarmonicOscillator& s) { return {s.omega}; }
};
template <>
struct Parameters<Kepler> {
  static std::tuple<double> of(const Kepler& s) { return {s.mu}; }
};
template <>
struct Parameters<CurlNoise> {
  static std::tuple<std::vector<NoiseWave>, Vec3, double, double, double> of(const CurlNoise& f) {
    return {f.waves, f.centre, f.radius, f.ramp_width, f.step};
  }
};

template <class T, class = void>
struct HasParameters : std::false_type {};
template <class T>
struct HasParameters<T, std::void_t<decltype(Parameters<T>::of(std::declval<const T&>()))>> : std::true_type {};

template <class T>
struct Codec<T, std::enable_if_t<HasParameters<T>::value>> {
  static void put(Writer& out, const T& value) {
    std::apply([&](const auto&... p) { (remote::put(out, p), ...); }, Parameters<T>::of(value));
  }
};

/// The worker's copy: built by the class's own constructor from the arguments that came.
template <class T>
class Arg<T, std::enable_if_t<HasParameters<T>::value>> {
 public:
  explicit Arg(Reader& in) : value_(build(in)) {}
  const T& operator*() const { return value_; }

  static T build(Reader& in) {
    decltype(Parameters<T>::of(std::declval<const T&>())) p;
    std::apply([&](auto&... each) { (remote::get(in, each), ...); }, p);
    return std::make_from_tuple<T>(std::move(p));
  }

 private:
  T value_;
};

// ---- views ------------------------------------------------------------------------------------------

/// A ParticleView goes as its positions, velocities and masses.
template <>
struct Codec<ParticleView> {
  static void put(Writer& out, const ParticleView& s) {
    remote::put(out, s.x);
    remote::put(out, s.v);
    remote::put(out, s.m);
  }
};

template <class T>
T readValue(Reader& in) {
  T value{};
  get(in, value);
  return value;
}

template <>
class Arg<ParticleView> {
 public:
  explicit Arg(Reader& in)
      : x_(readValue<Mat3X>(in)),
        v_(readValue<Mat3X>(in)),
        m_(readValue<VecX>(in)),
        view_{ConstPoints(x_.data(), 3, x_.cols()), ConstPoints(v_.data(), 3, v_.cols()), m_} {}
  Arg(const Arg&) = delete;
  Arg& operator=(const Arg&) = delete;
  const ParticleView& operator*() const { return view_; }

 private:
  Mat3X x_, v_;
  VecX m_;
  ParticleView view_;
};

/// Points (writable) and ConstPoints: the matrix they show, read into one the view maps.
template <class M>
class Arg<Eigen::Map<M>> {
 public:
  explicit Arg(Reader& in) : value_(readValue<Mat3X>(in)) {}
  Eigen::Map<M> operator*() { return Eigen::Map<M>(value_.data(), 3, value_.cols()); }
  void back(Writer& out) const { put(out, value_); }

 private:
  Mat3X value_;
};

// ---- handles ----------------------------------------------------------------------------------------

/// A System: the framework's own (HarmonicOscillator, Kepler, ParticleSystem) as data, which the
/// worker evaluates without a callback; any other as a handle, with its sizes and name.
template <>
struct Codec<System> {
  static void put(Writer& out, const System& system);
};

/// The worker's stand-in of a lent System: every derivative, Jacobian and projection is the
/// checker's, through a callback.
class RemoteSystem final : public System {
 public:
  explicit RemoteSystem(Reader& in);
  Index positionSize() const override { return position_size_; }
  Index velocitySize() const override { return velocity_size_; }
  std::string name() const override { return name_; }
  bool positionRateIsVelocity() const override { return rate_is_velocity_; }
  void project(VecX& X) const override;

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override;
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override;
  bool computeJacobian(const VecX& X, MatX& J) const override;

 private:
  /// A rate (position or velocity) computed by the lent system, through a callback.
  void rate(Method method, const VecX& X, Eigen::Ref<VecX> out) const;
  std::uint32_t handle_ = 0;
  Index position_size_ = 0;
  Index velocity_size_ = 0;
  bool rate_is_velocity_ = false;
  std::string name_;
};

/// The worker's System: a copy, or a stand-in. back() writes the force evaluations made on a copy
/// (those made through a stand-in were counted in the checker as they were made).
template <>
class Arg<System> {
 public:
  explicit Arg(Reader& in);
  const System& operator*() const { return *value_; }
  void back(Writer& out) const;

 private:
  std::unique_ptr<System> value_;
  bool copy_ = false;
};

/// The checker's side of Arg<System>::back(): the evaluations the worker made on its copy are
/// counted on `system`, as if they had been made here.
void addEvaluations(Call& call, const System& system);

/// The worker's stand-in of a lent Force (one of a ParticleSystem's that is not the lab's own).
class RemoteForce final : public Force {
 public:
  explicit RemoteForce(Reader& in);
  std::string name() const override { return name_; }
  void accumulate(const ParticleView& s, Points F) const override;
  double potential(const ParticleView& s) const override;
  bool addJacobians(const ParticleView& s, MatX& dF_dx, MatX& dF_dv) const override;
  std::optional<Vec3> uniformAcceleration() const override { return uniform_acceleration_; }

 private:
  std::uint32_t handle_ = 0;
  std::string name_;
  std::optional<Vec3> uniform_acceleration_;
};

/// A force of a ParticleSystem: the lab's own classes as data, any other as a handle.
void putForce(Writer& out, const Force& force, Index particles);
std::shared_ptr<const Force> takeForce(Reader& in);

/// A ParticleSystem goes as its masses and its forces, in the order they were added.
template <>
struct Codec<ParticleSystem> {
  static void put(Writer& out, const ParticleSystem& system) {
    remote::put(out, system.masses());
    remote::put(out, static_cast<std::uint64_t>(system.forces().size()));
    for (const auto& force : system.forces()) putForce(out, *force, system.count());
  }
};

template <>
class Arg<ParticleSystem> {
 public:
  explicit Arg(Reader& in);
  const ParticleSystem& operator*() const { return value_; }

 private:
  ParticleSystem value_;
};

}  // namespace physlab::remote
