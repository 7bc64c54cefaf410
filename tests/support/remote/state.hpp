// The state of the framework's classes that cross the wire (tests/support/remote): a class that is
// not an aggregate lists its members here, and how to make a blank one to read them into. A
// class whose student functions are graded remotely (rigid.hpp: RigidBodySystem; broadphase.hpp:
// the broad phases and the dynamic tree) befriends remote::Access, so that these lists, and the
// worker's table, reach its private members. Lab 2's SpringSystem and ImplicitWorkspace cannot be
// read member by member (they own a workspace, a sparse factorisation): they have codecs of their
// own at the end.
#pragma once

#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "physlab/broadphase.hpp"
#include "physlab/collision.hpp"
#include "physlab/error.hpp"
#include "physlab/resting.hpp"
#include "physlab/rigid.hpp"
#include "physlab/soft_step.hpp"
#include "physlab/springs.hpp"
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
  // What solve() leaves for placeBodies(); its points and sweep order are rebuilt every step
  template <class F>
  static void visit(SoftStepSolver& solver, F&& f) {
    f(solver.settings_);
    f(solver.soft_);
    f(solver.soft_fixed_);
    f(solver.motion_);
    f(solver.dq_);
    f(solver.moved_);
  }
  static SoftStepSolver blank(std::common_type<SoftStepSolver>) { return SoftStepSolver(SoftStepSettings{}); }
  // A step runs in the worker (resting_solve.cpp, IN_WORKER): its settings and what it leaves
  // (the residual); the rows, loads and matrix-free points are rebuilt at every step
  template <class F>
  static void visit(LcpContactSolver& solver, F&& f) {
    f(solver.settings_);
    f(solver.last_residual_);
  }
  static LcpContactSolver blank(std::common_type<LcpContactSolver>) { return LcpContactSolver(RestingSettings{}); }
  /// The force evaluations a worker made on its copy of `system` (handles.hpp).
  static void addEvaluations(const System& system, long evaluations) { system.force_evaluations_ += evaluations; }
  static RigidBody blank(std::common_type<RigidBody>) { return RigidBody(1.0, Mat3::Identity()); }
  static RigidBodySystem blank(std::common_type<RigidBodySystem>) {
    return RigidBodySystem(RigidBody(1.0, Mat3::Identity()));
  }
  // A valid network has a particle: the blanks below are built for one.
  static SpringNetwork oneParticle() {
    SpringNetwork network;
    network.masses = VecX::Ones(1);
    network.rest_positions = Mat3X::Zero(3, 1);
    return network;
  }
  static SpringSystem blank(std::common_type<SpringSystem>) { return SpringSystem(oneParticle()); }
  static ImplicitWorkspace blank(std::common_type<ImplicitWorkspace>) { return ImplicitWorkspace(oneParticle()); }

  /// The pattern of a spring matrix: each spring's particles (a, b), as its network has them.
  using SpringPairs = std::vector<std::pair<Index, Index>>;
  static SpringPairs springPairs(const SpringMatrix& A) {
    SpringPairs pairs;
    pairs.reserve(A.slots_.size());
    for (const SpringMatrix::Slot& slot : A.slots_) {
      const SpringMatrix::Pair& pair = A.pairs_[slot.pair];
      pairs.push_back(slot.transposed ? std::pair{pair.j, pair.i} : std::pair{pair.i, pair.j});
    }
    return pairs;
  }
  /// Lays `A` out for `n` particles joined as `pairs` (checked here: they come off the wire).
  static void rebuild(SpringMatrix& A, Index n, const SpringPairs& pairs) {
    SpringNetwork network;
    network.masses = VecX::Ones(n);
    network.springs.reserve(pairs.size());
    for (const auto& [a, b] : pairs) {
      if (a < 0 || a >= n || b < 0 || b >= n || a == b) {
        throw WireError("a spring (" + std::to_string(a) + ", " + std::to_string(b) + ") among " +
                        std::to_string(n) + " particles");
      }
      network.springs.push_back({a, b, 0.0, 0.0, 0.0});
    }
    A.build(network);
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
  // A step runs in the worker (incremental_pairs.cpp, IN_WORKER): everything it reads or leaves
  // but its scratch lists (leaving_, kept_, found_), which it clears before use
  template <class F>
  static void visit(IncrementalBroadPhase& phase, F&& f) {
    visitBase(phase, f);
    f(phase.margin_);
    f(phase.tree_);
    f(phase.tight_);
    f(phase.fat_);
    f(phase.leaf_);
    f(phase.dirty_);
    f(phase.dirty_list_);
    f(phase.free_ids_);
    f(phase.pair_set_);
    f(phase.reinsertions_);
    f(phase.last_reinsertions_);
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

/// A spring system crosses as its network; the reader builds the system anew from it (inverse
/// masses, its own workspace), as the checker built it.
template <>
struct Codec<SpringSystem> {
  static void put(Writer& out, const SpringSystem& value) { remote::put(out, value.network()); }
  static void get(Reader& in, SpringSystem& value) {
    SpringNetwork network;
    remote::get(in, network);
    try {
      value = SpringSystem(std::move(network));
    } catch (const InvalidInput& why) {
      throw WireError(std::string("a spring network that is not valid: ") + why.what());
    }
  }
};

/// An implicit step's workspace crosses as its matrix's pattern and its vectors (dv is CG's warm
/// start). The matrix's values do not cross: implicitEulerUpdate() refills them from zero every
/// step, and no caller reads them afterwards. A workspace laid out for another pattern (the
/// worker's blank) is laid out anew for the one that comes; each vector must then have 3n entries.
template <>
struct Codec<ImplicitWorkspace> {
  static void put(Writer& out, const ImplicitWorkspace& value) {
    remote::put(out, value.A.count());
    remote::put(out, Access<0>::springPairs(value.A));
    for (const VecX* v : {&value.b, &value.Kv, &value.dv, &value.Adv}) remote::put(out, *v);
  }
  static void get(Reader& in, ImplicitWorkspace& value) {
    Index n = 0;
    Access<0>::SpringPairs pairs;
    remote::get(in, n);
    remote::get(in, pairs);
    // The four vectors of 3n entries that follow bound n before anything is sized by it.
    constexpr std::size_t kBytesPerParticle = 4 * 3 * sizeof(double);
    if (n < 1 || static_cast<std::size_t>(n) > in.remaining() / kBytesPerParticle) {
      throw WireError("a workspace of " + std::to_string(n) + " particles");
    }
    if (n != value.A.count() || pairs != Access<0>::springPairs(value.A)) Access<0>::rebuild(value.A, n, pairs);
    for (VecX* v : {&value.b, &value.Kv, &value.dv, &value.Adv}) {
      remote::get(in, *v);
      if (v->size() != 3 * n) {
        throw WireError("a workspace vector of " + std::to_string(v->size()) + " entries for " +
                        std::to_string(n) + " particles");
      }
    }
  }
};

}  // namespace physlab::remote
