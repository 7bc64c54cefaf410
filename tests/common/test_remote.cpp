// The wire between a checker and its worker (tests/support/remote): what crosses comes back as it
// was, and what a hostile worker sends is refused with an error, never read past its end.
#include <catch2/catch.hpp>

#include <cstdlib>

#include "physlab/collision.hpp"
#include "physlab/lcp.hpp"
#include "physlab/resting.hpp"
#include "physlab/soft_step.hpp"
#include "physlab/springs.hpp"
#include "physlab/timewarp.hpp"
#include "physlab/world.hpp"
#include "physlab/scenes.hpp"
#include "remote/handles.hpp"
#include "remote/remote.hpp"
#include "remote/state.hpp"
#include "support.hpp"

namespace {

using namespace physlab;
using physlab::remote::Reader;
using physlab::remote::WireError;
using physlab::remote::Writer;

template <class T>
std::vector<char> bytesOf(const T& value) {
  Writer out;
  remote::put(out, value);
  return out.buffer();
}

template <class T>
T readBack(const std::vector<char>& bytes) {
  Reader in(bytes.data(), bytes.size());
  T value{};
  remote::get(in, value);
  REQUIRE(in.remaining() == 0);
  return value;
}

Contact randomContact() {
  Contact c;
  c.a = static_cast<int>(test::uniform(0, 100));
  c.b = -static_cast<int>(test::uniform(0, 100));
  c.p = test::randomVec3(5.0);
  c.n = test::randomVec3(1.0).normalized();
  c.depth = test::uniform(-1, 1);
  c.id = static_cast<std::uint32_t>(test::uniform(0, 4e9));
  c.epsilon = test::uniform(0, 1);
  c.mu = test::uniform(0, 1);
  c.v_rel_minus = test::uniform(-3, 3);
  c.kind = ContactKind::Resting;
  c.j = test::uniform(0, 2);
  c.j_t = test::randomVec3(1.0);
  c.r_a = test::randomVec3(1.0);
  c.r_b = test::randomVec3(1.0);
  c.K_matrix = test::randomRotation();
  return c;
}

// A system of the tests' own (the worker cannot rebuild it): p-dot = -q, and when `nested`, -2q
// computed by the worker's `twice` (tests/support/remote/test_worker.cpp) while the worker waits
// for this callback's answer.
class Callable final : public System {
 public:
  explicit Callable(bool nested = false) : nested_(nested) {}
  Index positionSize() const override { return 1; }
  Index velocitySize() const override { return 1; }
  std::string name() const override { return "callable"; }

 protected:
  void computePositionRate(const VecX& X, Eigen::Ref<VecX> qdot) const override { qdot[0] = X[1]; }
  void computeVelocityRate(const VecX& X, Eigen::Ref<VecX> pdot) const override {
    if (!nested_) {
      pdot[0] = -X[0];
      return;
    }
    remote::Call call(1, "twice");
    call.in(X[0]);
    call.send();
    pdot[0] = -call.result<double>();
  }

 private:
  bool nested_;
};

// The handle a system crosses as: the worker's view of the request's first bytes.
std::uint32_t handleOf(const System& system) {
  Writer out;
  remote::put(out, system);
  Reader in(out.buffer().data(), out.buffer().size());
  std::uint8_t kind = 1;
  std::uint32_t handle = 0;
  remote::get(in, kind);
  remote::get(in, handle);
  REQUIRE(kind == 0);
  return handle;
}

std::vector<char> callbackOf(std::uint32_t handle, remote::Method method, const VecX& X) {
  Writer out;
  remote::put(out, handle);
  remote::put(out, method);
  remote::put(out, X);
  return out.buffer();
}

}  // namespace

