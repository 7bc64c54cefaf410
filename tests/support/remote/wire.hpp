// The wire between a checker and the worker that runs submitted code: how values are written to
// and read from a byte buffer (see docs/grading.md, "Where submitted code runs").
//
// The checker runs the tests and decides every verdict; the worker runs the student's functions
// and only hands back data. So everything read here may come from hostile code: every read is
// bounds-checked, every size is checked against the bytes that remain, and a malformed message
// ends the call with WireError, never with memory the checker did not allocate.
//
// What crosses: arithmetic values and enums (their bytes), bool (one byte, any non-zero is true),
// std::string, Eigen's dense matrices (fixed or dynamic: sizes, then entries column by column)
// and quaternions, std::vector, std::optional, std::pair, std::array, std::variant (the index of
// its alternative, then the alternative: Lab 4's Shape), and aggregates (structs
// with public members and no constructors: ContactBody, LcpSolution, ...), whose members are
// found by the compiler (AggregateFields below), so a member added to a header crosses without
// a line written here.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace physlab::remote {

/// Access<0> lists the members of classes that are not aggregates (state.hpp); Access<1> is a
/// worker's table, which calls their student member functions. A framework class befriends both.
template <int>
struct Access;

/// The most members an aggregate that crosses may have (visitFields() spells out each count).
inline constexpr std::size_t kMaxFields = 24;

/// A message that does not read back as what the checker asked for.
class WireError : public std::runtime_error {
 public:
  explicit WireError(const std::string& what) : std::runtime_error("malformed reply from the worker: " + what) {}
};

/// Bytes being written.
class Writer {
 public:
  void bytes(const void* data, std::size_t size) {
    if (size == 0) return;
    const std::size_t at = buffer_.size();
    buffer_.resize(at + size);
    std::memcpy(buffer_.data() + at, data, size);
  }
  std::vector<char>& buffer() { return buffer_; }

 private:
  std::vector<char> buffer_;
};

/// Bytes being read; every read checks that they are there.
class Reader {
 public:
  Reader(const char* data, std::size_t size) : at_(data), end_(data + size) {}
  void bytes(void* data, std::size_t size) {
    if (size > remaining()) throw WireError("it ends early");
    std::memcpy(data, at_, size);
    at_ += size;
  }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - at_); }
  /// A count of things that take at least `each` bytes apiece: refused when the rest of the
  /// message could not hold them (no allocation is ever sized by an unchecked number).
  std::size_t count(std::size_t each) {
    std::uint64_t n = 0;
    bytes(&n, sizeof n);
    if (each > 0 && n > remaining() / each) throw WireError("a size of " + std::to_string(n) + " exceeds the message");
    if (each == 0 && n > (1u << 20)) throw WireError("a size of " + std::to_string(n) + " of empty things");
    return static_cast<std::size_t>(n);
  }

 private:
  const char* at_;
  const char* end_;
};

// ---- aggregates: their members, found by the compiler ------------------------------------------

namespace detail {
// Converts to a reference of any type: T{AnyField{}...} compiles for as many initialisers as T
// has members, or fewer (a reference conversion leaves no copy/move ambiguity and no brace
// elision), so the largest count that compiles is the number of members.
struct AnyField {
  template <class T>
  operator T&() const;
};

// Counting initialises with too few initialisers on purpose: clang's -Wmissing-field-initializers
// would say so for every count below the number of members.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
template <class T, std::size_t... I>
constexpr auto initializable(int, std::index_sequence<I...>) -> decltype(T{(void(I), AnyField{})...}, true) {
  return true;
}
template <class T, std::size_t... I>
constexpr bool initializable(long, std::index_sequence<I...>) {
  return false;
}
#pragma GCC diagnostic pop

template <class T, std::size_t N = 0>
constexpr std::size_t fieldCount() {
  if constexpr (N > kMaxFields) {
    return N;
  } else if constexpr (initializable<T>(0, std::make_index_sequence<N + 1>{})) {
    return fieldCount<T, N + 1>();
  } else {
    return N;
  }
}
}  // namespace detail

