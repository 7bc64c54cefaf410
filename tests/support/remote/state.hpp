// The state of the framework's classes that cross the wire (tests/support/remote): a class that is
// not an aggregate lists its members here, and how to make a blank one to read them into. A
// class whose student functions are graded remotely (rigid.hpp: RigidBodySystem; broadphase.hpp:
// the broad phases and the dynamic tree) befriends remote::Access, so that these lists, and the
// worker's table, reach its private members.
#pragma once

#include <type_traits>
#include <utility>

#include "physlab/broadphase.hpp"
#include "physlab/collision.hpp"
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
  static RigidBody blank(std::common_type<RigidBody>) { return RigidBody(1.0, Mat3::Identity()); }
  static RigidBodySystem blank(std::common_type<RigidBodySystem>) {
    return RigidBodySystem(RigidBody(1.0, Mat3::Identity()));
  }

  // Lab 4's shapes (collision.hpp): public members, but constructors that check them, so no
  // aggregates. A shape crosses as it is, checked or not: the student's functions check it.
  template <class F>
  static void visit(Sphere& sphere, F&& f) {
    f(sphere.radius);
  }
  template <class F>
  static void visit(Box& box, F&& f) {
    f(box.half_extents);
  }
  template <class F>
  static void visit(Capsule& capsule, F&& f) {
    f(capsule.radius);
    f(capsule.half_height);
  }
  template <class F>
  static void visit(Plane& plane, F&& f) {
    f(plane.normal);
    f(plane.offset);
  }
  template <class F>
  static void visit(ConvexPolyhedron& polyhedron, F&& f) {
    f(polyhedron.vertices);
    f(polyhedron.faces);
    f(polyhedron.normals);
    f(polyhedron.offsets);
    f(polyhedron.edges);
  }
  template <class F>
  static void visit(Triangle& triangle, F&& f) {
    f(triangle.corners);
  }
  static Sphere blank(std::common_type<Sphere>) { return Sphere(1.0); }
  static Box blank(std::common_type<Box>) { return Box(Vec3::Ones()); }
  static Capsule blank(std::common_type<Capsule>) { return Capsule(1.0, 1.0); }
  static Plane blank(std::common_type<Plane>) { return Plane(Vec3::UnitZ(), 0.0); }
  static ConvexPolyhedron blank(std::common_type<ConvexPolyhedron>) { return ConvexPolyhedron::box(Vec3::Ones()); }
  static Triangle blank(std::common_type<Triangle>) { return Triangle(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()); }
  static Shape blank(std::common_type<Shape>) { return blank(std::common_type<Sphere>{}); }

  // Lab 4's broad phases (broadphase.hpp): every member, working buffers included, so that an
  // object comes back exactly as the student's function left it; and the test count of
  // BroadPhase, which their test() raises.
  template <class F>
  static void visit(SweepAndPrune& phase, F&& f) {
    visitBase(phase, f);
    f(phase.entries_);
    f(phase.axis_);
    f(phase.swaps_);
  }
  template <class F>
  static void visit(UniformGrid& phase, F&& f) {
    visitBase(phase, f);
    f(phase.bucket_start_);
    f(phase.cell_entries_);
    f(phase.oversized_);
    f(phase.is_oversized_);
    f(phase.edges_);
    f(phase.cell_size_);
  }
  template <class F>
  static void visit(Bvh& phase, F&& f) {
    visitBase(phase, f);
    f(phase.nodes_);
    f(phase.order_);
    f(phase.stack_);
  }
  template <class F>
  static void visit(KdTree& phase, F&& f) {
    visitBase(phase, f);
    f(phase.lists_);
    f(phase.keys_);
    f(phase.leaves_);
  }
  template <class F>
  static void visit(DynamicAabbTree& tree, F&& f) {
    Changes<DynamicAabbTree::Node> nodes(tree.nodes_);  // a pool of which a call changes a few nodes
    f(nodes);
    f(tree.stack_);
    f(tree.root_);
    f(tree.free_);
    f(tree.leaves_);
  }

 private:
  template <class F>
  static void visitBase(BroadPhase& phase, F& f) {
    f(phase.tests_);
  }
};

/// A blank T to read into (wire.hpp): T{} for what has a default constructor, Access<0>::blank
/// otherwise.
template <class T>
T blank() {
  if constexpr (std::is_default_constructible_v<T>) {
    return T{};
  } else {
    return Access<0>::blank(std::common_type<T>{});
  }
}

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
