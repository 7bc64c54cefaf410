// The main() of every test executable: Catch2's session, plus a verdict the grader can trust.
//
// A test's output and exit code come from a process that also runs student code, which can print
// anything and exit with any code, so the grader counts neither as a pass. Instead, when the
// grader sets PHYSLAB_VERDICT=<key fd>:<verdict fd>, this file
//  1. reads a fresh secret key from <key fd> in .preinit_array, which runs before every
//     constructor of the executable and so before any student code, and closes that descriptor;
//  2. counts the test cases and assertions Catch2 ran, with a listener;
//  3. writes one line "physlab-verdict <key> <cases> <passed> <failed> <name in hex>" to
//     <verdict fd> when the session ends, then leaves with _exit() so that no student code
//     (static destructors, atexit handlers) runs after the verdict.
// Student code never learns the key by reading the channel; what remains possible for code that
// searches its own process's memory is written on the Grading page.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

namespace {

struct Channel {
  char key[64] = {};
  int key_size = 0;
  int fd = -1;  // where the verdict goes; -1 outside the grader
};
Channel channel;

struct Tally {
  int cases = 0;
  std::string name;
  std::uint64_t passed = 0;
  std::uint64_t failed = 0;
};
Tally tally;

// Parses a non-negative decimal number from s up to `stop`; -1 if there is none.
int parseFd(const char*& s, char stop) {
  int value = 0;
  bool any = false;
  for (; *s >= '0' && *s <= '9' && value < 100000; ++s, any = true) value = 10 * value + (*s - '0');
  if (!any || *s != stop) return -1;
  if (stop != '\0') ++s;
  return value;
}

// Runs from .preinit_array, before the C++ runtime and the executable's constructors: it uses the
// environment it is handed and plain system calls only.
void takeKey(int, char**, char** envp) {
  static const char kVariable[] = "PHYSLAB_VERDICT=";
  for (char** e = envp; e && *e; ++e) {
    if (std::strncmp(*e, kVariable, sizeof kVariable - 1) != 0) continue;
    const char* spec = *e + sizeof kVariable - 1;
    const int key_fd = parseFd(spec, ':');
    const int verdict_fd = parseFd(spec, '\0');
    if (key_fd < 0 || verdict_fd < 0) return;
    ssize_t got = 0;
    while (channel.key_size < static_cast<int>(sizeof channel.key) &&
           (got = read(key_fd, channel.key + channel.key_size, sizeof channel.key - channel.key_size)) > 0) {
      channel.key_size += static_cast<int>(got);
    }
    close(key_fd);
    if (channel.key_size > 0) channel.fd = verdict_fd;
    return;
  }
}

__attribute__((section(".preinit_array"), used)) void (*preinit_take_key)(int, char**, char**) = takeKey;

std::string hex(const std::string& text) {
  static const char digits[] = "0123456789abcdef";
  std::string out;
  for (unsigned char c : text) {
    out += digits[c >> 4];
    out += digits[c & 15];
  }
  return out;
}

class VerdictListener : public Catch::TestEventListenerBase {
 public:
  using TestEventListenerBase::TestEventListenerBase;
  void testCaseEnded(const Catch::TestCaseStats& stats) override {
    ++tally.cases;
    tally.name = stats.testInfo.name;
    tally.passed += stats.totals.assertions.passed;
    tally.failed += stats.totals.assertions.failed;
  }
};

void writeVerdict() {
  const std::string line = "physlab-verdict " + std::string(channel.key, channel.key_size) + " " +
                           std::to_string(tally.cases) + " " + std::to_string(tally.passed) + " " +
                           std::to_string(tally.failed) + " " + hex(tally.name) + "\n";
  const char* data = line.data();
  std::size_t left = line.size();
  while (left > 0) {
    const ssize_t wrote = write(channel.fd, data, left);
    if (wrote <= 0) return;
    data += wrote;
    left -= static_cast<std::size_t>(wrote);
  }
}

// One line per test case: its name in hex, a tab, its tags joined by commas. The grader reads the
// test list and points from the instructor's executables this way, never from student output.
int listTests() {
  for (const Catch::TestCase& test : Catch::getRegistryHub().getTestCaseRegistry().getAllTests()) {
    std::string tags;
    for (const std::string& tag : test.tags) tags += (tags.empty() ? "" : ",") + tag;
    std::cout << hex(test.name) << '\t' << tags << '\n';
  }
  return 0;
}

}  // namespace

CATCH_REGISTER_LISTENER(VerdictListener)

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--physlab-list") == 0) return listTests();
  Catch::Session session;
  const int status = session.applyCommandLine(argc, argv);
  if (status != 0) return status;
  const int failures = session.run();
  if (channel.fd < 0) return failures;
  std::cout.flush();
  std::fflush(nullptr);
  writeVerdict();
  _exit(failures == 0 ? 0 : 1);
}