/// Calls f(member) for each member of the aggregate `value`, in declaration order.
template <class T, class F>
void visitFields(T& value, F&& f) {
  using Plain = std::remove_const_t<T>;
  static_assert(std::is_aggregate_v<Plain>, "only aggregates cross the wire member by member");
  constexpr std::size_t n = detail::fieldCount<Plain>();
  static_assert(n <= kMaxFields, "an aggregate of more members than visitFields() spells out");
  if constexpr (n == 0) {
  } else if constexpr (n == 1) {
    auto& [m0] = value;
    f(m0);
  } else if constexpr (n == 2) {
    auto& [m0, m1] = value;
    f(m0); f(m1);
  } else if constexpr (n == 3) {
    auto& [m0, m1, m2] = value;
    f(m0); f(m1); f(m2);
  } else if constexpr (n == 4) {
    auto& [m0, m1, m2, m3] = value;
    f(m0); f(m1); f(m2); f(m3);
  } else if constexpr (n == 5) {
    auto& [m0, m1, m2, m3, m4] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4);
  } else if constexpr (n == 6) {
    auto& [m0, m1, m2, m3, m4, m5] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5);
  } else if constexpr (n == 7) {
    auto& [m0, m1, m2, m3, m4, m5, m6] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6);
  } else if constexpr (n == 8) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7);
  } else if constexpr (n == 9) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8);
  } else if constexpr (n == 10) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9);
  } else if constexpr (n == 11) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10);
  } else if constexpr (n == 12) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11);
  } else if constexpr (n == 13) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12);
  } else if constexpr (n == 14) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13);
  } else if constexpr (n == 15) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14);
  } else if constexpr (n == 16) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14); f(m15);
  } else if constexpr (n == 17) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15, m16] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14); f(m15); f(m16);
  } else if constexpr (n == 18) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15, m16, m17] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14); f(m15); f(m16); f(m17);
  } else if constexpr (n == 19) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15, m16, m17, m18] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14); f(m15); f(m16); f(m17); f(m18);
  } else if constexpr (n == 20) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15, m16, m17, m18, m19] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14); f(m15); f(m16); f(m17); f(m18); f(m19);
  } else if constexpr (n == 21) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15, m16, m17, m18, m19, m20] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14); f(m15); f(m16); f(m17); f(m18); f(m19); f(m20);
  } else if constexpr (n == 22) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15, m16, m17, m18, m19, m20, m21] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14); f(m15); f(m16); f(m17); f(m18); f(m19); f(m20); f(m21);
  } else if constexpr (n == 23) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15, m16, m17, m18, m19, m20, m21, m22] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14); f(m15); f(m16); f(m17); f(m18); f(m19); f(m20); f(m21); f(m22);
  } else if constexpr (n == 24) {
    auto& [m0, m1, m2, m3, m4, m5, m6, m7, m8, m9, m10, m11, m12, m13, m14, m15, m16, m17, m18, m19, m20, m21, m22, m23] = value;
    f(m0); f(m1); f(m2); f(m3); f(m4); f(m5); f(m6); f(m7); f(m8); f(m9); f(m10); f(m11); f(m12); f(m13); f(m14); f(m15); f(m16); f(m17); f(m18); f(m19); f(m20); f(m21); f(m22); f(m23);
  }
}

// ---- values --------------------------------------------------------------------------------------

template <class T, class Enable = void>
struct Codec;

/// A blank T to read into (state.hpp: the classes without a default constructor have one there).
template <class T>
T blank();

/// Writes `value`.
template <class T>
void put(Writer& out, const T& value) {
  Codec<T>::put(out, value);
}

/// Reads into `value` (which keeps nothing of what it held).
template <class T>
void get(Reader& in, T& value) {
  Codec<T>::get(in, value);
}

template <class T>
struct Codec<T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>>> {
  static void put(Writer& out, T value) { out.bytes(&value, sizeof value); }
  static void get(Reader& in, T& value) { in.bytes(&value, sizeof value); }
};

template <>
struct Codec<bool> {
  static void put(Writer& out, bool value) {
    const unsigned char byte = value ? 1 : 0;
    out.bytes(&byte, 1);
  }
  static void get(Reader& in, bool& value) {
    unsigned char byte = 0;
    in.bytes(&byte, 1);
    value = byte != 0;
  }
};

template <class T>
struct Codec<T, std::enable_if_t<std::is_enum_v<T>>> {
  using Raw = std::underlying_type_t<T>;
  static void put(Writer& out, T value) { remote::put(out, static_cast<Raw>(value)); }
  static void get(Reader& in, T& value) {
    Raw raw{};
    remote::get(in, raw);
    value = static_cast<T>(raw);
  }
};

template <>
struct Codec<std::string> {
  static void put(Writer& out, const std::string& value) {
    const std::uint64_t n = value.size();
    out.bytes(&n, sizeof n);
    out.bytes(value.data(), value.size());
  }
  static void get(Reader& in, std::string& value) {
    value.resize(in.count(1));
    in.bytes(value.data(), value.size());
  }
};