TEST_CASE("remote wire: aggregates, matrices and vectors come back as they were", "[common]") {
  SECTION("a fixed contact, member by member") {
    Contact c;
    c.a = 3;
    c.b = 7;
    c.p = Vec3(1, 2, 3);
    c.id = 0xdeadbeef;
    c.kind = ContactKind::Colliding;
    c.j_t = Vec3(0, -0.5, 0.25);
    c.K_matrix << 1, 2, 3, 4, 5, 6, 7, 8, 9;
    const Contact back = readBack<Contact>(bytesOf(c));
    CHECK(back.a == 3);
    CHECK(back.b == 7);
    CHECK(back.p == c.p);
    CHECK(back.id == 0xdeadbeef);
    CHECK(back.kind == ContactKind::Colliding);
    CHECK(back.j_t == c.j_t);
    CHECK(back.K_matrix == c.K_matrix);
    // 15 members: 2 int, 5 Vec3 (sizes, entries), 5 double, a uint32, an enum (int) and a Mat3, no padding
    CHECK(bytesOf(c).size() == 2 * 4 + 5 * (16 + 24) + 5 * 8 + 4 + 4 + (16 + 72));
  }
  SECTION("seeded contacts, bodies, settings and LCP data: written again, the same bytes") {
    std::vector<Contact> contacts(5);
    for (auto& c : contacts) c = randomContact();
    const auto bytes = bytesOf(contacts);
    CHECK(bytesOf(readBack<std::vector<Contact>>(bytes)) == bytes);
    ContactBody body{test::randomVec3(1), test::randomVec3(1), test::randomVec3(1), test::uniform(0, 1), test::randomRotation()};
    CHECK(bytesOf(readBack<ContactBody>(bytesOf(body))) == bytesOf(body));
    Settings settings;
    settings.method = ResponseMethod::Simultaneous;
    settings.warm_start = false;
    settings.gravity = test::randomVec3(10);
    const Settings settings_back = readBack<Settings>(bytesOf(settings));
    CHECK(settings_back.method == ResponseMethod::Simultaneous);
    CHECK_FALSE(settings_back.warm_start);
    CHECK(settings_back.gravity == settings.gravity);
    LcpOptions options;
    options.initial = VecX::Random(7);
    CHECK(readBack<LcpOptions>(bytesOf(options)).initial == options.initial);
    LcpProblem problem{MatX::Random(4, 3), VecX::Random(4)};
    const LcpProblem problem_back = readBack<LcpProblem>(bytesOf(problem));
    CHECK(problem_back.A == problem.A);
    CHECK(problem_back.b == problem.b);
    TimewarpRollback rollback{0.5, 1, 2, {1, 4, 9}, {0.1, 0.2, 0.3}};
    CHECK(readBack<TimewarpRollback>(bytesOf(rollback)).times == rollback.times);
    CHECK(readBack<Quat>(bytesOf(Quat(0.5, -0.5, 0.5, -0.5))).coeffs() == Quat(0.5, -0.5, 0.5, -0.5).coeffs());
  }
  SECTION("empty things and the edges of sizes") {
    CHECK(readBack<VecX>(bytesOf(VecX())).size() == 0);
    CHECK(readBack<MatX>(bytesOf(MatX(0, 5))).cols() == 5);
    CHECK(readBack<std::vector<double>>(bytesOf(std::vector<double>{})).empty());
    CHECK(readBack<std::string>(bytesOf(std::string("a\0b", 3))) == std::string("a\0b", 3));
    CHECK(readBack<std::optional<Vec3>>(bytesOf(std::optional<Vec3>())) == std::nullopt);
  }
}

