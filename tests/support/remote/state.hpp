// The state of the framework's classes that cross the wire (tests/support/remote): a class that is
// not an aggregate lists its members here, and how to make a blank one to read them into. A
// class whose student functions are graded remotely (rigid.hpp: RigidBodySystem) befriends
// remote::Access, so that these lists, and the worker's table, reach its private members.
#pragma once

#include <type_traits>
#include <utility>

#include "physlab/rigid.hpp"
#include "wire.hpp"

namespace physlab::remote {

/// Access<0>: the members of each class below, and a blank one (valid, to be overwritten).
template <>
struct Access<0> {
  template <class F>
  static void visit(RigidBody& body, F&& f) {
    f(body.mass);
    f(body.inertia_body);
    f(body.inertia_body_inv);
  }
  template <class F>
  static void visit(RigidBodySystem& system, F&& f) {
    f(system.body_);
    f(system.forces_);
    f(system.gravity_);
    f(system.renormalize_);
  }
  /// The force evaluations a worker made on its copy of `system` (handles.hpp).
  static void addEvaluations(const System& system, long evaluations) { system.force_evaluations_ += evaluations; }
  static RigidBody blank(std::common_type<RigidBody>) { return RigidBody(1.0, Mat3::Identity()); }
  static RigidBodySystem blank(std::common_type<RigidBodySystem>) {
    return RigidBodySystem(RigidBody(1.0, Mat3::Identity()));
  }
};

/// A blank T to read into: T{} for what has a default constructor, Access<0>::blank otherwise.
template <class T>
T blank() {
  if constexpr (std::is_default_constructible_v<T>) {
    return T{};
  } else {
    return Access<0>::blank(std::common_type<T>{});
  }
}

/// What the worker reads an argument of type T into: by default a T, read in place; handles.hpp
/// gives the types that are views or handles a holder of what they refer to. *arg is the argument
/// the student's function gets, back() writes it into the reply.
template <class T, class = void>
class Arg {
 public:
  explicit Arg(Reader& in) : value_(blank<T>()) { get(in, value_); }
  T& operator*() { return value_; }
  void back(Writer& out) const { put(out, value_); }

 private:
  T value_;
};

struct IgnoreMember {
  template <class M>
  void operator()(M&) const {}
};
template <class T, class = void>
struct HasState : std::false_type {};
template <class T>
struct HasState<T, std::void_t<decltype(Access<0>::visit(std::declval<T&>(), IgnoreMember{}))>> : std::true_type {};

/// Classes with a state list: member by member.
template <class T>
struct Codec<T, std::enable_if_t<HasState<T>::value>> {
  static void put(Writer& out, const T& value) {
    Access<0>::visit(const_cast<T&>(value), [&](const auto& member) { remote::put(out, member); });
  }
  static void get(Reader& in, T& value) {
    Access<0>::visit(value, [&](auto& member) { remote::get(in, member); });
  }
};

}  // namespace physlab::remote