template <class S, int R, int C, int O, int MR, int MC>
struct Codec<Eigen::Matrix<S, R, C, O, MR, MC>> {
  using M = Eigen::Matrix<S, R, C, O, MR, MC>;
  static void put(Writer& out, const M& value) {
    const std::uint64_t rows = static_cast<std::uint64_t>(value.rows());
    const std::uint64_t cols = static_cast<std::uint64_t>(value.cols());
    out.bytes(&rows, sizeof rows);
    out.bytes(&cols, sizeof cols);
    out.bytes(value.data(), sizeof(S) * static_cast<std::size_t>(value.size()));
  }
  static void get(Reader& in, M& value) {
    const std::size_t rows = in.count(0);
    const std::size_t cols = in.count(0);
    const bool fits = (R == Eigen::Dynamic ? (MR == Eigen::Dynamic || rows <= std::size_t(MR)) : rows == std::size_t(R)) &&
                      (C == Eigen::Dynamic ? (MC == Eigen::Dynamic || cols <= std::size_t(MC)) : cols == std::size_t(C));
    if (!fits) throw WireError("a matrix of " + std::to_string(rows) + " x " + std::to_string(cols) + " where its type allows none");
    if (cols != 0 && rows > in.remaining() / sizeof(S) / cols) throw WireError("a matrix larger than the message");
    value.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
    in.bytes(value.data(), sizeof(S) * rows * cols);
  }
};

/// A map of a matrix (Points, ConstPoints) goes as the matrix it shows; it is read back into one.
template <class M>
struct Codec<Eigen::Map<M>> {
  static void put(Writer& out, const Eigen::Map<M>& value) {
    remote::put(out, typename Eigen::Map<M>::PlainObject(value));
  }
};

template <class S, int O>
struct Codec<Eigen::Quaternion<S, O>> {
  static void put(Writer& out, const Eigen::Quaternion<S, O>& value) { out.bytes(value.coeffs().data(), 4 * sizeof(S)); }
  static void get(Reader& in, Eigen::Quaternion<S, O>& value) { in.bytes(value.coeffs().data(), 4 * sizeof(S)); }
};

template <class T, class A>
struct Codec<std::vector<T, A>> {
  static void put(Writer& out, const std::vector<T, A>& value) {
    const std::uint64_t n = value.size();
    out.bytes(&n, sizeof n);
    for (const auto& item : value) remote::put(out, static_cast<const T&>(item));
  }
  static void get(Reader& in, std::vector<T, A>& value) {
    value.clear();
    value.resize(in.count(1));
    for (auto& item : value) {
      T read{};
      remote::get(in, read);
      item = std::move(read);
    }
  }
};

template <class T, std::size_t N>
struct Codec<std::array<T, N>> {
  static void put(Writer& out, const std::array<T, N>& value) {
    for (const auto& item : value) remote::put(out, item);
  }
  static void get(Reader& in, std::array<T, N>& value) {
    for (auto& item : value) remote::get(in, item);
  }
};

template <class T>
struct Codec<std::optional<T>> {
  static void put(Writer& out, const std::optional<T>& value) {
    remote::put(out, value.has_value());
    if (value) remote::put(out, *value);
  }
  static void get(Reader& in, std::optional<T>& value) {
    bool present = false;
    remote::get(in, present);
    value.reset();
    if (present) remote::get(in, value.emplace());
  }
};

template <class A, class B>
struct Codec<std::pair<A, B>> {
  static void put(Writer& out, const std::pair<A, B>& value) {
    remote::put(out, value.first);
    remote::put(out, value.second);
  }
  static void get(Reader& in, std::pair<A, B>& value) {
    remote::get(in, value.first);
    remote::get(in, value.second);
  }
};

/// The index of the alternative held, then the alternative. An index the variant has no
/// alternative for is refused; the alternative is read into a blank one (its type may have no
/// default constructor: Sphere, Box, ...), so a failed read leaves `value` as it was.
template <class... T>
struct Codec<std::variant<T...>> {
  using V = std::variant<T...>;
  static void put(Writer& out, const V& value) {
    remote::put(out, static_cast<std::uint32_t>(value.index()));
    std::visit([&](const auto& alternative) { remote::put(out, alternative); }, value);
  }
  static void get(Reader& in, V& value) {
    std::uint32_t index = 0;
    remote::get(in, index);
    if (index >= sizeof...(T)) {
      throw WireError("a variant's alternative " + std::to_string(index) + " where it has " + std::to_string(sizeof...(T)));
    }
    readers(std::index_sequence_for<T...>{})[index](in, value);
  }