TEST_CASE("remote wire: a std::variant crosses as its alternative's index, then the alternative", "[common]") {
  // Lab 4's Shape: every alternative, none of them default constructible
  const std::vector<Shape> shapes{Sphere(0.25),
                                  Box(Vec3(0.5, 1, 2)),
                                  Capsule(0.1, 0.7),
                                  Plane(Vec3(0, 3, 4), 2),
                                  ConvexPolyhedron::tetrahedron(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()),
                                  Triangle(Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 3))};
  for (const Shape& shape : shapes) {
    CAPTURE(shapeName(shape));
    const auto bytes = bytesOf(shape);
    Reader in(bytes.data(), bytes.size());
    Shape back = Sphere(9);
    remote::get(in, back);
    CHECK(in.remaining() == 0);
    CHECK(back.index() == shape.index());
    CHECK(bytesOf(back) == bytes);
  }
  const auto box = bytesOf(shapes[1]);
  Reader box_in(box.data(), box.size());
  Shape box_back = Sphere(9);
  remote::get(box_in, box_back);
  CHECK(std::get<Box>(box_back).half_extents == Vec3(0.5, 1, 2));

  SECTION("an index the variant has no alternative for is refused, and the value kept") {
    for (const std::uint32_t index : {6u, 7u, ~0u}) {
      Writer out;
      remote::put(out, index);
      remote::put(out, 1.0);
      Reader in(out.buffer().data(), out.buffer().size());
      Shape value = Capsule(0.1, 0.7);
      CHECK_THROWS_AS(remote::get(in, value), WireError);
      CHECK(std::get<Capsule>(value).half_height == 0.7);
    }
  }
  SECTION("an alternative cut short is refused") {
    const auto bytes = bytesOf(shapes[4]);
    for (std::size_t size = 0; size < bytes.size(); ++size) {
      Reader in(bytes.data(), size);
      Shape value = Sphere(1);
      CHECK_THROWS_AS(remote::get(in, value), WireError);
    }
  }
}

TEST_CASE("remote wire: a pool crosses as its changes since it last crossed", "[common]") {
  std::vector<Aabb> boxes(100);
  for (auto& box : boxes) box = Aabb{test::randomVec3(1), test::randomVec3(1) + Vec3::Constant(2)};
  const auto crossed = [](std::vector<Aabb>& items) {
    Writer out;
    remote::Changes<Aabb> sent(items);
    remote::put(out, sent);
    return out.buffer();
  };
  const auto received = [](const std::vector<char>& bytes) {
    std::vector<Aabb> items;
    remote::Changes<Aabb> back(items);
    Reader in(bytes.data(), bytes.size());
    remote::get(in, back);
    CHECK(in.remaining() == 0);
    return items;
  };
  const auto whole = crossed(boxes);
  CHECK(bytesOf(received(whole)) == bytesOf(boxes));
  // One box changed, one added: a size, a count, and two (index, box)
  boxes[17].max.x() += 1;
  boxes.push_back(boxes[3]);
  const auto changes = crossed(boxes);
  CHECK(changes.size() == 8 + 8 + 2 * (8 + 2 * (16 + 24)));
  CHECK(bytesOf(received(changes)) == bytesOf(boxes));
  // Unchanged and shrunk: nothing but the size
  boxes.resize(50);
  CHECK(crossed(boxes).size() == 16);
  CHECK(bytesOf(received(crossed(boxes))) == bytesOf(boxes));

  SECTION("a size past the last vector's end and its changes, or a change past the size, is refused") {
    // 50 items known and one change: a size of at most 51, and an index below it
    for (const auto& [size, index] : {std::pair<std::uint64_t, std::uint64_t>{60, 0}, {51, 51}}) {
      Writer out;
      remote::put(out, size);
      remote::put(out, std::uint64_t{1});
      remote::put(out, index);
      remote::put(out, boxes[0]);
      std::vector<Aabb> items;
      remote::Changes<Aabb> back(items);
      Reader in(out.buffer().data(), out.buffer().size());
      CHECK_THROWS_AS(remote::get(in, back), WireError);
    }
  }
}

