// adversarial: a compile-time computation that takes minutes
// mode: append
// grade: --compile-timeout 15
namespace {
constexpr unsigned long long spin(unsigned long long n) {
  unsigned long long s = 0;
  for (unsigned long long i = 0; i < n; ++i) s += i % 7;
  return s;
}
constexpr unsigned long long stalled = spin(33000000ULL);
}  // namespace
unsigned long long physlabStall() { return stalled; }
