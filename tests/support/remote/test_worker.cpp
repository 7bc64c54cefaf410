// The worker of test_remote.cpp's calls across processes (tests/common/test_remote.cpp): a table of
// two functions that are no lab's, one that calls back into the checker and one that the
// checker's code calls while it answers that callback (a nested request).
#include "remote/handles.hpp"
#include "remote/remote.hpp"

namespace {

using namespace physlab;
using namespace physlab::remote;

// p-dot of a System at X: one callback for a handle, none for a copy.
void velocityRate(Reader& in, Writer& out) {
  Arg<System> system(in);
  Arg<VecX> X(in);
  respond(
      out,
      [&] {
        VecX rate((*system).velocitySize());
        (*system).velocityRate(*X, rate);
        return rate;
      },
      [&] { system.back(out); });
}

void twice(Reader& in, Writer& out) {
  Arg<double> x(in);
  respond(out, [&] { return 2.0 * *x; }, [] {});
}

}  // namespace

int main() {
  static constexpr Entry kTable[] = {velocityRate, twice};
  return serve(kTable, 2);
}