TEST_CASE("remote wire: a malformed reply is refused, never read past its end", "[common]") {
  std::vector<Contact> contacts{randomContact(), randomContact()};
  const auto bytes = bytesOf(contacts);
  SECTION("every truncation of a valid message") {
    for (std::size_t size = 0; size < bytes.size(); ++size) {
      Reader in(bytes.data(), size);
      std::vector<Contact> back;
      CHECK_THROWS_AS(remote::get(in, back), WireError);
    }
  }
  SECTION("sizes larger than the message, and matrices of the wrong shape") {
    const std::uint64_t huge[] = {~0ull, 2};
    Reader vector_in(reinterpret_cast<const char*>(huge), sizeof huge);
    std::vector<double> v;
    CHECK_THROWS_AS(remote::get(vector_in, v), WireError);
    Reader matrix_in(reinterpret_cast<const char*>(huge), sizeof huge);
    MatX m;
    CHECK_THROWS_AS(remote::get(matrix_in, m), WireError);
    const auto four = bytesOf(VecX(VecX::Zero(4)));
    Reader fixed_in(four.data(), four.size());
    Vec3 x;
    CHECK_THROWS_AS(remote::get(fixed_in, x), WireError);
  }
  SECTION("a bool is one byte, any non-zero byte true") {
    const char byte = 7;
    Reader in(&byte, 1);
    bool value = false;
    remote::get(in, value);
    CHECK(value);
  }
}

TEST_CASE("remote wire: an exception crosses as its family with its message", "[common]") {
  using remote::Family;
  const std::string message = "invalid input: mass m must be positive, got -1";
  CHECK_THROWS_AS(remote::rethrow(Family::InvalidInput, message), InvalidInput);
  CHECK_THROWS_WITH(remote::rethrow(Family::InvalidInput, message), message);
  CHECK_THROWS_AS(remote::rethrow(Family::NotImplemented, "not implemented: f"), NotImplemented);
  CHECK_THROWS_WITH(remote::rethrow(Family::NotImplemented, "not implemented: f"), "not implemented: f");
  CHECK_THROWS_AS(remote::rethrow(Family::LcpFailure, "ray"), LcpFailure);
  CHECK_THROWS_AS(remote::rethrow(Family::NumericalFailure, "x"), NumericalFailure);
  CHECK_THROWS_AS(remote::rethrow(Family::OutOfRange, "x"), std::out_of_range);
  CHECK_THROWS_AS(remote::rethrow(Family::Other, "x"), std::exception);
  CHECK(remote::currentFamily(LcpFailure("x")) == Family::LcpFailure);
  CHECK(remote::currentFamily(NumericalFailure("x")) == Family::NumericalFailure);
  CHECK(remote::currentFamily(InvalidInput("x")) == Family::InvalidInput);
  CHECK(remote::currentFamily(std::invalid_argument("x")) == Family::InvalidArgument);
  CHECK(remote::currentFamily(std::runtime_error("x")) == Family::RuntimeError);

  SECTION("a function that changed an argument and then threw: the change comes back before the exception") {
    Writer out;
    Vec3 v = Vec3::Zero();
    remote::respond(out, [&]() -> double { v = Vec3(1, 2, 3); throw InvalidInput("too late"); },
                    [&] { remote::put(out, v); });
    Reader in(out.buffer().data(), out.buffer().size());
    remote::Ending ending{};
    Vec3 back;
    Family family{};
    std::string what;
    remote::get(in, ending);
    remote::get(in, back);
    remote::get(in, family);
    remote::get(in, what);
    CHECK(ending == remote::Ending::Threw);
    CHECK(back == Vec3(1, 2, 3));
    CHECK(family == Family::InvalidInput);
    CHECK(what == "invalid input: too late");
    CHECK(in.remaining() == 0);
  }
}

TEST_CASE("remote callbacks: a lent system answers through its public, counting methods", "[common]") {
  remote::forgetHandles();
  const Callable system;
  const std::uint32_t handle = handleOf(system);
  const VecX X = (VecX(2) << 3.0, -1.0).finished();
  const auto callback = callbackOf(handle, remote::Method::VelocityRate, X);
  Reader in(callback.data(), callback.size());
  Writer answer;
  remote::answerCallback(in, answer);
  Reader back(answer.buffer().data(), answer.buffer().size());
  remote::Ending ending{};
  VecX rate;
  remote::get(back, ending);
  remote::get(back, rate);
  CHECK(ending == remote::Ending::Returned);
  CHECK(rate == VecX::Constant(1, -3.0));
  CHECK(back.remaining() == 0);
  CHECK(system.forceEvaluations() == 1);

  SECTION("an exception of the system's crosses back as its family, with its message") {
    const auto wrong = callbackOf(handle, remote::Method::VelocityRate, VecX::Zero(3));
    Reader wrong_in(wrong.data(), wrong.size());
    Writer thrown;
    remote::answerCallback(wrong_in, thrown);
    Reader thrown_back(thrown.buffer().data(), thrown.buffer().size());
    remote::get(thrown_back, ending);
    remote::get(thrown_back, rate);
    remote::Family family{};
    remote::get(thrown_back, family);
    CHECK(ending == remote::Ending::Threw);
    CHECK(family == remote::Family::InvalidInput);
  }
  remote::forgetHandles();
}

