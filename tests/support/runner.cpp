// The main() of every test executable: Catch2's session, plus a verdict the grader can trust.
//
// A test's output and exit code come from a process that also runs student code, which can print
// anything and read or write any of its own memory, so the grader counts neither its output nor a
// secret it holds as a pass. Instead, when the grader sets
// PHYSLAB_VERDICT=<key fd>:<verdict fd>:<test name in hex>, this file
//  1. forks in .preinit_array, which runs before every constructor of the executable and so before
//     any student code. The parent becomes the notary: it reads a fresh secret key from <key fd>,
//     waits for the child and writes one line "physlab-verdict <key> exit <code>" (or
//     "signal <number>") to <verdict fd>, then leaves with _exit(). It never returns from
//     .preinit_array, so no constructor and no line of student code ever runs in it;
//  2. the child closes both descriptors before anything else runs, so student code never holds the
//     key nor the verdict channel; it runs the one test with a listener that counts the test cases
//     and assertions Catch2 ran;
//  3. when the session ends, the child leaves with _exit(): 0 only if exactly the named test ran,
//     asserted something and failed nothing (see Outcome). No student code (static destructors,
//     atexit handlers) runs after that.
// Student code cannot end a process with a status of its choosing: the grader refuses objects that
// import exit(), _exit(), system calls or anything else of the kind. What remains possible is on
// the Grading page.
//
// The notary needs an ELF executable (.preinit_array) and POSIX (fork, waitpid): Linux and the BSDs.
// Elsewhere (macOS, Windows), or when CMake defines PHYSLAB_PORTABLE_RUNNER (-DPHYSLAB_PORTABLE_RUNNER=ON,
// which CI uses to check this path on Linux), this file is the portable runner: a plain Catch2 main
// that ends a named test with the same outcome codes (see Outcome) and, on POSIX under
// PHYSLAB_VERDICT, writes the verdict line itself from the process that ran the test. That
// verdict is only as trustworthy as the student's own code, which is enough for a student's own
// `./physlab test`; the grader refuses to grade with a build whose runner has no notary
// (toolchain.json "notary": false).
#include <string>

// How every double and float in a report reads (expansions, Approx, CAPTURE): the shortest form
// that reads back as the same value, e.g. 1e-12, 2.5, 0.1, 2.0. Catch2 2.13 prints them fixed-point
// with StringMaker<double>::precision digits, so a tolerance of 1e-12 read "0.0" and two different
// values could read the same. Its StringMaker<double>::convert and <float>::convert call the
// function template Catch::fpToString(value, precision); these exact overloads, declared before the
// implementation below is compiled, are chosen over it (precision is not used: every value shows
// as many digits as it needs). test_common checks that they are the ones called.
namespace Catch {
std::string fpToString(double value, int precision);
std::string fpToString(float value, int precision);
}  // namespace Catch

#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#if !defined(PHYSLAB_PORTABLE_RUNNER) && !(defined(__ELF__) && defined(__unix__))
#define PHYSLAB_PORTABLE_RUNNER 1
#endif
#if !defined(PHYSLAB_PORTABLE_RUNNER) || defined(__unix__) || defined(__APPLE__)
#define PHYSLAB_POSIX 1
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>
#endif

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <type_traits>

namespace {

// The shortest of printf's %.Ng forms (N from the type's digits10 up) that reads back as `value`;
// ".0" is added to whole numbers so that they read as floating point.
template <typename T>
std::string shortestText(T value) {
  char text[48];
  int digits = std::numeric_limits<T>::digits10;
  const auto readsBack = [&] {
    if (std::isnan(value)) return true;
    if constexpr (std::is_same_v<T, float>) {
      return std::strtof(text, nullptr) == value;
    } else {
      return std::strtod(text, nullptr) == value;
    }
  };
  do {
    std::snprintf(text, sizeof text, "%.*g", digits, static_cast<double>(value));
  } while (!readsBack() && ++digits <= std::numeric_limits<T>::max_digits10);
  std::string out = text;
  if (out.find_first_not_of("-0123456789") == std::string::npos) out += ".0";
  return out;
}

// The child's side of the channel: whether it runs under the grader, and the test it must run.
struct Channel {
  bool graded = false;
  char expected[4096] = {};  // the test's name in hex
};
Channel channel;

struct Tally {
  int cases = 0;
  std::string name;
  std::uint64_t passed = 0;
  std::uint64_t failed = 0;
};
Tally tally;

#if defined(PHYSLAB_POSIX)
// Parses a non-negative decimal number from s up to `stop`; -1 if there is none.
int parseFd(const char*& s, char stop) {
  int value = 0;
  bool any = false;
  for (; *s >= '0' && *s <= '9' && value < 100000; ++s, any = true) value = 10 * value + (*s - '0');
  if (!any || *s != stop) return -1;
  if (stop != '\0') ++s;
  return value;
}

// Writes all of `data` to fd; false if the descriptor refuses.
bool writeAll(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t wrote = write(fd, data, size);
    if (wrote <= 0) return false;
    data += wrote;
    size -= static_cast<std::size_t>(wrote);
  }
  return true;
}