 private:
  template <std::size_t I>
  static void read(Reader& in, V& value) {
    using Alternative = std::variant_alternative_t<I, V>;
    Alternative alternative = blank<Alternative>();
    remote::get(in, alternative);
    value.template emplace<I>(std::move(alternative));
  }
  // The reader of each alternative, by index.
  template <std::size_t... I>
  static constexpr std::array<void (*)(Reader&, V&), sizeof...(T)> readers(std::index_sequence<I...>) {
    return {&read<I>...};
  }
};

/// Which worker the checker talks to: a number that changes whenever one starts (remote.cpp).
/// What is kept of the last crossing (Changes) belongs to one worker; a worker keeps 0 for life.
inline std::uint64_t& workerEpoch() {
  static std::uint64_t epoch = 0;
  return epoch;
}

/// A vector that crosses as its changes: its size, then the items that differ from the vector
/// that last crossed this way, in either direction (each with its index). For a large pool of
/// which a call changes a few items, such as Lab 4's dynamic tree, whose framework calls the
/// student's functions at every insertion and removal: whole, its nodes made such a test cross
/// hundreds of megabytes, and take minutes. Both processes keep the last vector, and the pipe
/// carries one message at a time, each read as it was written, so they keep the same one; a
/// checker forgets its last vector when it starts a new worker (each test has its own).
///
/// An item is unchanged when its bytes are those it had in memory right after the last crossing
/// (a snapshot, padding included: a copy would not copy the padding, so every item would differ
/// from it). A byte that differs only sends an item more; an item sent is its value, member by
/// member, as always.
template <class T>
class Changes {
 public:
  explicit Changes(std::vector<T>& items) : items_(items) {}

  void put(Writer& out) const {
    Crossed& last = crossed();
    last.changed.clear();
    for (std::size_t i = 0; i < items_.size(); ++i) {
      if (i >= last.items.size() || std::memcmp(&items_[i], &last.bytes[i * sizeof(T)], sizeof(T)) != 0) {
        last.changed.push_back(i);
      }
    }
    remote::put(out, static_cast<std::uint64_t>(items_.size()));
    remote::put(out, static_cast<std::uint64_t>(last.changed.size()));
    for (const std::uint64_t i : last.changed) {
      remote::put(out, i);
      remote::put(out, items_[i]);
    }
    last.items = items_;
    snapshot(last);
  }
  void get(Reader& in) {
    Crossed& last = crossed();
    std::uint64_t size = 0;
    remote::get(in, size);
    const std::size_t count = in.count(sizeof(std::uint64_t));
    // Every item past the last vector's end comes as a change: no allocation past the message
    if (size > last.items.size() + count) {
      throw WireError("a vector of " + std::to_string(size) + " with " + std::to_string(count) + " changes");
    }
    last.items.resize(static_cast<std::size_t>(size));
    for (std::size_t k = 0; k < count; ++k) {
      std::uint64_t i = 0;
      remote::get(in, i);
      if (i >= size) throw WireError("a change at " + std::to_string(i) + " of a vector of " + std::to_string(size));
      remote::get(in, last.items[static_cast<std::size_t>(i)]);
    }
    items_ = last.items;
    snapshot(last);
  }

 private:
  struct Crossed {
    std::vector<T> items;               // the vector that crossed last
    std::vector<unsigned char> bytes;   // the crossing side's items right after it crossed
    std::vector<std::uint64_t> changed;  // scratch: the indices to send
    std::uint64_t epoch = 0;             // the worker it crossed to or from (workerEpoch())
  };
  static Crossed& crossed() {
    static Crossed last;
    if (last.epoch != workerEpoch()) last = Crossed{{}, {}, {}, workerEpoch()};
    return last;
  }
  void snapshot(Crossed& last) const {
    last.bytes.resize(items_.size() * sizeof(T));
    if (!items_.empty()) std::memcpy(last.bytes.data(), static_cast<const void*>(items_.data()), last.bytes.size());
  }

  std::vector<T>& items_;
};

template <class T>
struct Codec<Changes<T>> {
  static void put(Writer& out, const Changes<T>& value) { value.put(out); }
  static void get(Reader& in, Changes<T>& value) { value.get(in); }
};

/// Aggregates: member by member.
template <class T>
struct IsStdArray : std::false_type {};
template <class T, std::size_t N>
struct IsStdArray<std::array<T, N>> : std::true_type {};

template <class T>
struct Codec<T, std::enable_if_t<std::is_class_v<T> && std::is_aggregate_v<T> && !IsStdArray<T>::value>> {
  static void put(Writer& out, const T& value) {
    visitFields(value, [&](const auto& member) { remote::put(out, member); });
  }
  static void get(Reader& in, T& value) {
    visitFields(value, [&](auto& member) { remote::get(in, member); });
  }
};

}  // namespace physlab::remote