TEST_CASE("remote callbacks: only what the checker lent during the call is reached", "[common]") {
  remote::forgetHandles();
  const Callable system;
  const std::uint32_t handle = handleOf(system);
  const VecX X = VecX::Zero(2);
  Writer answer;
  SECTION("a handle never lent") {
    const auto callback = callbackOf(handle + 1, remote::Method::VelocityRate, X);
    Reader in(callback.data(), callback.size());
    CHECK_THROWS_AS(remote::answerCallback(in, answer), WireError);
  }
  SECTION("a handle of a call that has ended") {
    remote::forgetHandles();
    const auto callback = callbackOf(handle, remote::Method::VelocityRate, X);
    Reader in(callback.data(), callback.size());
    CHECK_THROWS_AS(remote::answerCallback(in, answer), WireError);
  }
  SECTION("a method no system has") {
    const auto callback = callbackOf(handle, remote::Method::Potential, X);
    Reader in(callback.data(), callback.size());
    CHECK_THROWS_AS(remote::answerCallback(in, answer), WireError);
  }
  SECTION("bytes past the arguments") {
    auto callback = callbackOf(handle, remote::Method::VelocityRate, X);
    callback.push_back(0);
    Reader in(callback.data(), callback.size());
    CHECK_THROWS_AS(remote::answerCallback(in, answer), WireError);
  }
  CHECK(system.forceEvaluations() == 0);
  remote::forgetHandles();
}

TEST_CASE("remote callbacks: across processes, a callback's code may call the worker again", "[common]") {
  ::setenv("PHYSLAB_WORKER", PHYSLAB_TEST_WORKER, 1);
  const auto velocityRate = [](const System& system, const VecX& X) {
    remote::Call call(0, "velocityRate");
    call.in(system);
    call.in(X);
    call.send();
    remote::addEvaluations(call, system);
    return call.result<VecX>();
  };
  const VecX X = (VecX(2) << 3.0, -1.0).finished();
  SECTION("a handle: one callback, counted in the checker") {
    const Callable system;
    CHECK(velocityRate(system, X) == VecX::Constant(1, -3.0));
    CHECK(system.forceEvaluations() == 1);
  }
  SECTION("a nested request while the worker waits for the callback's answer") {
    const Callable system(true);
    CHECK(velocityRate(system, X) == VecX::Constant(1, -6.0));
    CHECK(system.forceEvaluations() == 1);
  }
  SECTION("a framework system crosses as a copy; its evaluations are counted back") {
    const HarmonicOscillator oscillator(2.0);
    CHECK(velocityRate(oscillator, X) == VecX::Constant(1, -12.0));
    CHECK(oscillator.forceEvaluations() == 1);
  }
}

namespace {

// A 3 x 3 cloth with a pinned corner, its workspace's vectors filled with seeded values.
SpringNetwork smallCloth() {
  SpringNetwork net = makeCloth(3, 3, 1.0, 1.0, 0.5, test::uniform(100.0, 1000.0), test::uniform(0.0, 2.0));
  net.masses[0] = std::numeric_limits<double>::infinity();
  return net;
}

void fillVectors(ImplicitWorkspace& ws) {
  for (VecX* v : {&ws.b, &ws.Kv, &ws.dv, &ws.Adv}) *v = VecX::Random(v->size());
}

}  // namespace

