"""Where and as whom submitted code runs (Sandbox): this run's own identities, resource limits,
process groups, and the kill and sweep that end whatever a run left behind.
"""

import ctypes
import functools
import heapq
import itertools
import os
import shutil
import signal
import stat
import subprocess
import threading
import time
from pathlib import Path

from .common import OUTPUT_FILE_LIMIT, SANDBOX_PROCESSES

# Identities of submitted code when the grader runs as root: a number no other run on the machine
# has, IDENTITY_BASE + (the grader's process id << 8) + n, with n a slot (a parallel job) or, for
# groups, a submission graded at the same time. Process ids are unique while their process runs,
# so two grades at once (two terminals, a grade beside `./physlab mutants`) never share one, and
# the clean-up of one ("kill every process of this identity") never reaches the other's. No user
# or group is created: the kernel needs only the numbers.
IDENTITY_BASE = 0x10000000
IDENTITY_SPAN = 1 << 30  # (largest process id, 2^22) << 8


class Sandbox:
    """Where and as whom student code runs. As root: one identity of this run per parallel slot
    (identity()), so that killing every process of that identity ends whatever a test left
    behind, and nothing of another run. Otherwise: the current user, with process groups and the
    grader as subreaper for orphans.

    Several submissions graded at once each have a Sandbox of their own with slots (users) no other
    one has (`first`), and as root a group of their own (`group`): only its users may enter that
    submission's sandbox folder, so no other submission's code can read its hidden tests."""

    # Processes started by any Sandbox and not yet reaped by their thread: a sweep leaves them
    # alone, whichever Sandbox (submission) runs them.
    lock = threading.Lock()
    live = set()

    def __init__(self, jobs: int, switch_user: bool, first: int = 0, group=None):
        self.root = switch_user and os.geteuid() == 0
        self.slots = list(range(first, first + max(1, jobs)))
        if self.slots[-1] > 127:
            raise RuntimeError("more than 128 parallel jobs: lower --jobs")
        self.free = list(self.slots)
        self.cond = threading.Condition()
        self.waiting, self.tickets = [], itertools.count()  # acquire()'s queue: (-priority, arrival)
        self.gid = identity(group) if self.root and group is not None else None
        self.isolation = None  # how checkers start workers (Isolation), for remote stages
        try:  # orphans of a killed test become our children, so the sweep can find them
            ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER
        except (OSError, AttributeError):
            pass

    def acquire(self, priority: float = 0.0) -> int:
        """A free slot. Of the threads waiting, the one of highest `priority` gets the next (a
        compile passes its file's size: the long compiles start first, so that no slot idles at
        the end of a grade while one long file compiles alone); equal ones in turn."""
        with self.cond:
            ticket = (-priority, next(self.tickets))
            heapq.heappush(self.waiting, ticket)
            while not self.free or self.waiting[0] != ticket:
                self.cond.wait()
            heapq.heappop(self.waiting)
            self.cond.notify_all()  # the next in line may take another free slot
            return self.free.pop()

    def release(self, slot: int) -> None:
        with self.cond:
            self.free.append(slot)
            self.cond.notify_all()

    def ids(self, slot: int):
        """(uid, gid) of the slot's identity as root; None otherwise."""
        return (identity(slot), identity(slot)) if self.root else None

    def limits(self, memory: int, cpu_seconds: float, fsize: int) -> list:
        nproc = SANDBOX_PROCESSES if self.root else count_processes(os.getuid()) + SANDBOX_PROCESSES
        return ["prlimit", f"--as={memory}", f"--nproc={nproc}", f"--fsize={fsize}",
                f"--cpu={int(cpu_seconds) + 1}", "--core=0", "--nofile=256", "--"]

    def processor(self, slot: int) -> list:
        """A prefix that keeps a command and its children on one processor of those this run may
        use, chosen by `slot`: a checker and its worker take turns on their pipes, so on one
        processor each reply wakes its reader without a hand-over between processors (Lab 1's
        Kepler test, 126,000 calls: 3.1 s to 2.1 s)."""
        cpus = sorted(os.sched_getaffinity(0))
        if len(cpus) < 2 or not self.can_pin():
            return []
        return ["taskset", "--cpu-list", str(cpus[slot % len(cpus)])]

    @functools.lru_cache(maxsize=None)
    def can_pin(self) -> bool:
        """Whether taskset is there and allowed to pin (a container may refuse the call): if not,
        checkers run unpinned, as fast as the scheduler makes them."""
        try:
            return shutil.which("taskset") is not None and subprocess.run(
                ["taskset", "--cpu-list", str(min(os.sched_getaffinity(0))), "true"],
                capture_output=True, timeout=10).returncode == 0
        except (OSError, subprocess.TimeoutExpired):
            return False

    def spawn(self, cmd: list, ids, **options) -> subprocess.Popen:
        """Starts cmd in a session of its own, as the sandbox user `ids` (uid, gid) if any; the
        sweep leaves it alone until run() or end() has waited for it."""
        with self.lock:
            proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, start_new_session=True,
                                    user=ids[0] if ids else None, group=ids[1] if ids else None,
                                    extra_groups=([self.gid] if self.gid is not None else []) if ids else None,
                                    **options)
            self.live.add(proc.pid)
        return proc

    def run(self, cmd: list, *, slot: int, cwd: Path, timeout: float, memory: int,
            stdout: int, pass_fds=(), extra_env=None, fsize: int = OUTPUT_FILE_LIMIT) -> tuple:
        """Runs cmd in its own session; returns (returncode or None on timeout, seconds)."""
        env = {"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8", "HOME": str(cwd), "TMPDIR": str(cwd)}
        env.update(extra_env or {})
        ids = self.ids(slot)
        start = time.monotonic()
        proc = self.spawn(self.limits(memory, timeout, fsize) + cmd, ids, cwd=cwd, env=env,
                          stdout=stdout, stderr=stdout, pass_fds=pass_fds)
        try:
            code = proc.wait(timeout=max(timeout, 0.1))
        except subprocess.TimeoutExpired:
            code = None
        finally:
            kill_group(proc.pid)
            proc.wait()
            with self.lock:
                self.live.discard(proc.pid)
            self.end(slot)
        return code, time.monotonic() - start

    def end(self, slot: int) -> None:
        """Kills every process a run left behind."""
        ids = self.ids(slot)
        if ids:
            # kill(-1) as the sandbox user: every process of that user but the shell; three times,
            # for a process that was forking at the first (one shell: a process start costs more
            # than the kills, and a grade ends some 150 runs)
            killer = self.spawn(["/bin/sh", "-c", "kill -9 -1; kill -9 -1; kill -9 -1"], ids,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            killer.wait()
            with self.lock:
                self.live.discard(killer.pid)
        self.sweep()

    def sweep(self) -> None:
        """Kills and reaps our children that no running test owns: orphans of ended tests. As root
        student code runs only as the sandbox users, so the grader's own tools (the linker, nm),
        which run as root, are left alone: another submission graded at once may be using them."""
        me = os.getpid()
        for _ in range(50):
            with self.lock:
                orphans = [p for p, ppid, uid in proc_stats() if ppid == me and p not in self.live
                           and not (self.root and uid == 0)]
            if not orphans:
                return
            for pid in orphans:
                kill_group(pid)
                try:
                    os.kill(pid, signal.SIGKILL)
                    os.waitpid(pid, 0)
                except (ProcessLookupError, ChildProcessError, PermissionError):
                    pass

    def finish(self) -> None:
        for slot in self.slots:
            self.end(slot)
            if self.root:
                remove_files_of(self.ids(slot)[0])


def identity(n: int) -> int:
    """This run's identity number n (a uid or gid): see IDENTITY_BASE."""
    return IDENTITY_BASE + (os.getpid() << 8) + n


def is_identity(number: int) -> bool:
    """Whether a uid is one the grader gives submitted code (in any run)."""
    return IDENTITY_BASE <= number < IDENTITY_BASE + IDENTITY_SPAN


def grader_of(number: int) -> int:
    """The process id of the grader whose identity `number` is."""
    return (number - IDENTITY_BASE) >> 8


def kill_group(pid: int) -> None:
    try:
        os.killpg(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def proc_stats():
    """(pid, ppid, uid) of every process."""
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            with open(f"/proc/{entry.name}/stat") as f:
                ppid = int(f.read().rsplit(")", 1)[1].split()[1])
            yield int(entry.name), ppid, entry.stat().st_uid
        except (OSError, IndexError, ValueError):
            continue


def count_processes(uid: int) -> int:
    return sum(1 for _, _, u in proc_stats() if u == uid)


def remove_files_of(uid: int, folders=("/tmp", "/var/tmp", "/dev/shm")) -> None:
    """Deletes what a sandbox user left in the world-writable folders: it can create files only in
    those and in folders of its own, so only world-writable folders are searched."""
    for folder in folders:
        try:
            entries = list(os.scandir(folder))
        except OSError:
            continue
        for entry in entries:
            try:
                info = entry.stat(follow_symlinks=False)
                if info.st_uid == uid:
                    if stat.S_ISDIR(info.st_mode):
                        shutil.rmtree(entry.path, ignore_errors=True)
                    else:
                        os.unlink(entry.path)
                elif stat.S_ISDIR(info.st_mode) and info.st_mode & 0o002:
                    remove_files_of(uid, (entry.path,))
            except OSError:
                pass


def make_private(path: Path) -> None:
    """Takes other users' access away (as root, before student code runs as a sandbox user)."""
    if path.exists():
        os.chmod(path, stat.S_IMODE(os.stat(path).st_mode) & ~0o077)
