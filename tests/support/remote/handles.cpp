// Handles and callbacks (handles.hpp): the checker's table of lent objects and its answers, the
// worker's stand-ins that call back.
#include "handles.hpp"

#include <memory>
#include <string>
#include <type_traits>

namespace physlab::remote {

namespace {

// What the checker has lent during the current outermost call: a system, or a force with the
// number of particles of the system it acts in (the checker's code trusts a view's sizes).
struct Lent {
  const System* system = nullptr;
  const Force* force = nullptr;
  Index particles = 0;
};

std::vector<Lent>& lent() {
  static std::vector<Lent> table;
  return table;
}

std::uint32_t lendEntry(Lent entry) {
  lent().push_back(entry);
  return static_cast<std::uint32_t>(lent().size() - 1);
}

// The arguments of a callback end where the message does.
void readAll(const Reader& in) {
  if (in.remaining() != 0) throw WireError("a callback with " + std::to_string(in.remaining()) + " bytes too many");
}

void answerSystem(const System& system, Method method, Reader& in, Writer& out) {
  switch (method) {
    case Method::PositionRate:
    case Method::VelocityRate: {
      const auto X = readValue<VecX>(in);
      readAll(in);
      const bool position = method == Method::PositionRate;
      VecX rate(position ? system.positionSize() : system.velocitySize());
      respond(
          out, [&] { position ? system.positionRate(X, rate) : system.velocityRate(X, rate); },
          [&] { put(out, rate); });
      return;
    }
    case Method::Jacobian: {
      const auto X = readValue<VecX>(in);
      readAll(in);
      respond(out, [&] { return system.jacobian(X); }, [] {});
      return;
    }
    case Method::Project: {
      auto X = readValue<VecX>(in);
      readAll(in);
      if (X.size() != system.size()) throw WireError("a state of " + std::to_string(X.size()) + " entries to project");
      respond(out, [&] { system.project(X); }, [&] { put(out, X); });
      return;
    }
    default: break;
  }
  throw WireError("a callback of method " + std::to_string(static_cast<int>(method)) + " on a system");
}

// Reads a matrix of the size the callback's particles need.
template <class M>
M readSized(Reader& in, Index rows, Index cols, const char* what) {
  auto value = readValue<M>(in);
  if (value.rows() != rows || value.cols() != cols) throw WireError(std::string(what) + " of the wrong size");
  return value;
}

void answerForce(const Force& force, Index n, Method method, Reader& in, Writer& out) {
  const Arg<ParticleView> s(in);
  if ((*s).x.cols() != n || (*s).v.cols() != n || (*s).m.size() != n) {
    throw WireError("a view of other than the " + std::to_string(n) + " particles the force acts on");
  }
  switch (method) {
    case Method::Accumulate: {
      auto F = readSized<Mat3X>(in, 3, n, "a force total");
      readAll(in);
      respond(out, [&] { force.accumulate(*s, Points(F.data(), 3, F.cols())); }, [&] { put(out, F); });
      return;
    }
    case Method::Potential:
      readAll(in);
      respond(out, [&] { return force.potential(*s); }, [] {});
      return;
    case Method::AddJacobians: {
      auto dF_dx = readSized<MatX>(in, 3 * n, 3 * n, "a Jacobian");
      auto dF_dv = readSized<MatX>(in, 3 * n, 3 * n, "a Jacobian");
      readAll(in);
      respond(out, [&] { return force.addJacobians(*s, dF_dx, dF_dv); }, [&] {
        put(out, dF_dx);
        put(out, dF_dv);
      });
      return;
    }
    default: break;
  }
  throw WireError("a callback of method " + std::to_string(static_cast<int>(method)) + " on a force");
}

// The worker's side of one callback: the answer, read as respond() wrote it.
class Answer {
 public:
  explicit Answer(Writer& callback) : bytes_(callBack(callback)), in_(bytes_.data(), bytes_.size()) {
    get(in_, ending_);
  }
  template <class T>
  void back(T& value) {
    get(in_, value);
  }
  /// The method's result, or the exception it threw in the checker, thrown here.
  template <class R>
  R result() {
    if (ending_ == Ending::Threw) {
      Family family = Family::Other;
      std::string message;
      get(in_, family);
      get(in_, message);
      rethrow(family, message);
    }
    if constexpr (std::is_void_v<R>) {
      return;
    } else {
      R value{};
      get(in_, value);
      return value;
    }
  }