TEST_CASE("remote wire: a spring system crosses as its network, a workspace as its pattern and vectors", "[common]") {
  const SpringNetwork net = smallCloth();
  const SpringSystem sys(net);
  SECTION("the system is built anew from its network") {
    const auto bytes = bytesOf(sys);
    CHECK(bytes == bytesOf(net));
    SpringSystem back = remote::blank<SpringSystem>();
    Reader in(bytes.data(), bytes.size());
    remote::get(in, back);
    CHECK(in.remaining() == 0);
    CHECK(bytesOf(back.network()) == bytes);
    CHECK(back.inverseMasses() == sys.inverseMasses());
    CHECK(back.implicitWorkspace().A.count() == sys.count());
  }
  SECTION("a blank workspace (the worker's) is laid out for the pattern that comes, with its vectors") {
    ImplicitWorkspace& ws = sys.implicitWorkspace();
    fillVectors(ws);
    const auto bytes = bytesOf(ws);
    ImplicitWorkspace back = remote::blank<ImplicitWorkspace>();
    Reader in(bytes.data(), bytes.size());
    remote::get(in, back);
    CHECK(in.remaining() == 0);
    CHECK(bytesOf(back) == bytes);
    CHECK(back.dv == ws.dv);
    // The same blocks added spring by spring make the same matrix: the same pairs, transposes and
    // shared blocks.
    for (SpringMatrix* A : {&ws.A, &back.A}) {
      A->setZero();
      for (Index i = 0; i < A->count(); ++i) A->addDiagonal(i, (10.0 + static_cast<double>(i)) * Mat3::Identity());
      for (std::size_t k = 0; k < net.springs.size(); ++k) A->addSpring(k, static_cast<double>(k + 1) * Mat3::Ones());
    }
    CHECK(back.A.toDense() == ws.A.toDense());
    VecX x = VecX::Zero(ws.b.size());
    CHECK(back.A.solveLDLT(ws.b, x));
    // Read again into a workspace of that pattern, it keeps its layout and takes the vectors.
    fillVectors(ws);
    const auto second = bytesOf(ws);
    Reader in_again(second.data(), second.size());
    remote::get(in_again, back);
    CHECK(back.Adv == ws.Adv);
    CHECK(back.A.toDense() == ws.A.toDense());
  }
}

TEST_CASE("remote wire: a malformed workspace is refused", "[common]") {
  const SpringNetwork net = smallCloth();
  const SpringSystem sys(net);
  ImplicitWorkspace& ws = sys.implicitWorkspace();
  fillVectors(ws);
  const Index n = sys.count();
  const auto pairs = remote::Access<0>::springPairs(ws.A);
  auto message = [&](Index particles, const remote::Access<0>::SpringPairs& springs, Index entries) {
    Writer out;
    remote::put(out, particles);
    remote::put(out, springs);
    for (int v = 0; v < 4; ++v) remote::put(out, VecX(VecX::Zero(entries)));
    return out.buffer();
  };
  auto refused = [&](const std::vector<char>& bytes) {
    ImplicitWorkspace into(net);
    Reader in(bytes.data(), bytes.size());
    CHECK_THROWS_AS(remote::get(in, into), WireError);
  };
  SECTION("every truncation of a valid reply") {
    const auto bytes = bytesOf(ws);
    for (std::size_t size = 0; size < bytes.size(); ++size) {
      refused(std::vector<char>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(size)));
    }
  }
  SECTION("vectors of another size, springs outside the particles, and counts the message cannot hold") {
    const auto valid = message(n, pairs, 3 * n);
    ImplicitWorkspace into(net);
    Reader in(valid.data(), valid.size());
    CHECK_NOTHROW(remote::get(in, into));
    refused(message(n, pairs, 3 * n - 3));
    refused(message(n, {{0, n}}, 3 * n));
    refused(message(n, {{2, 2}}, 3 * n));
    refused(message(n, {{-1, 1}}, 3 * n));
    refused(message(0, {}, 0));
    refused(message(Index(1) << 40, pairs, 3 * n));
  }
}
