// The wire between a checker and its worker (tests/support/remote): what crosses comes back as it
// was, and what a hostile worker sends is refused with an error, never read past its end.
#include <catch2/catch.hpp>

#include "physlab/collision.hpp"
#include "physlab/lcp.hpp"
#include "physlab/resting.hpp"
#include "physlab/soft_step.hpp"
#include "physlab/timewarp.hpp"
#include "physlab/world.hpp"
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