// Appends the decimal digits of value to out at *at.
void appendNumber(char* out, std::size_t& at, unsigned value) {
  char digits[16];
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  while (n > 0) out[at++] = digits[--n];
}

#endif  // PHYSLAB_POSIX

#if !defined(PHYSLAB_PORTABLE_RUNNER)
// The notary: the parent after the fork. Reads the key, waits for the child that runs the test and
// writes how it ended, then leaves without returning (no constructor of the executable runs here).
[[noreturn]] void notarise(pid_t child, int key_fd, int verdict_fd) {
  char line[160] = "physlab-verdict ";
  std::size_t at = std::strlen(line);
  const std::size_t key_end = at + 64;
  ssize_t got = 0;
  while (at < key_end && (got = read(key_fd, line + at, key_end - at)) > 0) at += static_cast<std::size_t>(got);
  close(key_fd);
  int status = 0;
  pid_t waited = -1;
  while ((waited = waitpid(child, &status, 0)) < 0 && errno == EINTR) {
  }
  if (at == key_end && waited == child) {
    const bool exited = WIFEXITED(status);
    const char* how = exited ? " exit " : " signal ";
    std::memcpy(line + at, how, std::strlen(how));
    at += std::strlen(how);
    appendNumber(line, at, static_cast<unsigned>(exited ? WEXITSTATUS(status) : WTERMSIG(status)));
    line[at++] = '\n';
    writeAll(verdict_fd, line, at);
  }
  _exit(0);
}

// Runs from .preinit_array, before the C++ runtime and the executable's constructors: it uses the
// environment it is handed and plain system calls only.
void startNotary(int, char**, char** envp) {
  static const char kVariable[] = "PHYSLAB_VERDICT=";
  for (char** e = envp; e && *e; ++e) {
    if (std::strncmp(*e, kVariable, sizeof kVariable - 1) != 0) continue;
    const char* spec = *e + sizeof kVariable - 1;
    const int key_fd = parseFd(spec, ':');
    const int verdict_fd = parseFd(spec, ':');
    if (key_fd < 0 || verdict_fd < 0) return;
    if (std::strlen(spec) >= sizeof channel.expected) {  // no verdict: the test scores nothing
      close(key_fd);
      close(verdict_fd);
      return;
    }
    const pid_t child = fork();
    if (child > 0) notarise(child, key_fd, verdict_fd);
    close(key_fd);
    close(verdict_fd);
    if (child < 0) _exit(125);  // no notary: the grader sees no verdict and scores nothing
    std::strcpy(channel.expected, spec);
    channel.graded = true;
    return;
  }
}

__attribute__((section(".preinit_array"), used)) void (*preinit_start_notary)(int, char**, char**) = startNotary;

#elif defined(PHYSLAB_POSIX)
// The portable runner's side of the channel, set up in main(): the verdict descriptor and key.
int portable_verdict_fd = -1;
char portable_key[64] = {};

// Reads PHYSLAB_VERDICT as the notary would, but in main(): reads the key, closes the key pipe and
// keeps the verdict descriptor for portableVerdict().
void startPortableChannel() {
  const char* spec = std::getenv("PHYSLAB_VERDICT");
  if (spec == nullptr) return;
  const int key_fd = parseFd(spec, ':');
  const int verdict_fd = parseFd(spec, ':');
  if (key_fd < 0 || verdict_fd < 0) return;
  std::size_t at = 0;
  ssize_t got = 0;
  while (at < sizeof portable_key && (got = read(key_fd, portable_key + at, sizeof portable_key - at)) > 0) {
    at += static_cast<std::size_t>(got);
  }
  close(key_fd);
  if (at != sizeof portable_key || std::strlen(spec) >= sizeof channel.expected) {
    close(verdict_fd);  // no verdict: the test scores nothing
    return;
  }
  std::strcpy(channel.expected, spec);
  portable_verdict_fd = verdict_fd;
  channel.graded = true;
}

