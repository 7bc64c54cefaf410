// The checker's connection to its worker, the worker's loop, and exceptions across the wire.
#include "remote.hpp"

#include <fcntl.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/uio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>

#include "handles.hpp"
#include "physlab/error.hpp"
#include "physlab/lcp.hpp"

namespace physlab::remote {

Family currentFamily(const std::exception& error) {
  if (dynamic_cast<const NotImplemented*>(&error)) return Family::NotImplemented;
  if (dynamic_cast<const InvalidInput*>(&error)) return Family::InvalidInput;
  if (dynamic_cast<const LcpFailure*>(&error)) return Family::LcpFailure;
  if (dynamic_cast<const NumericalFailure*>(&error)) return Family::NumericalFailure;
  if (dynamic_cast<const std::invalid_argument*>(&error)) return Family::InvalidArgument;
  if (dynamic_cast<const std::out_of_range*>(&error)) return Family::OutOfRange;
  if (dynamic_cast<const std::domain_error*>(&error)) return Family::DomainError;
  if (dynamic_cast<const std::length_error*>(&error)) return Family::LengthError;
  if (dynamic_cast<const std::logic_error*>(&error)) return Family::LogicError;
  if (dynamic_cast<const std::runtime_error*>(&error)) return Family::RuntimeError;
  if (dynamic_cast<const std::bad_alloc*>(&error)) return Family::BadAlloc;
  return Family::Other;
}

namespace {

// An exception of family Base whose what() is the worker's message, word for word.
template <class Base>
class Carried : public Base {
 public:
  template <class... A>
  Carried(std::string message, A&&... base) : Base(std::forward<A>(base)...), message_(std::move(message)) {}
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

class OtherError : public std::exception {
 public:
  explicit OtherError(std::string message) : message_(std::move(message)) {}
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

}  // namespace

void rethrow(Family family, const std::string& message) {
  switch (family) {
    case Family::NotImplemented: throw Carried<NotImplemented>(message, "", "");
    case Family::InvalidInput: throw Carried<InvalidInput>(message, "");
    case Family::LcpFailure: throw Carried<LcpFailure>(message, "");
    case Family::NumericalFailure: throw Carried<NumericalFailure>(message, "");
    case Family::InvalidArgument: throw std::invalid_argument(message);
    case Family::OutOfRange: throw std::out_of_range(message);
    case Family::DomainError: throw std::domain_error(message);
    case Family::LengthError: throw std::length_error(message);
    case Family::LogicError: throw std::logic_error(message);
    case Family::RuntimeError: throw std::runtime_error(message);
    case Family::BadAlloc: throw std::bad_alloc();
    case Family::Other: break;
  }
  throw OtherError(message);
}

void Call::throwHere() {
  Family family = Family::Other;
  std::string message;
  get(*reader_, family);
  get(*reader_, message);
  finish();
  rethrow(family, message);
}

void Call::finish() {
  if (reader_->remaining() != 0) throw WireError(std::to_string(reader_->remaining()) + " bytes more than the reply holds");
}

namespace {

constexpr int kRequests = 3;  // the worker reads requests here
constexpr int kReplies = 4;   // and writes replies here
constexpr int kFilter = 5;    // the seccomp filter, for the sandbox's command (bwrap --seccomp 5)
constexpr std::uint32_t kLargestMessage = 1u << 30;

bool writeAll(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t wrote = ::write(fd, data, size);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return false;
    data += wrote;
    size -= static_cast<std::size_t>(wrote);
  }
  return true;
}

bool readAll(int fd, char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t got = ::read(fd, data, size);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    data += got;
    size -= static_cast<std::size_t>(got);
  }
  return true;
}

// A message is its size (4 bytes), its Tag (1 byte, counted in the size) and its bytes, written
// with one system call and, when it fits in kChunk, read with one: a call's round trip costs four
// system calls, not eight.
constexpr std::size_t kChunk = 1 << 16;
constexpr std::size_t kHeader = sizeof(std::uint32_t) + 1;

bool sendMessage(int fd, Tag tag, const std::vector<char>& payload) {
  char header[kHeader];
  const auto size = static_cast<std::uint32_t>(payload.size() + 1);
  std::memcpy(header, &size, sizeof size);
  header[sizeof size] = static_cast<char>(tag);
  iovec parts[2] = {{header, kHeader}, {const_cast<char*>(payload.data()), payload.size()}};
  const std::size_t total = kHeader + payload.size();
  ssize_t wrote;
  do {
    wrote = ::writev(fd, parts, 2);
  } while (wrote < 0 && errno == EINTR);
  if (wrote < 0) return false;
  auto done = static_cast<std::size_t>(wrote);
  if (done < kHeader) {
    if (!writeAll(fd, header + done, kHeader - done)) return false;
    done = kHeader;
  }
  return done == total || writeAll(fd, payload.data() + (done - kHeader), total - done);
}

// 1: a message, 0: the other end closed, -1: a size the protocol does not allow, or more bytes
// than the message (nothing is ever sent before the answer to the last message is read).
int receiveMessage(int fd, std::vector<char>& payload, Tag& tag) {
  payload.resize(kChunk);
  std::size_t got = 0;
  while (got < kHeader) {
    const ssize_t n = ::read(fd, payload.data() + got, payload.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return 0;
    got += static_cast<std::size_t>(n);
  }
  std::uint32_t size = 0;
  std::memcpy(&size, payload.data(), sizeof size);
  if (size < 1 || size > kLargestMessage) return -1;
  const std::size_t total = sizeof size + size;
  if (got > total) return -1;
  payload.resize(total);
  if (!readAll(fd, payload.data() + got, total - got)) return 0;
  tag = static_cast<Tag>(payload[sizeof size]);
  payload.erase(payload.begin(), payload.begin() + kHeader);
  return 1;
}

// The checker's worker: started at the first call, gone when the test process ends.
struct Worker {
  pid_t pid = -1;
  int requests = -1;
  int replies = -1;
  std::string failure;  // set once the worker is gone: every later call fails the same way

  void start() {
    const char* command = std::getenv("PHYSLAB_WORKER");
    if (command == nullptr || *command == '\0') {
      throw WorkerFailure("no worker to run the submitted code: PHYSLAB_WORKER is not set (the grader sets it)");
    }
    std::vector<std::string> words;
    for (const char* at = command;;) {
      const char* end = std::strchr(at, '\x1f');
      words.emplace_back(at, end ? static_cast<std::size_t>(end - at) : std::strlen(at));
      if (!end) break;
      at = end + 1;
    }
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    // The seccomp filter: handed to the sandbox's command on descriptor 5 (bwrap --seccomp 5),
    // or, where there is no such sandbox (PHYSLAB_WORKER_FILTER_MODE=install), installed here
    // in the child before it starts the worker.
    const char* filter = std::getenv("PHYSLAB_WORKER_FILTER");
    const char* mode = std::getenv("PHYSLAB_WORKER_FILTER_MODE");
    const bool install = mode != nullptr && std::strcmp(mode, "install") == 0;
    int to_worker[2], from_worker[2];
    if (pipe2(to_worker, O_CLOEXEC) != 0 || pipe2(from_worker, O_CLOEXEC) != 0) {
      throw WorkerFailure(std::string("could not make the worker's pipes: ") + std::strerror(errno));
    }
    const int filter_fd = filter ? ::open(filter, O_RDONLY | O_CLOEXEC) : -1;
    if (filter && filter_fd < 0) throw WorkerFailure(std::string("could not open the worker's filter ") + filter);
    std::vector<sock_filter> program;
    if (install) {
      if (filter_fd < 0) throw WorkerFailure("PHYSLAB_WORKER_FILTER_MODE=install without PHYSLAB_WORKER_FILTER");
      sock_filter instruction{};
      while (readAll(filter_fd, reinterpret_cast<char*>(&instruction), sizeof instruction)) program.push_back(instruction);
      if (program.empty()) throw WorkerFailure(std::string("the worker's filter ") + filter + " is empty");
    }
    const sock_fprog rules_program{static_cast<unsigned short>(program.size()), program.data()};
    // Tells the start of the worker (its exec) from anything the worker's code does: the child
    // writes errno here only if exec fails; a successful exec closes it empty.
    int started[2];
    if (pipe2(started, O_CLOEXEC) != 0) throw WorkerFailure(std::string("could not make a pipe: ") + std::strerror(errno));
    const pid_t child = fork();
    if (child < 0) throw WorkerFailure(std::string("could not start the worker: ") + std::strerror(errno));
    if (child == 0) {
      // Only async-signal-safe calls from here to exec; a failure says errno on `report`.
      const int report = fcntl(started[1], F_DUPFD_CLOEXEC, 16);
      const auto fail = [report] {
        const int error = errno;
        writeAll(report, reinterpret_cast<const char*>(&error), sizeof error);
        _exit(126);
      };
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      const int null = ::open("/dev/null", O_RDWR);
      if (report < 0 || null < 0 || dup2(null, 0) < 0 || dup2(null, 1) < 0 || dup2(null, 2) < 0) fail();
      // Above the three numbers first, so that no dup2 below overwrites a descriptor still needed.
      const int in = fcntl(to_worker[0], F_DUPFD_CLOEXEC, 16);
      const int out = fcntl(from_worker[1], F_DUPFD_CLOEXEC, 16);
      const int rules = filter_fd >= 0 ? fcntl(filter_fd, F_DUPFD_CLOEXEC, 16) : -1;
      if (in < 0 || out < 0 || dup2(in, kRequests) < 0 || dup2(out, kReplies) < 0) fail();
      if (rules >= 0 && dup2(rules, kFilter) < 0) fail();
      // Nothing else the checker holds reaches the worker (its records of verdicts above all):
      // every other descriptor closes at the exec
      if (close_range(kFilter + 1, ~0U, CLOSE_RANGE_CLOEXEC) != 0) {  // a kernel before 5.11
        for (int fd = kFilter + 1; fd < 65536; ++fd) fcntl(fd, F_SETFD, FD_CLOEXEC);
      }
      if (install && (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0 ||
                      prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &rules_program) != 0)) {
        fail();
      }
      execv(argv[0], argv.data());
      fail();
    }
    ::close(started[1]);
    int error = 0;
    const bool failed = readAll(started[0], reinterpret_cast<char*>(&error), sizeof error);
    ::close(started[0]);
    if (failed) {
      waitpid(child, nullptr, 0);
      throw WorkerFailure(std::string("could not start the worker ") + argv[0] + ": " + std::strerror(error));
    }
    ::close(to_worker[0]);
    ::close(from_worker[1]);
    if (filter_fd >= 0) ::close(filter_fd);
    pid = child;
    ++workerEpoch();  // a new worker knows nothing of what crossed to the last one
    requests = to_worker[1];
    replies = from_worker[0];
    signal(SIGPIPE, SIG_IGN);  // a worker gone while we write: write() says so
  }

  // Why the worker is gone, from its exit status.
  std::string ending() {
    int status = 0;
    pid_t got;
    do {
      got = waitpid(pid, &status, 0);
    } while (got < 0 && errno == EINTR);
    if (got != pid) return "ended";
    if (WIFSIGNALED(status)) {
      const int number = WTERMSIG(status);
      const char* name = sigabbrev_np(number);
      return "was killed by signal " + std::to_string(number) + (name ? std::string(" (SIG") + name + ")" : "");
    }
    const int code = WEXITSTATUS(status);
    // bubblewrap ends with 128 + the signal that killed the worker inside it
    const char* name = code > 128 ? sigabbrev_np(code - 128) : nullptr;
    return "exited with status " + std::to_string(code) +
           (name ? std::string(" (killed by SIG") + name + " in its sandbox)" : std::string());
  }
};

Worker& worker() {
  static Worker instance;
  return instance;
}

}  // namespace

void endWorker() {
  Worker& w = worker();
  if (w.pid < 0) return;
  ::close(w.requests);
  ::close(w.replies);
  kill(w.pid, SIGKILL);
  w.ending();
  w = Worker{};
}

namespace {

// How a test process ends when the worker fails it (tests/support/runner.cpp, Outcome): a failed
// test, or, when the worker could not be started at all, a test the grader could not run.
constexpr int kFailed = 1;
constexpr int kNotGraded = 5;

// A worker that ended during a call fails the test whatever the test expects of the call (a
// check that the call throws must not pass on a crash): the reason goes to the report, and the
// test process ends.
[[noreturn]] void endTest(const std::string& why, int code = kFailed) {
  const std::string line = "\nphyslab: " + why + "\n";
  writeAll(2, line.data(), line.size());
  std::fflush(nullptr);
  _exit(code);
}

// Calls in progress in the checker: 1 during a call, more while a callback's code makes calls of
// its own. Handles live while it is above 0 (handles.hpp).
int depth = 0;

}  // namespace

void beginCall() {
  if (depth == 0) forgetHandles();
}

std::vector<char> exchange(const char* function, Writer& request) {
  Worker& w = worker();
  if (!w.failure.empty()) endTest(w.failure);
  if (w.pid < 0) {
    try {
      w.start();
    } catch (const WorkerFailure& error) {
      endTest(error.what(), kNotGraded);
    }
  }
  struct Nesting {
    Nesting() { ++depth; }
    ~Nesting() {
      if (--depth == 0) forgetHandles();
    }
  } nesting;
  std::vector<char> message;
  Tag tag = Tag::Reply;
  int got = 0;
  if (sendMessage(w.requests, Tag::Request, request.buffer())) got = receiveMessage(w.replies, message, tag);
  while (got == 1 && tag == Tag::Callback) {
    Writer answer;
    try {
      Reader in(message.data(), message.size());
      answerCallback(in, answer);
    } catch (const WireError& error) {
      kill(w.pid, SIGKILL);
      w.ending();
      w.failure = std::string("the submitted code's process made a callback no call allows, during ") + function +
                  ": " + error.what();
      endTest(w.failure);
    }
    got = sendMessage(w.requests, Tag::Answer, answer.buffer()) ? receiveMessage(w.replies, message, tag) : 0;
  }
  if (got == 1 && tag == Tag::Reply) return message;
  if (got != 0) {
    kill(w.pid, SIGKILL);
    w.ending();
    w.failure = std::string("the submitted code's process sent a message no call has, during ") + function;
  } else {
    w.failure = std::string("the submitted code's process ") + w.ending() + " during " + function +
                "() (in your own `./physlab test`, run this test under a debugger to see where)";
  }
  endTest(w.failure);
}

namespace {

// The worker's table, for the requests that come while a callback waits for its answer.
const Entry* served = nullptr;
std::uint32_t served_size = 0;

// Answers one request: 0 when answered, -1 when the checker has closed its end, else the worker's
// exit status (a function the table does not have). Each request has its own buffers: a nested
// one is answered while the entry that made the callback still reads its own.
int serveRequest(const std::vector<char>& request) {
  Reader in(request.data(), request.size());
  std::uint32_t index = 0;
  get(in, index);
  if (index >= served_size) return 3;
  Writer out;
  served[index](in, out);
  return sendMessage(kReplies, Tag::Reply, out.buffer()) ? 0 : -1;
}

}  // namespace

int serve(const Entry* table, std::uint32_t size) {
  served = table;
  served_size = size;
  std::vector<char> request;
  for (;;) {
    Tag tag = Tag::Request;
    const int got = receiveMessage(kRequests, request, tag);
    if (got == 0) return 0;
    if (got < 0 || tag != Tag::Request) return 2;
    const int status = serveRequest(request);
    if (status != 0) return status < 0 ? 0 : status;
  }
}

std::vector<char> callBack(Writer& callback) {
  if (!sendMessage(kReplies, Tag::Callback, callback.buffer())) _exit(0);
  std::vector<char> message;
  for (;;) {
    Tag tag = Tag::Answer;
    const int got = receiveMessage(kRequests, message, tag);
    if (got == 0) _exit(0);
    if (got < 0 || (tag != Tag::Answer && tag != Tag::Request)) _exit(2);
    if (tag == Tag::Answer) return message;
    const int status = serveRequest(message);
    if (status != 0) _exit(status < 0 ? 0 : status);
  }
}

}  // namespace physlab::remote