 private:
  std::vector<char> bytes_;
  Reader in_;
  Ending ending_ = Ending::Returned;
};

template <class... A>
Writer callback(std::uint32_t handle, Method method, const A&... arguments) {
  Writer out;
  put(out, handle);
  put(out, method);
  (put(out, arguments), ...);
  return out;
}

// A view's entries back from the checker, at the size the view has (the checker's code may not
// resize what it was lent).
template <class View, class Plain>
void assign(View&& view, const Plain& value) {
  if (value.rows() != view.rows() || value.cols() != view.cols()) throw WireError("a callback's view came back resized");
  view = value;
}

}  // namespace

std::uint32_t lend(const System& system) { return lendEntry({&system, nullptr, 0}); }

std::uint32_t lend(const Force& force, Index particles) { return lendEntry({nullptr, &force, particles}); }

void forgetHandles() { lent().clear(); }

void answerCallback(Reader& in, Writer& out) {
  std::uint32_t handle = 0;
  Method method{};
  get(in, handle);
  get(in, method);
  if (handle >= lent().size()) {
    throw WireError("a callback to handle " + std::to_string(handle) + ", which this call did not hand over");
  }
  const Lent entry = lent()[handle];
  if (entry.system) {
    answerSystem(*entry.system, method, in, out);
  } else {
    answerForce(*entry.force, entry.particles, method, in, out);
  }
}

RemoteSystem::RemoteSystem(Reader& in) {
  get(in, handle_);
  get(in, position_size_);
  get(in, velocity_size_);
  get(in, rate_is_velocity_);
  get(in, name_);
}

void RemoteSystem::computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const {
  rate(Method::PositionRate, X, qdot);
}

void RemoteSystem::computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const {
  rate(Method::VelocityRate, X, pdot);
}

void RemoteSystem::rate(Method method, const VecX& X, Eigen::Ref<VecX> out) const {
  Writer call = callback(handle_, method, X);
  Answer answer(call);
  VecX rate;
  answer.back(rate);
  answer.result<void>();
  assign(out, rate);
}

bool RemoteSystem::computeJacobian(const VecX& X, MatX& J) const {
  Writer call = callback(handle_, Method::Jacobian, X);
  Answer answer(call);
  const MatX jacobian = answer.result<MatX>();
  assign(J, jacobian);
  return true;
}

void RemoteSystem::project(VecX& X) const {
  Writer call = callback(handle_, Method::Project, X);
  Answer answer(call);
  VecX projected;
  answer.back(projected);
  answer.result<void>();
  assign(X, projected);
}

RemoteForce::RemoteForce(Reader& in) {
  get(in, handle_);
  get(in, name_);
  get(in, uniform_acceleration_);
}

void RemoteForce::accumulate(const ParticleView& s, Points F) const {
  Writer call = callback(handle_, Method::Accumulate, s, F);
  Answer answer(call);
  Mat3X total;
  answer.back(total);
  answer.result<void>();
  assign(F, total);
}

double RemoteForce::potential(const ParticleView& s) const {
  Writer call = callback(handle_, Method::Potential, s);
  Answer answer(call);
  return answer.result<double>();
}

bool RemoteForce::addJacobians(const ParticleView& s, MatX& dF_dx, MatX& dF_dv) const {
  Writer call = callback(handle_, Method::AddJacobians, s, dF_dx, dF_dv);
  Answer answer(call);
  MatX dx, dv;
  answer.back(dx);
  answer.back(dv);
  const bool added = answer.result<bool>();
  assign(dF_dx, dx);
  assign(dF_dv, dv);
  return added;
}

namespace {

// The lab's own forces, by their tag on the wire (0 is a handle).
template <class... F>
struct ForceKinds {
  static bool put(Writer& out, const Force& force) {
    std::uint8_t tag = 0;
    return (putIf<F>(out, force, ++tag) || ...);
  }
  static std::shared_ptr<const Force> take(Reader& in, std::uint8_t tag) {
    std::uint8_t at = 0;
    std::shared_ptr<const Force> made;
    static_cast<void>(((++at == tag ? (made = std::make_shared<F>(Arg<F>::build(in)), true) : false) || ...));
    if (!made) throw WireError("a force of kind " + std::to_string(tag));
    return made;
  }
  template <class One>
  static bool putIf(Writer& out, const Force& force, std::uint8_t tag) {
    const auto* one = dynamic_cast<const One*>(&force);  // each is final: a match is the exact class
    if (!one) return false;
    remote::put(out, tag);
    remote::put(out, *one);
    return true;
  }
};
using LabForces = ForceKinds<UniformGravity, NBodyGravity, ViscousDrag, DampedSpring, LennardJones, CutoffLennardJones, Boids>;

}  // namespace

void putForce(Writer& out, const Force& force, Index particles) {
  if (LabForces::put(out, force)) return;
  put(out, std::uint8_t{0});
  put(out, lend(force, particles));
  put(out, force.name());
  put(out, force.uniformAcceleration());
}

std::shared_ptr<const Force> takeForce(Reader& in) {
  std::uint8_t tag = 0;
  get(in, tag);
  if (tag == 0) return std::make_shared<RemoteForce>(in);
  return LabForces::take(in, tag);
}

void Codec<System>::put(Writer& out, const System& system) {
  // Each is final: a match is the exact class.
  if (const auto* oscillator = dynamic_cast<const HarmonicOscillator*>(&system)) {
    remote::put(out, std::uint8_t{1});
    remote::put(out, *oscillator);
  } else if (const auto* kepler = dynamic_cast<const Kepler*>(&system)) {
    remote::put(out, std::uint8_t{2});
    remote::put(out, *kepler);
  } else if (const auto* particles = dynamic_cast<const ParticleSystem*>(&system)) {
    remote::put(out, std::uint8_t{3});
    remote::put(out, *particles);
  } else {
    remote::put(out, std::uint8_t{0});
    remote::put(out, lend(system));
    remote::put(out, system.positionSize());
    remote::put(out, system.velocitySize());
    remote::put(out, system.positionRateIsVelocity());
    remote::put(out, system.name());
  }
}

Arg<System>::Arg(Reader& in) {
  std::uint8_t kind = 0;
  get(in, kind);
  copy_ = kind != 0;
  switch (kind) {
    case 0: value_ = std::make_unique<RemoteSystem>(in); return;
    case 1: value_ = std::make_unique<HarmonicOscillator>(Arg<HarmonicOscillator>::build(in)); return;
    case 2: value_ = std::make_unique<Kepler>(Arg<Kepler>::build(in)); return;
    case 3: value_ = std::make_unique<ParticleSystem>(*Arg<ParticleSystem>(in)); return;
    default: throw WireError("a system of kind " + std::to_string(kind));
  }
}

void Arg<System>::back(Writer& out) const { put(out, copy_ ? value_->forceEvaluations() : 0L); }

void addEvaluations(Call& call, const System& system) {
  long evaluations = 0;
  call.back(evaluations);
  // No call makes 2^40 evaluations; the bound keeps the checker's sum from overflowing.
  if (evaluations < 0 || evaluations > (1L << 40)) throw WireError("a count of " + std::to_string(evaluations) + " force evaluations");
  Access<0>::addEvaluations(system, evaluations);
}

Arg<ParticleSystem>::Arg(Reader& in) : value_(readValue<VecX>(in)) {
  const std::size_t forces = in.count(1);
  for (std::size_t k = 0; k < forces; ++k) value_.addForce(takeForce(in));
}

}  // namespace physlab::remote