// Writes the line the notary would write for a child that exited with `code`.
void portableVerdict(int code) {
  char line[160] = "physlab-verdict ";
  std::size_t at = std::strlen(line);
  std::memcpy(line + at, portable_key, sizeof portable_key);
  at += sizeof portable_key;
  static const char kExit[] = " exit ";
  std::memcpy(line + at, kExit, sizeof kExit - 1);
  at += sizeof kExit - 1;
  appendNumber(line, at, static_cast<unsigned>(code));
  line[at++] = '\n';
  writeAll(portable_verdict_fd, line, at);
  close(portable_verdict_fd);
}
#endif

std::string hex(const std::string& text) {
  static const char digits[] = "0123456789abcdef";
  std::string out;
  for (unsigned char c : text) {
    out += digits[c >> 4];
    out += digits[c & 15];
  }
  return out;
}

#if defined(PHYSLAB_POSIX)
// Batch mode (PHYSLAB_RECORDS=<fd>): many tests in one process, for code the grader trusts — a
// checker, which never loads submitted code, or the tree's own tests in `./physlab test`. One
// line per event on <fd>, written before anything else can happen:
//   start <name in hex>                  a test begins
//   end <name in hex> <passed> <failed>  it ended, with its counts of assertions
// A test that starts and never ends took the process with it (a crash, a worker that failed it,
// a time-out); the grader decides it from how the process ended and runs the rest again.
int records_fd = -1;

void startRecords() {
  const char* spec = std::getenv("PHYSLAB_RECORDS");
  if (spec == nullptr) return;
  const int fd = parseFd(spec, '\0');
  // Not inherited by anything this process starts (a checker's worker): records come from here only
  if (fd < 0 || fcntl(fd, F_SETFD, FD_CLOEXEC) != 0) return;
  records_fd = fd;
}

void record(const char* event, const std::string& name, const Catch::Counts* counts = nullptr) {
  std::string line = std::string(event) + ' ' + hex(name);
  if (counts) line += ' ' + std::to_string(counts->passed) + ' ' + std::to_string(counts->failed);
  line += '\n';
  writeAll(records_fd, line.data(), line.size());
}
#endif

class VerdictListener : public Catch::TestEventListenerBase {
 public:
  using TestEventListenerBase::TestEventListenerBase;
  void testCaseStarting(const Catch::TestCaseInfo& info) override {
#if defined(PHYSLAB_POSIX)
    if (records_fd < 0) return;
    // The reports of the tests before this one are whole on disk, whatever ends this process
    stream.flush();
    record("start", info.name);
#else
    static_cast<void>(info);
#endif
  }
  void testCaseEnded(const Catch::TestCaseStats& stats) override {
    ++tally.cases;
    tally.name = stats.testInfo.name;
    tally.passed += stats.totals.assertions.passed;
    tally.failed += stats.totals.assertions.failed;
#if defined(PHYSLAB_POSIX)
    if (records_fd >= 0) record("end", stats.testInfo.name, &stats.totals.assertions);
#endif
  }
};

// How the graded child ends; the grader passes a test only on exit status 0.
// kNotGraded: a remote test whose worker could not be started (tests/support/remote/remote.cpp).
enum Outcome : int { kPassed = 0, kFailed = 1, kNothingAsserted = 3, kOtherTests = 4, kNotGraded = 5 };

Outcome outcome() {
  if (tally.cases != 1 || hex(tally.name) != channel.expected) return kOtherTests;
  if (tally.failed != 0) return kFailed;
  if (tally.passed == 0) return kNothingAsserted;
  return kPassed;
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

std::string Catch::fpToString(double value, int) { return shortestText(value); }
std::string Catch::fpToString(float value, int) { return shortestText(value); }

CATCH_REGISTER_LISTENER(VerdictListener)

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--physlab-list") == 0) return listTests();
#if defined(PHYSLAB_PORTABLE_RUNNER) && defined(PHYSLAB_POSIX)
  startPortableChannel();
#endif
#if defined(PHYSLAB_POSIX)
  startRecords();
#endif
  Catch::Session session;
  const int status = session.applyCommandLine(argc, argv);
  if (status != 0) return status;
  const int failures = session.run();
  if (!channel.graded) return failures;
  std::cout.flush();
  std::fflush(nullptr);
  const Outcome code = outcome();
#if !defined(PHYSLAB_PORTABLE_RUNNER)
  _exit(code);
#else
#if defined(PHYSLAB_POSIX)
  portableVerdict(code);
#endif
  std::_Exit(code);
#endif
}
