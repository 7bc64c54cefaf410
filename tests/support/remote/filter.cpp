// Writes the seccomp filter of a grading worker (docs/grading.md, "Where submitted code runs") as
// a BPF program, for `bwrap --seccomp` or a kernel that installs it before the worker starts.
//
//   physlab_worker_filter OUT
//
// The worker may compute and talk on the pipes it was given, nothing else: read and write on its
// descriptors, memory (brk, mmap, mremap, mprotect, madvise), the clock, the calls a static
// program makes as it starts, and its own end. execve is allowed because the sandbox's own exec
// of the worker comes after the filter; the sandbox's view of the file system holds nothing else
// to start. Every other call fails with EPERM (open, socket, kill, ptrace, process_vm_readv,
// fork, ...); a call of another architecture's table kills the process.
#include <fcntl.h>
#include <seccomp.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <initializer_list>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: physlab_worker_filter OUT\n");
    return 2;
  }
  scmp_filter_ctx filter = seccomp_init(SCMP_ACT_ERRNO(EPERM));
  if (filter == nullptr) {
    std::fprintf(stderr, "physlab_worker_filter: seccomp_init failed\n");
    return 1;
  }
  const std::initializer_list<int> allowed = {
      SCMP_SYS(read), SCMP_SYS(write), SCMP_SYS(readv), SCMP_SYS(writev), SCMP_SYS(close),
      SCMP_SYS(brk), SCMP_SYS(mmap), SCMP_SYS(munmap), SCMP_SYS(mremap), SCMP_SYS(mprotect),
      SCMP_SYS(madvise), SCMP_SYS(futex), SCMP_SYS(clock_gettime), SCMP_SYS(clock_getres),
      SCMP_SYS(gettimeofday), SCMP_SYS(getrandom), SCMP_SYS(rt_sigreturn), SCMP_SYS(rt_sigprocmask),
      SCMP_SYS(arch_prctl), SCMP_SYS(set_tid_address), SCMP_SYS(set_robust_list), SCMP_SYS(rseq),
      SCMP_SYS(fstat), SCMP_SYS(newfstatat), SCMP_SYS(exit), SCMP_SYS(exit_group), SCMP_SYS(execve),
      SCMP_SYS(wait4), SCMP_SYS(waitid)};
  for (const int call : allowed) {
    if (seccomp_rule_add(filter, SCMP_ACT_ALLOW, call, 0) != 0) {
      std::fprintf(stderr, "physlab_worker_filter: cannot allow system call %d\n", call);
      return 1;
    }
  }
  const int out = open(argv[1], O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (out < 0 || seccomp_export_bpf(filter, out) != 0 || close(out) != 0) {
    std::fprintf(stderr, "physlab_worker_filter: cannot write %s: %s\n", argv[1], std::strerror(errno));
    return 1;
  }
  seccomp_release(filter);
  return 0;
}
