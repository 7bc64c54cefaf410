// Linked into every checker (cmake/PhysLab.cmake, physlab_add_remote): each test case gets a
// worker of its own. A checker may run many tests in one process (batch mode, runner.cpp); the
// worker of the test before is ended as the next one starts, so that no test sees what the
// submitted code kept from an earlier one, and a test's result is the same alone or in a batch.
#define CATCH_CONFIG_EXTERNAL_INTERFACES  // the listener's base class
#include <catch2/catch.hpp>

#include "remote.hpp"

namespace {

class WorkerPerTest : public Catch::TestEventListenerBase {
 public:
  using TestEventListenerBase::TestEventListenerBase;
  void testCaseStarting(const Catch::TestCaseInfo&) override { physlab::remote::endWorker(); }
};

}  // namespace

CATCH_REGISTER_LISTENER(WorkerPerTest)
