// adversarial: a compile-time computation that takes minutes
// mode: append
// grade: --compile-timeout 15
// quick
namespace {
// 8 x 440 x 440 distinct class instantiations (under GCC's depth limit of 900): over a minute.
template <int T, int A, int B>
struct Grid {
  static constexpr unsigned long value = Grid<T, A - 1, B>::value + Grid<T, A, B - 1>::value;
};
template <int T, int B>
struct Grid<T, 0, B> {
  static constexpr unsigned long value = 1;
};
template <int T, int A>
struct Grid<T, A, 0> {
  static constexpr unsigned long value = 1;
};
}  // namespace
unsigned long physlabStall() {
  return Grid<0, 440, 440>::value + Grid<1, 440, 440>::value + Grid<2, 440, 440>::value +
         Grid<3, 440, 440>::value + Grid<4, 440, 440>::value + Grid<5, 440, 440>::value +
         Grid<6, 440, 440>::value + Grid<7, 440, 440>::value;
}
