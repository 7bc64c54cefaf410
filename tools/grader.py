#!/usr/bin/env python3
"""PhysLab's test runner and autograder.

Runs every Catch2 test case in its own process group with a time limit and resource limits, takes
each verdict from an authenticated channel (tests/support/runner.cpp) rather than from anything the
test prints, and writes a readable report plus Gradescope's results.json. `grade` compiles a
submission's lab files apart from the instructor's tree (in bubblewrap where allowed), checks what
the objects define, and links them with the instructor's prebuilt objects (Lab 4) or into a
sandboxed worker that the instructor's checker calls (Labs 1, 2, 3, 5, 6: Isolation, Program), running
everything as this run's own identities when run as root. The design and its limits are on the
Grading page (docs/grading.md).
"""

import argparse
import concurrent.futures
import ctypes
import functools
import hashlib
import hmac
import json
import os
import re
import secrets
import select
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import threading
import time
import tomllib
import xml.etree.ElementTree as ET
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import course as course_file  # noqa: E402  (tools/course.py, beside this file)

ROOT = Path(__file__).resolve().parent.parent
STAGE_RE = re.compile(r"^(\d\d)_[a-z0-9_]+$")
OUTPUT_LIMIT = 8000          # characters of a test's explanation kept in results.json
OUTPUT_FILE_LIMIT = 4 << 20  # bytes a test process may write to stdout and stderr together
SOURCE_LIMIT = 1 << 20       # bytes of one submitted source file
TEST_MEMORY = 2 << 30        # address space of a test process; the largest test uses ~100 MB
COMPILE_MEMORY = 4 << 30     # address space of the compiler on one lab file
COMPILE_OUTPUT = 256 << 20   # bytes of one object file (ours are under 2 MB)
SANDBOX_PROCESSES = 64       # processes a sandbox user may have at once
# Identities of submitted code when the grader runs as root: a number no other run on the machine
# has, IDENTITY_BASE + (the grader's process id << 8) + n, with n a slot (a parallel job) or, for
# groups, a submission graded at the same time. Process ids are unique while their process runs,
# so two grades at once (two terminals, a grade beside `./physlab mutants`) never share one, and
# the clean-up of one ("kill every process of this identity") never reaches the other's. No user
# or group is created: the kernel needs only the numbers.
IDENTITY_BASE = 0x10000000
IDENTITY_SPAN = 1 << 30  # (largest process id, 2^22) << 8
SHARED_LIBRARIES = ("libstdc++.so.6", "libm.so.6", "libc.so.6", "libgcc_s.so.1")
# Sections a compiled lab file may contain. Anything else (.preinit_array, prioritised
# .init_array.NNNNN, .ctors, .init, linker directives) could run code before the harness or change
# the link, and is refused.
ALLOWED_SECTIONS = re.compile(
    r"^(|\.text(\..*)?|\.data(\..*)?|\.bss(\..*)?|\.rodata(\..*)?|\.tdata(\..*)?|\.tbss(\..*)?|"
    r"\.init_array|\.fini_array|\.eh_frame|\.gcc_except_table(\..*)?|\.group|\.note\.GNU-stack|"
    r"\.note\.gnu\.property|\.comment|\.rela?\..*|\.symtab|\.strtab|\.shstrtab|\.debug_.*)$")

# What a lab file may reference beyond the framework's API and its own code (the Grading page,
# "What student code may use"): the C++ standard library's containers, strings, string streams,
# the standard streams, exceptions and allocation; libm; and the C functions below. Nothing that
# reaches files, processes, signals, memory maps, dynamic loading, threads, the environment or the
# kernel directly: a test process then cannot end itself with a status of its choosing, write to a
# descriptor it was not given, or read what it may not.
ALLOWED_C = frozenset("""
    malloc calloc realloc free aligned_alloc posix_memalign memalign
    memcpy memmove memset memcmp memchr strlen strnlen strcmp strncmp strchr strrchr strstr
    strcpy strncpy strcat strncat strtod strtof strtold strtol strtoll strtoul strtoull
    atof atoi atol atoll sscanf __isoc99_sscanf __isoc23_sscanf __isoc99_vsscanf __isoc23_vsscanf
    __isoc23_strtol __isoc23_strtoll __isoc23_strtoul __isoc23_strtoull
    snprintf sprintf vsnprintf vsprintf printf vprintf puts putchar fprintf vfprintf fputs fputc
    fwrite fflush stdout stderr __printf_chk __vprintf_chk __fprintf_chk __vfprintf_chk
    __snprintf_chk __sprintf_chk __vsnprintf_chk __vsprintf_chk __memcpy_chk __memmove_chk
    __memset_chk __strcpy_chk __strncpy_chk __strcat_chk __strncat_chk
    abort __assert_fail __stack_chk_fail qsort bsearch abs labs llabs div ldiv rand srand
    clock time clock_gettime gettimeofday __errno_location
    __ctype_b_loc __ctype_tolower_loc __ctype_toupper_loc tolower toupper isalpha isdigit isspace
    __gxx_personality_v0 _Unwind_Resume __dso_handle __libc_single_threaded __tls_get_addr
    _GLOBAL_OFFSET_TABLE_ __cxa_atexit __cxa_finalize __cxa_thread_atexit_impl __dynamic_cast
""".split())
# Demangled names of the C++ runtime a lab file may reference (the standard library as its
# headers instantiate it), less the parts that reach the system (FORBIDDEN_STD).
ALLOWED_STD = re.compile(r"^(?:(?:typeinfo|typeinfo name|vtable|VTT|construction vtable) for )?"
                         r"(?:std::|__gnu_cxx::|__cxxabiv1::|operator new|operator delete|__cxa_)")
# An instantiation of a standard-library template (a weak copy the headers make, never a C function).
STD_INSTANCE = re.compile(r"^(?:std::|__gnu_cxx::)[^(]*<")
# The framework's and the labs' own names (their vtables and type information included).
PHYSLAB_NAME = re.compile(r"^(?:(?:typeinfo|typeinfo name|vtable|VTT|construction vtable) for )?physlab::")
FORBIDDEN_STD = re.compile(
    r"^(?:(?:typeinfo|typeinfo name|vtable|VTT|construction vtable) for )?"
    r"(?:std::(?:__cxx11::)?(?:basic_filebuf|basic_ifstream|basic_ofstream|basic_fstream|"
    r"__basic_file|filesystem|experimental::filesystem|thread|this_thread|jthread|"
    r"condition_variable|mutex|recursive_mutex|timed_mutex|shared_mutex|__future_base|"
    r"__atomic_futex|__once_|call_once|set_terminate|set_unexpected|set_new_handler|"
    r"quick_exit|_Exit|exit|at_quick_exit|atexit|system)|"
    r"__gnu_cxx::stdio_(?:sync_)?filebuf)")
# Why a refused symbol is refused, by family (the first match names it).
FORBIDDEN_WHY = [
    (re.compile(r"exit|^_Exit"), "it ends the process; throw an exception instead"),
    (re.compile(r"^dl|_dl_|dl_iterate_phdr|_r_debug|_DYNAMIC|link_map"),
     "it loads code or walks the loaded objects"),
    (re.compile(r"fork|exec|spawn|system|popen|wait|kill|clone|daemon|setsid|setpgid|"
                r"setuid|setgid|ptrace|prctl|setrlimit|prlimit"),
     "it reaches other processes or the process itself"),
    (re.compile(r"signal|sigaction|sigprocmask|raise|alarm|setitimer|sigsuspend|pause|longjmp|setjmp"),
     "it handles signals or jumps out of the harness"),
    (re.compile(r"mmap|munmap|mprotect|mremap|madvise|brk|sbrk|shm|memfd|process_vm"),
     "it maps or protects memory"),
    (re.compile(r"syscall"), "it is a raw system call"),
    (re.compile(r"thread|mutex|cond|once|futex|sem_"),
     "it starts or synchronises threads; lab code is single-threaded"),
    (re.compile(r"env|environ|getpid|getuid|uname|hostname|socket|connect|bind|listen|accept|send|recv"),
     "it reaches the environment or the network"),
    (re.compile(r"open|creat|close|read|write|seek|stat|unlink|remove|rename|mkdir|rmdir|chdir|"
                r"link|chmod|chown|dup|pipe|fcntl|ioctl|sendfile|splice|truncate|sync|getdents|"
                r"filebuf|fstream|__basic_file|filesystem|FILE|tmp|opendir|readdir|fopen|fdopen|"
                r"freopen|fscanf|fgets|fread|getline|getchar|scanf"),
     "it reaches files; lab code reads and writes none"),
]
# Instructions that enter the kernel: no lab file needs one, and only inline assembly writes one.
KERNEL_ENTRY_RE = re.compile(r"^\s*[0-9a-f]+:\s+(syscall|sysenter|int\s+\$0x[0-9a-f]+|int1|vmcall)\b",
                             re.MULTILINE)
ASM_KEYWORD_RE = re.compile(r"\b(asm|__asm|__asm__)\b")


# ---- text that reaches a report ----------------------------------------------------------------

ANSI_RE = re.compile(r"\x1b(\[[0-9;?]*[ -/]*[@-~]|\][^\x07\x1b]*(\x07|\x1b\\)|[@-Z\\-_])")
CONTROL_RE = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def clean(text) -> str:
    """Text safe for a report: valid UTF-8, no escape sequences or control characters."""
    if isinstance(text, bytes):
        text = text.decode("utf-8", errors="replace")
    text = text.encode("utf-8", errors="replace").decode("utf-8")
    return CONTROL_RE.sub("", ANSI_RE.sub("", text.replace("\r\n", "\n")))


def read_capped(path: Path, limit: int = 1 << 20) -> str:
    try:
        with open(path, "rb") as f:
            return clean(f.read(limit))
    except OSError:
        return ""


# ---- tests and their results -------------------------------------------------------------------

@dataclass
class TestCase:
    """One Catch2 TEST_CASE of one stage, and what running it gave."""

    stage: str
    name: str
    tags: list
    status: str = "not run"  # passed | failed | not implemented | timed out | crashed | not compiled
    output: str = ""
    seconds: float = 0.0
    checks: list = field(default_factory=list)  # the failed checks, "file:line: expression"
    captured: dict = field(default_factory=dict)  # CAPTURE'd values of the first failure
    course_points: float = None  # the points a course file gives it (None: its tag's)
    course_hidden: bool = False  # hidden by the course file

    @property
    def points(self) -> float:
        if self.course_points is not None:
            return self.course_points
        for tag in self.tags:
            m = re.fullmatch(r"pts=(\d+(?:\.\d+)?)", tag)
            if m:
                return float(m.group(1))
        return 0.0

    @property
    def graded(self) -> bool:
        return "common" not in self.tags and self.points > 0

    @property
    def hidden(self) -> bool:
        return "hidden" in self.tags or self.course_hidden

    @property
    def sections(self) -> list:
        """The handout sections whose functions the test grades, from its [sec=N] tags."""
        return sorted({int(t[4:]) for t in self.tags if re.fullmatch(r"sec=\d+", t)})

    @property
    def units(self) -> frozenset:
        """The lab files (names without .cpp) whose functions the test grades: with the reference
        of the lab's other files, a finished file earns its tests' points (partial credit)."""
        table = section_files(self.stage)
        return frozenset(table[s] for s in self.sections if s in table)

    @property
    def unit(self):
        """The one lab file the test grades, or None when it grades several (a scene): such a test
        runs with all of the student's files of the lab."""
        return next(iter(self.units)) if len(self.units) == 1 else None

    @property
    def passed(self) -> bool:
        return self.status == "passed"


class GradingFailure(Exception):
    """The grading itself failed (not the submission): a stub that does not compile, a compile
    killed from outside, a sandbox that does not start. Never a score: the submission is "not
    graded", a class grade tries it once more, and `grade` exits non-zero."""


class SubmissionError(Exception):
    """The submission cannot be graded as it is (no labs/ folder): a score of 0 that says why."""


@dataclass(frozen=True)
class Program:
    """What runs a test: a test executable that links the submitted code (its verdict from the
    notary), or a checker that links none and starts `worker`, the submitted code's process.
    `batch`: code the grader trusts (a checker, or the tree's own tests), which runs many tests
    per process and records each one's verdict itself (run_batch())."""

    exe: Path
    worker: Path = None
    batch: bool = False


@dataclass
class StageResult:
    stage: str
    tests: list = field(default_factory=list)
    compile_error: str = ""
    notes: list = field(default_factory=list)
    how: str = ""  # how its tests ran, when not as usual (", checker and worker")


@functools.lru_cache(maxsize=None)
def section_files(stage: str) -> dict:
    """Handout section -> the lab file (name without .cpp) that holds its functions, read from the
    first line of each stub ("// Lab 4, sections 2-4 and 7: ..."). The instructor's stubs, never
    a submission's files."""
    return course_file.section_table(ROOT, stage)


def tag_problems(results: list) -> list:
    """Graded tests whose [sec=N] tags do not name a section of their lab's files: without one,
    partial credit and the handout hint cannot place them."""
    problems = []
    for r in results:
        for t in r.tests:
            if not t.graded:
                continue
            unknown = [s for s in t.sections if s not in section_files(r.stage)]
            if not t.sections or unknown:
                why = f"section {', '.join(map(str, unknown))} is in no lab file" if unknown else \
                      "no [sec=N] tag naming the handout section it grades"
                problems.append(f"lab {r.stage}: {t.name}: {why}")
    return problems


def discover_stages(root: Path) -> list:
    """Stage folders under tests/ (01_particles, 02_springs, ...), in order."""
    tests = root / "tests"
    return sorted(p.name for p in tests.iterdir() if p.is_dir() and STAGE_RE.match(p.name))


def select_stages(all_stages: list, wanted: list) -> list:
    """Stages matching the numbers or names the user gave ('01', '1', '01_particles')."""
    if not wanted:
        return all_stages
    chosen = []
    for w in wanted:
        matches = [s for s in all_stages if s == w or (w.isdigit() and s[:2] == w.zfill(2))]
        if not matches:
            raise SystemExit(f"grader: no lab '{w}' (labs: {', '.join(all_stages)})")
        chosen += [m for m in matches if m not in chosen]
    return chosen


def graded_stages(wanted: list, course) -> list:
    """The labs a grade takes: those named (all when none), and of those the course's."""
    stages = select_stages(discover_stages(ROOT), wanted)
    return stages if course is None else [s for s in stages if s in course.labs]


def escape_spec(name: str) -> str:
    """A test name as a Catch2 test spec that matches exactly that test."""
    return re.sub(r'([\\,\[\]*"~])', r"\\\1", name)


def list_tests(exe: Path, stage: str) -> list:
    """The test cases of an instructor-built executable, from its --physlab-list."""
    listing = subprocess.run([str(exe), "--physlab-list"], capture_output=True, timeout=60,
                             check=True).stdout.decode("ascii", errors="replace")
    cases = []
    for line in listing.splitlines():
        name_hex, _, tags = line.partition("\t")
        cases.append(TestCase(stage=stage, name=bytes.fromhex(name_hex).decode("utf-8", "replace"),
                              tags=[t for t in tags.split(",") if t]))
    return cases


# What Catch2 records as the expression of a failure outside any check: an exception or a signal
# after the last check (or section start) that ran, whose line it reports.
UNKNOWN_EXPRESSION = "{Unknown expression after the reported line}"
# Lines of explanation per failed test: report() shows 12, and judge() may put one of its own
# (crashed, timed out) before them.
FAILURE_LINES = 11


def where(node) -> str:
    return f"{Path(node.get('filename', '?')).name}:{node.get('line', '?')}"


def text_of(node) -> str:
    return (node.text or "").strip() if node is not None else ""


def indented(prefix: str, text: str) -> list:
    """The lines of text, the first after prefix and the others under it."""
    first, *rest = text.splitlines() or [""]
    return [prefix + first] + [" " * len(prefix) + line for line in rest]


def failure_of(node, notes: list):
    """A failure as (key, (what, where), detail lines, notes) from one node of Catch2's XML report
    (Expression, Exception, FatalErrorCondition or Failure) and the messages (INFO, CAPTURE) that
    Catch2 wrote before it; None for a check that passed. The key is the same for every failure of
    one check: its place and expression. Its headline is what + where, with a count between them
    when the check failed more than once."""
    if node.tag != "Expression":  # FAIL(), or an exception or signal before any check
        verb = {"Exception": "threw before any check", "FatalErrorCondition": "crashed before any check"}
        first, *rest = text_of(node).splitlines() or [""]
        place = f" (test at {where(node)}): {first}" if node.tag in verb else f" at {where(node)}: {first}"
        return (where(node), first), (verb.get(node.tag, "failed"), place), rest, notes
    if node.get("success") != "false":
        return None
    original = text_of(node.find("Original"))
    expanded = text_of(node.find("Expanded"))
    exception, fatal = node.find("Exception"), node.find("FatalErrorCondition")
    if UNKNOWN_EXPRESSION in original:  # after the check at that line, not in it
        verb, message = ("threw", text_of(exception)) if exception is not None else ("crashed", text_of(fatal))
        first, *rest = message.splitlines() or [""]
        return (where(node), first), (f"{verb} outside any check", f", after {where(node)}: {first}"), rest, notes
    kind = node.get("type") or "CHECK"
    details = []
    if expanded and expanded != original:
        details.append(f"actual: {expanded}")
    if exception is not None:
        details.append(f"threw: {text_of(exception)}")
    elif fatal is not None:
        details.append(f"crashed: {text_of(fatal)}")
    elif "THROWS" in kind and not details:
        details.append("nothing was thrown")
    return (where(node), original), (f"{kind}( {original} ) failed", f" at {where(node)}"), details, notes


def failures_in(node, found: list) -> None:
    """Appends the failures under `node` to `found`, in the order Catch2 met them."""
    notes = []
    for child in node:
        if child.tag == "Info":
            notes.append(text_of(child))
        elif child.tag in ("Expression", "Exception", "FatalErrorCondition", "Failure"):
            failure = failure_of(child, notes)
            if failure:
                found.append(failure)
            notes = []
        else:
            failures_in(child, found)


def fit(blocks: list, limit: int) -> list:
    """At most `limit` lines from blocks of [headline, what happened, more lines...]: the first two
    lines of as many blocks as fit, then their other lines, first block first; a last line counts
    the blocks left out."""
    shown = len(blocks)
    while shown > 0 and sum(len(b[:2]) for b in blocks[:shown]) + (shown < len(blocks)) > limit:
        shown -= 1
    room = limit - sum(len(b[:2]) for b in blocks[:shown]) - (shown < len(blocks))
    lines = []
    for block in blocks[:shown]:
        extra = block[2:2 + room]
        room -= len(extra)
        lines += block[:2] + extra
    if shown < len(blocks):
        lines.append(f"and {len(blocks) - shown} more failed check{'s' if len(blocks) - shown > 1 else ''}")
    return lines


CAPTURED_RE = re.compile(r"^(\w+) := (.*)$")
COMPARISON_RE = re.compile(r" (==|!=|<=|>=|<|>) ")


def short_number(text: str) -> str:
    """A number to four significant digits (what a hint needs), any other text as it is."""
    try:
        return f"{float(text):.4g}"
    except ValueError:
        return text


def describe_failure(output: str) -> tuple:
    """(status, explanation, failed checks, captured values) from the Catch2 XML report inside a
    test's output: each distinct failed check once (a check in a loop says how many times it
    failed, and shows its first failure), what happened, then the messages in scope, within
    FAILURE_LINES lines; the checks as "file:line: expression" for the class page, and the values
    CAPTURE()d at the first failure (name -> text) for the hints. The output is the student's as
    much as the harness's: it only explains, it never decides a pass."""
    start, end = output.find("<Catch"), output.rfind("</Catch>")
    if start < 0 or end < 0:
        return "failed", "", [], {}
    try:
        tree = ET.fromstring(output[start:end + len("</Catch>")])
    except ET.ParseError:
        return "failed", "", [], {}
    found = []
    failures_in(tree, found)
    counts, firsts = {}, {}
    for key, head, details, notes in found:
        counts[key] = counts.get(key, 0) + 1
        firsts.setdefault(key, (head, details, notes))
    blocks = []
    for key, ((what, place), details, notes) in firsts.items():
        head = what + (f" {counts[key]} times{place}; the first:" if counts[key] > 1 else place)
        blocks.append([head] + [line for d in details for line in indented("  ", d)]
                      + [line for n in notes for line in indented("  note: ", n)])
    text = [line for block in blocks for line in block]
    status = "not implemented" if any("not implemented" in line for line in text) else "failed"
    checks = [clean(f"{place}: {expression}") for place, expression in firsts]
    captured = {}
    for note in (found[0][3] if found else []):
        m = CAPTURED_RE.match(note)
        if m:
            captured[m.group(1)] = short_number(clean(m.group(2)))[:80]
    actual = next((d[len("actual: "):] for d in (found[0][2] if found else []) if d.startswith("actual: ")), "")
    sides = COMPARISON_RE.split(re.sub(r"\s+", " ", actual), maxsplit=1)  # Catch2 may wrap long sides
    if len(sides) == 3:  # the first failed comparison's two sides, as the test wrote them
        captured["lhs"], captured["rhs"] = (short_number(clean(side.strip()))[:80] for side in sides[::2])
    return status, "\n".join(fit(blocks, FAILURE_LINES)), checks, captured


# ---- running untrusted processes ---------------------------------------------------------------

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
        self.gid = identity(group) if self.root and group is not None else None
        self.isolation = None  # how checkers start workers (Isolation), for remote stages
        try:  # orphans of a killed test become our children, so the sweep can find them
            ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER
        except (OSError, AttributeError):
            pass

    def acquire(self) -> int:
        with self.cond:
            while not self.free:
                self.cond.wait()
            return self.free.pop()

    def release(self, slot: int) -> None:
        with self.cond:
            self.free.append(slot)
            self.cond.notify()

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
            for _ in range(3):  # kill(-1) as the sandbox user: every process of that user
                killer = self.spawn(["/bin/sh", "-c", "kill -9 -1"], ids,
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


class Isolation:
    """How a checker starts its worker (docs/grading.md, "Where submitted code runs"): in
    bubblewrap's namespaces (no other process, no network, a file system holding the worker
    alone) with the seccomp filter, which lets it compute and talk on its pipes only; or, where
    namespaces are refused (an unprivileged container), with the filter alone, installed by the
    checker before the worker starts, under the run's own identity."""

    def __init__(self, kit: "Kit", folder: Path, sandbox: Sandbox):
        """Probes, as the identity tests run under, with a copy of a reference worker in `folder`
        (one the sandbox's identities may read), which kind the machine allows."""
        ids = sandbox.ids(sandbox.slots[0])
        extra = [sandbox.gid] if ids and sandbox.gid is not None else []
        self.filter = folder / "worker.bpf"
        shutil.copyfile(kit.toolchain["worker_filter"], self.filter)
        os.chmod(self.filter, 0o644)
        self.bwrap = shutil.which("bwrap")
        self.why = "bubblewrap (bwrap) is not installed"
        if self.bwrap:
            reference = next(spec["reference_worker"] for spec in kit.stages.values() if "checker" in spec)
            probe = folder / "probe-worker"
            shutil.copyfile(reference, probe)
            os.chmod(probe, 0o755)
            try:
                proc = subprocess.run(["/bin/sh", "-c", 'exec "$@" 5<"$PHYSLAB_FILTER"', "sh"] + self.command(probe),
                                      env={"PATH": "/usr/bin:/bin", "PHYSLAB_FILTER": str(self.filter)},
                                      user=ids[0] if ids else None, group=ids[1] if ids else None,
                                      extra_groups=extra if ids else None, capture_output=True, text=True,
                                      errors="replace", timeout=30)
                self.why = "" if proc.returncode == 0 else \
                    f"namespaces refused: {clean(proc.stderr).strip()[:200] or f'bwrap exited {proc.returncode}'}"
            except (OSError, subprocess.TimeoutExpired) as error:
                self.why = f"bwrap did not start: {error}"
            finally:
                probe.unlink(missing_ok=True)

    def command(self, worker: Path) -> list:
        return [self.bwrap, "--unshare-all", "--die-with-parent", "--new-session", "--cap-drop", "ALL",
                "--clearenv", "--ro-bind", str(worker), "/worker", "--seccomp", "5", "--chdir", "/", "/worker"]

    def compiling(self, cmd: list, work: Path, include: Path, precompiled: Path = None) -> list:
        """`cmd` (a compile of a submitted file in `work`) in bubblewrap's namespaces where they
        are allowed: the compiler sees the system's files (/usr), the framework's headers and the
        file, and nothing of the instructor's tree, other submissions or the network."""
        if self.why:
            return cmd
        view = ["--ro-bind", "/usr", "/usr"]
        for link in ("/bin", "/lib", "/lib64", "/sbin"):
            if os.path.islink(link):
                view += ["--symlink", os.readlink(link), link]
            elif os.path.isdir(link):
                view += ["--ro-bind", link, link]
        if os.path.isdir("/etc/alternatives"):
            view += ["--ro-bind", "/etc/alternatives", "/etc/alternatives"]
        return [self.bwrap, "--unshare-all", "--die-with-parent", "--new-session", "--cap-drop", "ALL",
                *view, "--dev", "/dev", "--tmpfs", "/tmp", "--ro-bind", str(include), str(include),
                *(["--ro-bind", str(precompiled), str(precompiled)] if precompiled else []),
                "--bind", str(work), str(work), "--chdir", str(work), "--"] + cmd

    def describe(self) -> str:
        if not self.why:
            return "your code ran in a process of its own: bubblewrap namespaces and a seccomp filter"
        return f"your code ran in a process of its own: a seccomp filter and this run's own identity ({self.why})"

    def environment(self, worker: Path) -> dict:
        """What a checker needs to start `worker` (tests/support/remote/remote.cpp)."""
        if not self.why:
            return {"PHYSLAB_WORKER": "\x1f".join(self.command(worker)), "PHYSLAB_WORKER_FILTER": str(self.filter)}
        return {"PHYSLAB_WORKER": str(worker), "PHYSLAB_WORKER_FILTER": str(self.filter),
                "PHYSLAB_WORKER_FILTER_MODE": "install"}


class Deadline:
    """The time left for grading; None means no overall limit."""

    def __init__(self, seconds):
        self.end = None if seconds is None else time.monotonic() + seconds

    def left(self) -> float:
        return float("inf") if self.end is None else self.end - time.monotonic()


def run_one(sandbox: Sandbox, program: Program, case: TestCase, seed: int, timeout: float,
            deadline: Deadline, scratch: Path, homes: Path, env=None) -> TestCase:
    """Runs one test case in homes/home-<slot>, its output and verdict files in the private
    `scratch`, with `env` added to its environment; its status comes from the harness's
    authenticated verdict."""
    budget = min(timeout, deadline.left())
    if budget <= 1.0:
        case.status, case.output = "not run", "not run: the grading deadline was reached"
        return case
    slot = sandbox.acquire()
    try:
        run_sandboxed_test(sandbox, slot, program, case, seed, budget, scratch, homes, env)
    except Exception as error:  # an error of the grader's own costs this test, not the grade
        case.status, case.output = "crashed", f"the grader could not run this test: {error}"
    finally:
        sandbox.release(slot)
    return case


def run_sandboxed_test(sandbox: Sandbox, slot: int, program: Program, case: TestCase, seed: int,
                       budget: float, scratch: Path, homes: Path, env=None) -> None:
    key = secrets.token_hex(32)
    work = Path(tempfile.mkdtemp(dir=scratch, prefix="test-"))
    home = homes / f"home-{slot}"
    try:
        read_end, write_end = os.pipe()
        os.write(write_end, key.encode())
        os.close(write_end)
        out_fd = os.open(work / "output", os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
        verdict_fd = os.open(work / "verdict", os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
        cmd = [str(program.exe), escape_spec(case.name), "-r", "xml", "--rng-seed", str(seed)]
        variables = {**(env or {}), "PHYSLAB_VERDICT": f"{read_end}:{verdict_fd}:{case.name.encode('utf-8').hex()}"}
        if program.worker is not None:
            variables.update(sandbox.isolation.environment(program.worker))
        try:
            code, case.seconds = sandbox.run(
                cmd, slot=slot, cwd=home, timeout=budget, memory=TEST_MEMORY, stdout=out_fd,
                pass_fds=(read_end, verdict_fd), extra_env=variables)
        finally:
            for fd in (read_end, out_fd, verdict_fd):
                os.close(fd)
        judge(case, code, budget, key, read_capped(work / "verdict", 1 << 16),
              read_capped(work / "output"))
    finally:
        shutil.rmtree(work, ignore_errors=True)


# How the harness's child ends (tests/support/runner.cpp, Outcome): only 0 is a pass.
# Exit statuses of a compile killed by SIGKILL or SIGTERM (directly, or as bubblewrap reports its
# child's end, 128 + the signal): nothing the grader does to a compile in time sends them.
KILLED = (-signal.SIGKILL, -signal.SIGTERM, 128 + signal.SIGKILL, 128 + signal.SIGTERM)
# What g++ says when one of its passes (cc1plus, as) was killed by SIGKILL or SIGTERM; it then exits 1.
KILLED_PASS_RE = re.compile(r"(Killed|Terminated) signal terminated program")
EXIT_NOT_GRADED = 3  # `grade`'s status when a submission was not graded (its outputs say why)
NOT_GRADED = 5  # a remote test whose worker could not be started: the grading failed, not the code
OUTCOMES = {1: None, 3: "the test ran but asserted nothing",
            4: "the harness ran other test cases than this one"}


def judge(case: TestCase, code, budget: float, key: str, verdicts: str, output: str) -> None:
    """Sets the case's status from the notary's line carrying this run's key: passed only when the
    process that ran the test exited with status 0 (exactly this test ran, asserted something and
    failed nothing). The test's output only explains a failure."""
    verdict = None
    for line in verdicts.splitlines():
        parts = line.split(" ")
        if len(parts) == 4 and parts[0] == "physlab-verdict" and hmac.compare_digest(parts[1], key) \
                and parts[2] in ("exit", "signal") and parts[3].isdigit():
            verdict = (parts[2], int(parts[3]))
    status, detail, case.checks, case.captured = describe_failure(output)
    if code is None:
        case.status = "timed out"
        case.output = f"killed after {budget:.3g} s" + (f"\n{detail}" if detail else "")
        return
    if verdict == ("exit", 0):
        case.status, case.output = "passed", ""
        return
    if verdict == ("exit", NOT_GRADED):
        case.status, case.output = "not graded", output.strip().splitlines()[-1][:OUTPUT_LIMIT] if output.strip() else ""
        return
    if verdict is not None and verdict[0] == "signal":
        number = verdict[1]
        name = signal.Signals(number).name if number in signal.Signals._value2member_map_ else str(number)
        why = " (output limit exceeded)" if number == signal.SIGXFSZ else ""
        case.status = "crashed"
        case.output = f"crashed ({name}){why}" + (f"\n{detail}" if detail else "")
        return
    if verdict is not None and verdict[1] in OUTCOMES:
        if OUTCOMES[verdict[1]]:
            status, detail = "failed", OUTCOMES[verdict[1]] + (f"\n{detail}" if detail else "")
    elif verdict is not None:
        status, detail = "crashed", f"the test process ended (exit code {verdict[1]}) without a verdict"
    else:
        status, detail = "crashed", "the test process ended without a verdict" + (f"\n{detail}" if detail else "")
    case.status = status
    case.output = detail or output[-OUTPUT_LIMIT:]


# Tests per process in a batch: enough that starting one costs little beside its tests, few
# enough that the batches of a lab spread over every slot.
BATCH_SIZE = 12
# What a batch's records say (tests/support/runner.cpp, batch mode).
RECORD_RE = re.compile(r"^(start|end) ([0-9a-f]+)(?: (\d+) (\d+))?$")
TEST_CASE_RE = re.compile(r"<TestCase\b.*?</TestCase>", re.DOTALL)


def run_cases(sandbox: Sandbox, jobs: list, seed: int, timeout: float, deadline: Deadline,
              scratch: Path, homes: Path, workers: int) -> None:
    """Runs (program, case) pairs, `workers` at a time: a batch program's cases in batches of
    BATCH_SIZE (run_batch()), any other's one process each (run_one())."""
    batches, single = {}, []
    for program, case in jobs:
        if program.batch:
            batches.setdefault(program, []).append(case)
        else:
            single.append((program, case))
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        futures = [pool.submit(run_batch, sandbox, program, cases[i:i + BATCH_SIZE], seed, timeout,
                               deadline, scratch, homes)
                   for program, cases in batches.items() for i in range(0, len(cases), BATCH_SIZE)]
        futures += [pool.submit(run_one, sandbox, program, case, seed, timeout, deadline, scratch, homes)
                    for program, case in single]
        for future in futures:
            future.result()


def run_batch(sandbox: Sandbox, program: Program, cases: list, seed: int, timeout: float,
              deadline: Deadline, scratch: Path, homes: Path) -> None:
    """Runs `cases` of one batch program, as many per process as it can: a process that ends in
    the middle of a test (a crash, a worker that failed it, a time-out) decides that test, and
    a new process runs the ones after it. Each test keeps its own time limit."""
    pending = list(cases)
    while pending:
        if min(timeout, deadline.left()) <= 1.0:
            for case in pending:
                case.status, case.output = "not run", "not run: the grading deadline was reached"
            return
        slot = sandbox.acquire()
        try:
            decided = run_batch_once(sandbox, slot, program, pending, seed, timeout, deadline, scratch, homes)
        except Exception as error:  # an error of the grader's own costs these tests, not the grade
            for case in pending:
                case.status, case.output = "crashed", f"the grader could not run this test: {error}"
            return
        finally:
            sandbox.release(slot)
        pending = [case for case in pending if id(case) not in decided]


def run_batch_once(sandbox: Sandbox, slot: int, program: Program, cases: list, seed: int,
                   timeout: float, deadline: Deadline, scratch: Path, homes: Path) -> set:
    """One process of a batch; returns the ids of the cases it decided (at least one)."""
    by_hex = {case.name.encode("utf-8").hex(): case for case in cases}
    work = Path(tempfile.mkdtemp(dir=scratch, prefix="batch-"))
    decided, current, timed_out = set(), None, False
    started = time.monotonic()  # of the current test, or of the wait for the next one
    try:
        records_read, records_write = os.pipe()
        out_fd = os.open(work / "output", os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
        cmd = [str(program.exe), ",".join(escape_spec(c.name) for c in cases), "-r", "xml", "--rng-seed", str(seed)]
        env = {"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8", "HOME": str(homes / f"home-{slot}"),
               "TMPDIR": str(homes / f"home-{slot}"), "PHYSLAB_RECORDS": str(records_write)}
        if program.worker is not None:
            env.update(sandbox.isolation.environment(program.worker))
        limits = sandbox.limits(TEST_MEMORY, timeout * len(cases), min(OUTPUT_FILE_LIMIT * len(cases), 64 << 20))
        try:
            pinned = sandbox.processor(slot) if program.worker is not None else []
            proc = sandbox.spawn(pinned + limits + cmd, sandbox.ids(slot), cwd=homes / f"home-{slot}", env=env,
                                 stdout=out_fd, stderr=out_fd, pass_fds=(records_write,))
        finally:
            for fd in (records_write, out_fd):
                os.close(fd)
        try:
            pending = b""
            while True:
                now = time.monotonic()
                wait = min(deadline.left(), started + timeout - now)
                if wait <= 0:
                    timed_out = True
                    break
                ready, _, _ = select.select([records_read], [], [], min(wait, 1.0))
                if not ready:
                    continue
                chunk = os.read(records_read, 1 << 16)
                if not chunk:
                    break
                *lines, pending = (pending + chunk).split(b"\n")
                for line in lines:
                    m = RECORD_RE.match(line.decode("ascii", errors="replace"))
                    case = by_hex.get(m.group(2)) if m else None
                    if case is None or id(case) in decided:
                        continue
                    if m.group(1) == "start":
                        current, started = case, time.monotonic()
                    elif case is current:
                        passed, failed = int(m.group(3)), int(m.group(4))
                        case.seconds = time.monotonic() - started
                        case.status = "passed" if failed == 0 and passed > 0 else "failed"
                        case.output = "" if failed or passed else "the test ran but asserted nothing"
                        decided.add(id(case))
                        current, started = None, time.monotonic()
        finally:
            os.close(records_read)
            kill_group(proc.pid)
            code = proc.wait()
            with sandbox.lock:
                sandbox.live.discard(proc.pid)
            sandbox.end(slot)
        output = read_capped(work / "output", 16 << 20)
        explain_batch(cases, decided, output)
        if current is not None:
            current.seconds = time.monotonic() - started
            ended_test(current, None if timed_out else code, timeout, output)
            decided.add(id(current))
        elif not decided:  # the process never started a test: nothing after it would either
            for case in cases:
                ended_test(case, None if timed_out else code, timeout, output)
                decided.add(id(case))
        return decided
    finally:
        shutil.rmtree(work, ignore_errors=True)


def explain_batch(cases: list, decided: set, output: str) -> None:
    """The explanation of each failed test of a batch, from its part of the XML report."""
    failed = {case.name: case for case in cases if id(case) in decided and case.status == "failed"}
    for match in TEST_CASE_RE.finditer(output):
        try:
            name = ET.fromstring(match.group(0)).get("name")
        except ET.ParseError:
            continue
        case = failed.get(name)
        if case is not None:
            status, detail, case.checks, case.captured = describe_failure(f"<Catch>{match.group(0)}</Catch>")
            case.status = status
            case.output = "\n".join(filter(None, [case.output, detail])) or "a check failed"


def ended_test(case: TestCase, code, budget: float, output: str) -> None:
    """A test of a batch that took its process with it: `code` is how the process ended (None:
    killed at the test's time limit); a checker says why a worker failed it on its last line."""
    said = [line[len("physlab: "):] for line in output.splitlines() if line.startswith("physlab: ")]
    why = said[-1][:OUTPUT_LIMIT] if said else ""
    if code is None:
        case.status, case.output = "timed out", f"killed after {budget:.3g} s"
    elif code == NOT_GRADED:
        case.status, case.output = "not graded", why
    elif code < 0:
        number = -code
        name = signal.Signals(number).name if number in signal.Signals._value2member_map_ else str(number)
        extra = " (output limit exceeded)" if number == signal.SIGXFSZ else ""
        case.status, case.output = "crashed", f"crashed ({name}){extra}"
    elif why:
        case.status, case.output = "failed", why
    else:
        case.status, case.output = "crashed", f"the test process ended (exit code {code}) without a verdict"


# ---- reports -----------------------------------------------------------------------------------

SYMBOL = {"passed": "PASS", "failed": "FAIL", "not implemented": "TODO", "timed out": "TIME",
          "crashed": "CRSH", "not compiled": "COMP", "not run": "----", "not graded": "NGRD"}


@functools.lru_cache(maxsize=None)
def handout_sections(stage: str) -> tuple:
    """The lab's handout (path relative to the tree) and its numbered sections {number: title}."""
    found = sorted((ROOT / "docs").glob(f"lab{stage[:2]}_*.md"))
    if not found:
        return None, {}
    text = found[0].read_text(encoding="utf-8", errors="replace")
    sections = re.findall(r"^## (\d+)\. (.+?)(?: \{#\w+\})?$", text, re.MULTILINE)
    return found[0].relative_to(ROOT), {int(number): title for number, title in sections}


def handout_hint(case: TestCase) -> str:
    """Where the handout explains what a failed test checks, and which of the student's files hold
    the functions it grades: from the test's [sec=N] tags."""
    path, titles = handout_sections(case.stage)
    if path is None or not case.sections:
        return ""
    named = [f"{n} ({titles[n]})" if n in titles else str(n) for n in case.sections]
    where = f"section {named[0]}" if len(named) == 1 else \
        "sections " + (", ".join(named) if len(named) <= 2 else ", ".join(map(str, case.sections)))
    files = ", ".join(f"labs/{case.stage}/{u}.cpp" for u in sorted(case.units))
    return f"handout: {path}, {where}; your code: {files}"


# ---- hints: what broke, in the physics' words, never a hidden test's expected value -------------

HINT_FIELD_RE = re.compile(r"\{(\w*)\}")
HINT_NUMBER_RE = re.compile(r"(?<![A-Za-z_])\d")  # a number, not a digit of a name (RK4)


@functools.lru_cache(maxsize=None)
def hint_table(stage: str, hidden: bool) -> dict:
    """test name -> (text, measured) from tests/NN_name/hints.toml (visible tests) or
    tests/hidden/NN_name/hints.toml (hidden tests): a hint is a string, or a table with `text` and
    `measured`, a sentence with {fields} filled from the failure (lhs and rhs, the two sides of the
    first failed comparison; a name the test CAPTUREs), shown only when every field was found."""
    path = ROOT / "tests" / ("hidden" if hidden else "") / stage / "hints.toml"
    if not path.exists():
        return {}
    table = {}
    for name, entry in tomllib.loads(path.read_text(encoding="utf-8")).items():
        if isinstance(entry, str):
            table[name] = (entry, "")
        elif isinstance(entry, dict):
            table[name] = (str(entry.get("text", "")), str(entry.get("measured", "")))
    return table


def hint_problems(stages: list) -> list:
    """Hints that name no test of their lab's file, and hidden tests' hints that could give a value
    away: a number of their own, or the expected side {rhs} of a comparison."""
    problems = []
    for stage in stages:
        for hidden in (False, True):
            where = f"tests/{'hidden/' if hidden else ''}{stage}/hints.toml"
            path = ROOT / where
            if not path.exists():
                continue
            try:
                raw = tomllib.loads(path.read_text(encoding="utf-8"))
            except tomllib.TOMLDecodeError as error:
                problems.append(f"{where}: not valid TOML: {error}")
                continue
            names = {t.name for t in course_file.tree_tests(ROOT, stage) if ("hidden" in t.tags) == hidden}
            for name, entry in raw.items():
                if name not in names:
                    problems.append(f"{where}: no {'hidden' if hidden else 'visible'} graded test named {name!r}")
                if not isinstance(entry, (str, dict)) or (isinstance(entry, dict) and (
                        set(entry) - {"text", "measured"} or not isinstance(entry.get("text", ""), str)
                        or not isinstance(entry.get("measured", ""), str))):
                    problems.append(f"{where}: {name!r}: a hint is text or a table of text and measured")
                    continue
                text, measured = hint_table(stage, hidden).get(name, ("", ""))
                if not text:
                    problems.append(f"{where}: {name!r}: the hint has no text")
                if hidden and HINT_NUMBER_RE.search(HINT_FIELD_RE.sub("", text + measured)):
                    problems.append(f"{where}: {name!r}: a hidden test's hint may hold no number of its "
                                    f"own (it could be the expected value); measured values come from fields")
                if hidden and "{rhs}" in measured:
                    problems.append(f"{where}: {name!r}: {{rhs}} is a hidden test's expected side")
                if "" in HINT_FIELD_RE.findall(text + measured):
                    problems.append(f"{where}: {name!r}: an empty {{}} field")
    return problems


def hint_of(case: TestCase) -> str:
    """The hint of a failed test (the test ran and broke: not unwritten, not uncompiled), or ''."""
    if case.passed or case.status in ("not implemented", "not compiled", "not run"):
        return ""
    text, measured = hint_table(case.stage, "hidden" in case.tags).get(case.name, ("", ""))
    if not text:
        return ""
    fields = HINT_FIELD_RE.findall(measured)
    if measured and all(f in case.captured for f in fields):
        text += " " + HINT_FIELD_RE.sub(lambda m: case.captured[m.group(1)], measured)
    return clean(f"hint: {text}")


WAITS_RE = re.compile(r"not implemented: (\S+) \(see Lab (\d+) handout, sections? (\d+)")


# Statuses of a test that ran and broke: the failures a student can act on, shown in full
BROKE = ("failed", "crashed", "timed out")


def test_line(t: TestCase) -> str:
    """A test's one line: status, points earned/possible (framework tests: -), name, marks."""
    pts = f"{t.points if t.passed else 0:g}/{t.points:g}" if t.graded else "  - "
    extra = " [hidden]" if t.hidden else (" [framework]" if not t.graded else "")
    return f" {SYMBOL[t.status]} {pts:>6}  {t.name}{extra}"


def failure_block(t: TestCase) -> list:
    """A broken test: its line, what its checks saw (the values), its hint, the handout's section."""
    lines = [test_line(t)] + ["            " + l for l in t.output.splitlines()[:12]]
    hint = hint_of(t)
    if hint:
        lines += indented("            ", hint)
    if not t.hidden:
        lines.append("            " + handout_hint(t))
    return lines


def unwritten(t: TestCase) -> tuple:
    """What an unwritten test waits for, as (function, where): its stub's message names the function
    and its handout section, and the lab's stubs name the file of that section."""
    m = WAITS_RE.search(t.output)
    if not m:
        return "a function not written yet", ""
    function, lab, section = m.group(1), m.group(2), int(m.group(3))
    if lab != t.stage[:2].lstrip("0"):
        return function, f"Lab {lab} handout, section {section}"
    unit = section_files(t.stage).get(section)
    return function, f"{unit}.cpp" if unit else f"handout section {section}"


def todo_lines(tests: list) -> list:
    """One line per unwritten function, the function most tests wait for first."""
    groups = {}
    for t in tests:
        groups.setdefault(unwritten(t), []).append(t)
    order = sorted(groups, key=lambda key: -len(groups[key]))  # stable: ties keep the tests' order
    lines = []
    for function, place in order:
        cases = groups[(function, place)]
        points = sum(t.points for t in cases if t.graded)
        count = f"{len(cases)} test{'s' if len(cases) > 1 else ''}"
        worth = f" ({points:g} point{'' if points == 1 else 's'})" if points else ""
        lines.append(f" TODO: {count}{worth} wait{'' if len(cases) > 1 else 's'} for {function}"
                     + (f" ({place})" if place else ""))
    return lines


def grouped_lines(tests: list) -> list:
    """Tests that did not run their checks (not compiled, not run, not graded): one line per status
    and reason."""
    groups = {}
    for t in tests:
        groups.setdefault((t.status, (t.output.strip().splitlines() or [""])[0]), []).append(t)
    lines = []
    for (status, why), cases in groups.items():
        if len(cases) == 1:
            lines.append(test_line(cases[0]) + (f": {why}" if why else ""))
        else:
            lines.append(f" {SYMBOL[status]}: {len(cases)} tests {status}" + (f": {why}" if why else ""))
    return lines


def report(results: list, seed: int, title: str) -> str:
    """The report, per lab: what the student can act on first (tests that broke, with their values,
    hint and handout section; visible before hidden), then one line per unwritten function, the
    passes, and a summary naming the failure to fix first. Deterministic: the tests' own order."""
    out = [title, f"random seed: {seed} (rerun one test: build/test_NN_name_labs \"<test name>\" "
                  f"--rng-seed {seed})", ""]
    total = earned = 0.0
    counts = {"pass": 0, "fail": 0, "todo": 0}
    first = ""
    for r in results:
        graded = [t for t in r.tests if t.graded]
        got = sum(t.points for t in graded if t.passed)
        possible = sum(t.points for t in graded)
        total += possible
        earned += got
        out.append(f"== lab {r.stage}{r.how}: {got:g} / {possible:g} points ==")
        out += ["   note: " + n for n in r.notes]
        if r.compile_error:
            out.append("   did not compile; every test of this lab scores 0. The build says:")
            out += ["   | " + l for l in r.compile_error.strip().splitlines()[-40:]]
        broke = sorted((t for t in r.tests if t.status in BROKE), key=lambda t: t.hidden)
        todo = [t for t in r.tests if t.status == "not implemented"]
        passed = [t for t in r.tests if t.passed]
        other = [t for t in r.tests if not t.passed and t not in broke and t not in todo]
        for t in broke:
            out += failure_block(t)
        out += grouped_lines(other) + todo_lines(todo)
        out += [test_line(t) for t in passed]
        failing = len(broke) + len(other)
        first_fix = broke[0].name if broke else ("the build's first error above" if r.compile_error else "")
        fix = f"; fix first: {first_fix}" if first_fix else ""
        out.append(f" summary: {got:g} / {possible:g} points; {len(passed)} pass, {failing} fail, "
                   f"{len(todo)} todo{fix}")
        counts["pass"] += len(passed)
        counts["fail"] += failing
        counts["todo"] += len(todo)
        first = first or (f"lab {r.stage}: {first_fix}" if first_fix else "")
        out.append("")
    fix = f"; fix first: {first}" if first else ""
    out.append(f"TOTAL: {earned:g} / {total:g} points; {counts['pass']} pass, {counts['fail']} fail, "
               f"{counts['todo']} todo{fix}")
    return clean("\n".join(out))


def gradescope_json(results: list, elapsed: float) -> dict:
    tests = []
    for lab_index, r in enumerate(results, start=1):
        for i, t in enumerate((t for t in r.tests if t.graded), start=1):
            tests.append({
                "name": clean(f"lab {r.stage}: {t.name}"),
                "number": f"{lab_index}.{i}",
                "score": t.points if t.passed else 0.0,
                "max_score": t.points,
                "status": "passed" if t.passed else "failed",
                "output": clean(t.status if t.passed else "\n".join(
                    [t.status] + ([hint_of(t)] if hint_of(t) else []) + [t.output]))[:OUTPUT_LIMIT],
                "visibility": "after_published" if t.hidden else "visible",
                "tags": t.tags,
                "extra_data": {"seconds": round(t.seconds, 3)},  # where a grade's time goes
            })
    notes = [clean(f"lab {r.stage}: {n}") for r in results for n in r.notes]
    return {
        # Points are multiples of 1e-4 (a course's rescaling): sums rounded there, not 200.00000000003
        "score": round(sum(t["score"] for t in tests), 4),
        "max_score": round(sum(t["max_score"] for t in tests), 4),
        "execution_time": round(elapsed, 2),
        "output": "\n".join(["Per-test results below; the full report is report.txt."] + notes),
        "tests": tests,
    }


def write_atomically(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{threading.get_ident()}.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def write_outputs(out: Path, text: str, data: dict) -> None:
    out.mkdir(parents=True, exist_ok=True)
    write_atomically(out / "report.txt", text + "\n")
    write_atomically(out / "results.json", json.dumps(data, indent=2))


def failure_outputs(out: Path, title: str, why: str, elapsed: float) -> dict:
    text = clean(f"{title}\n\nGRADING FAILED: {why}\nscore: 0")
    data = {"score": 0.0, "max_score": 0.0, "execution_time": round(elapsed, 2),
            "output": clean(f"Grading failed: {why}"), "tests": []}
    write_outputs(out, text, data)
    return data


def not_graded_outputs(out: Path, title: str, why: str, elapsed: float) -> dict:
    """report.txt and results.json of a submission the grading failed on (GradingFailure): no
    score; results.json says "not graded" and why (extra_data.not_graded)."""
    text = clean(f"{title}\n\nNOT GRADED: {why}\nThe grading failed, not your code: it will be graded again.")
    data = {"score": 0.0, "max_score": 0.0, "execution_time": round(elapsed, 2),
            "output": clean(f"Not graded: {why}. The grading failed, not your code: it will be graded again."),
            "tests": [], "extra_data": {"not_graded": clean(why)}}
    write_outputs(out, text, data)
    return data


def not_graded(data: dict) -> str:
    """Why a submission was not graded ("" when it was)."""
    return data.get("extra_data", {}).get("not_graded", "")


def summary_line(results: list) -> tuple:
    cases = [t for r in results for t in r.tests]
    passed = sum(t.passed for t in cases)
    return passed, len(cases) - passed


# ---- ./physlab test: the tree's own executables ------------------------------------------------

def executables(build: Path, stage: str, variant: str) -> list:
    suffix = "_labs" if variant == "labs" else ""
    found = [build / f"test_{stage}{suffix}"]
    if (build / f"test_{stage}_hidden{suffix}").exists():
        found.append(build / f"test_{stage}_hidden{suffix}")
    return found


def own_file_executable(exe: Path, case: TestCase) -> Path:
    """Where a test of one lab file runs: test_NN_labs_<file>, that student file with the
    reference of the lab's others (built where the reference is at hand), else `exe`."""
    mixed = exe.with_name(f"{exe.name}_{case.unit}")
    return mixed if exe.name.endswith("_labs") and case.unit and mixed.exists() else exe


def course_points(stage: str, cases: list) -> list:
    """In a student copy published for a course (tools/course-points.json): the course's tests of
    the lab at the course's points; elsewhere the cases as they are."""
    table = ROOT / course_file.POINTS_FILE
    if not table.exists():
        return cases
    points = json.loads(table.read_text(encoding="utf-8")).get(stage, {})
    kept = [c for c in cases if c.name in points or not c.graded]
    for case in kept:
        if case.name in points:
            case.course_points = float(points[case.name])
    return kept


def remote_pairs(build: Path, stages: list, sandbox: Sandbox, scratch: Path, results: list) -> list:
    """Jobs that run each remote stage's checkers with the reference's worker, sandboxed as in a
    grade: the tests must pass through the wire as they do in one process. Their results are
    added to `results` as "NN_name, checker and worker"."""
    if not (build / "grading" / "toolchain.json").exists():
        return []
    kit = Kit(build)
    jobs = []
    for stage in stages:
        spec = kit.stages.get(stage, {})
        if "checker" not in spec:
            continue
        if sandbox.isolation is None:
            sandbox.isolation = Isolation(kit, scratch, sandbox)
        result = StageResult(stage, how=", checker and worker")
        for key in ("checker", "checker_hidden"):
            if spec.get(key) and not Path(spec[key]).exists():
                result.compile_error += f"{Path(spec[key]).name} was not built\n"
            elif spec.get(key):  # framework tests grade nothing and run in the ordinary executables
                cases = [c for c in list_tests(Path(spec[key]), stage) if c.graded]
                result.tests += cases
                jobs += [(Program(Path(spec[key]), Path(spec["reference_worker"]), batch=True), c) for c in cases]
        results.append(result)
    return jobs


def cmd_run(args) -> int:
    """Run already built tests; print the report; optionally write results.json."""
    start = time.monotonic()
    build = Path(args.build).resolve()
    stages = select_stages(discover_stages(ROOT), args.labs)
    sandbox = Sandbox(args.jobs, switch_user=False)  # the tree's own code: run it as we are
    if args.timeout is None:
        args.timeout = course_file.DEFAULT_LIMITS["test"]
    scratch = Path(tempfile.mkdtemp(prefix="physlab-test-"))
    results, jobs = [], []
    kit = None
    if args.variant == "labs" and args.expect != "fail" and (build / "grading" / "toolchain.json").exists():
        kit = Kit(build)
    for stage in stages:
        result = StageResult(stage)
        result.notes += refusals_ahead(kit, stage)
        for exe in executables(build, stage, args.variant):
            if not exe.exists():
                result.compile_error += f"{exe.name} was not built\n"
                continue
            cases = course_points(stage, list_tests(exe, stage))
            result.tests += cases
            jobs += [(Program(own_file_executable(exe, c), batch=True), c) for c in cases]
        results.append(result)
    if args.variant == "solutions":
        jobs += remote_pairs(build, stages, sandbox, scratch, results)
    if args.variant == "solutions" and (build / "test_common").exists():
        common = StageResult("common", list_tests(build / "test_common", "common"))
        jobs += [(Program(build / "test_common", batch=True), c) for c in common.tests]
        results.append(common)
    for slot in sandbox.slots:
        (scratch / f"home-{slot}").mkdir()
    try:
        run_cases(sandbox, jobs, args.seed, args.timeout, Deadline(None), scratch, scratch, args.jobs)
    finally:
        sandbox.finish()
        shutil.rmtree(scratch, ignore_errors=True)
    title = f"PhysLab tests against {args.variant}/"
    text = report(results, args.seed, title)
    mistagged = [f"TAG: {p}" for p in tag_problems(results)] + [f"HINT: {p}" for p in hint_problems(stages)] \
        if args.variant == "solutions" else []
    if args.out:
        write_outputs(Path(args.out), text, gradescope_json(results, time.monotonic() - start))
    if args.expect == "fail":
        passed, failed = stub_check(results)
    else:
        print(text)
        passed, failed = summary_line(results)
        print(f"\n{passed} passed, {failed} failed")
    for problem in mistagged:
        print(f"  {problem}")
    failed += len(mistagged)
    if args.summary:  # the graded tests once: a checker's second run of a lab's tests is not counted again
        graded = [t for r in results if not r.how for t in r.tests if t.graded]
        graded_passed = sum(t.passed for t in graded)
        Path(args.summary).write_text(f"{passed} {failed} {len(graded)} {graded_passed}\n")
    return 0 if failed == 0 else 1


def stub_check(results: list) -> tuple:
    """Every graded test must fail on the stubs, and fail as 'not implemented'. Returns
    (tests that behaved so, tests that did not)."""
    graded = [t for r in results for t in r.tests if t.graded]
    passing = [t for t in graded if t.passed]
    bad = [t for t in graded if not t.passed and t.status != "not implemented"]
    print(f"stub check: {len(graded)} graded tests on labs/ stubs: "
          f"{len(graded) - len(passing)} fail, {len(passing)} pass")
    for t in passing:
        print(f"  PASSES ON A STUB (a test that cannot fail): lab {t.stage}: {t.name}")
    for t in bad:
        print(f"  fails as '{t.status}' instead of 'not implemented': lab {t.stage}: {t.name}")
    wrong = len(passing) + len(bad)
    return len(graded) - wrong, wrong


# ---- grading a submission: compile apart, check, link with the instructor's objects ------------

class Kit:
    """The instructor's build as the grader uses it (written by cmake/PhysLab.cmake): the compiler
    and flags, and per stage the test, hidden-test and framework objects and earlier stages'
    reference libraries. None of it is ever shown to student code."""

    def require_notary(self) -> None:
        """Grading trusts only the notary's verdict: refuse a build whose runner has none."""
        if self.toolchain.get("notary") is not True:
            raise RuntimeError("this build's test runner has no notary (the portable runner, built on "
                               "a non-ELF system or with -DPHYSLAB_PORTABLE_RUNNER=ON): its verdicts come "
                               "from the process that runs student code; grade with a Linux build")

    def __init__(self, build: Path):
        folder = build / "grading"
        if not (folder / "toolchain.json").exists():
            raise RuntimeError(f"{folder} is missing: build the tests first (./physlab build)")
        self.build = build
        self.toolchain = json.loads((folder / "toolchain.json").read_text())
        self.stages = {p.stem: json.loads(p.read_text()) for p in folder.glob("[0-9][0-9]_*.json")}
        self.cache = folder / "cache"
        self.cache.mkdir(mode=0o700, exist_ok=True)
        headers = sorted((ROOT / "common" / "include").rglob("*"))
        digest = hashlib.sha256(json.dumps(self.toolchain, sort_keys=True).encode())
        for h in headers:
            if h.is_file():
                digest.update(str(h.relative_to(ROOT)).encode() + h.read_bytes())
        self.digest = digest.hexdigest()
        self._exports = None
        self._libm = None
        self._api = {}
        self._symbols = {}
        self._precompiled = {}
        self._precompiled_lock = threading.Lock()

    def compiler(self, include: Path) -> list:
        """The compiler with the reference's flags and the framework's and Eigen's headers."""
        cmd = [self.toolchain["compiler"]] + self.toolchain["flags"].split() + ["-I", str(include)]
        for d in self.toolchain["system_include"]:
            cmd += ["-isystem", d]
        return cmd

    def compile_command(self, include: Path, source: Path, obj: Path, header: Path = None) -> list:
        """`header`: the stage's precompiled framework headers (precompiled()), included first."""
        return self.compiler(include) + self.toolchain["warnings"].split() + (
            ["-include", str(header)] if header else []) + [
            "-MD", "-MF", str(obj.with_suffix(".d")), "-c", str(source), "-o", str(obj)]

    def precompiled(self, stage: str):
        """The framework headers the stage's stubs include, precompiled with the flags a submitted
        file compiles with (GCC's .gch): a file then skips parsing Eigen and the framework, a
        third of its compile. They hold only the framework's public headers, and live where the
        sandbox's identities can read them (PRECOMPILED, not the instructor's tree, which is
        often closed to other users). Built at the first grade that needs them; None where the
        compiler would not use them, and the files then compile as they are."""
        with self._precompiled_lock:
            if stage not in self._precompiled:
                self._precompiled[stage] = self._precompile(stage)
            header = self._precompiled[stage]
        if header:
            os.utime(header.parent)  # in use: prune_precompiled() spares it
        return header

    def _precompile(self, stage: str):
        includes = sorted({i for f in (ROOT / "labs" / stage).glob("*.cpp")
                           for i in re.findall(r'^#include\s+"(physlab/[^"]+)"', f.read_text(), re.MULTILINE)})
        if not includes:
            return None
        text = ("// The framework headers of the stage's stubs, precompiled for grading (tools/grader.py)\n"
                + "".join(f'#include "{i}"\n' for i in includes))
        folder = precompiled_folder()
        if folder is None:
            return None
        final = folder / f"{stage}-{hashlib.sha256((self.digest + text).encode()).hexdigest()[:16]}"
        header = final / "framework.hpp"
        if (final / "framework.hpp.gch").exists():
            return header
        prune_precompiled(folder)
        work = Path(tempfile.mkdtemp(dir=folder, prefix=".building-"))
        try:
            (work / "framework.hpp").write_text(text)
            base = self.compiler(ROOT / "common" / "include") + self.toolchain["warnings"].split()
            built = subprocess.run(base + ["-x", "c++-header", str(work / "framework.hpp"), "-o",
                                           str(work / "framework.hpp.gch")], capture_output=True, timeout=300)
            if built.returncode != 0:
                return None
            # Only a header the compiler then reads from its .gch ("!" in -H's list) saves anything
            probe = subprocess.run(base + ["-include", str(work / "framework.hpp"), "-H", "-fsyntax-only",
                                           "-x", "c++", "/dev/null"], capture_output=True, text=True, timeout=120)
            if f"! {work / 'framework.hpp.gch'}" not in probe.stderr:
                return None
            for path in (work, work / "framework.hpp", work / "framework.hpp.gch"):
                os.chmod(path, 0o755 if path.is_dir() else 0o644)
            try:
                os.rename(work, final)  # whole or not at all: another grade may be building it too
            except OSError:
                pass  # that grade's is in place
            return header if (final / "framework.hpp.gch").exists() else None
        except (OSError, subprocess.TimeoutExpired):
            return None
        finally:
            shutil.rmtree(work, ignore_errors=True)

    def preprocess_command(self, include: Path, source: Path, out: Path) -> list:
        return self.compiler(include) + ["-E", str(source), "-o", str(out)]

    def link_command(self, stage: str, tests: str, student: list, exe: Path, reference=()) -> list:
        spec = self.stages[stage]
        # The instructor's objects come first and its libraries whole: wherever the student's
        # objects and the instructor's define the same inline function, the instructor's is used.
        cmd = [self.toolchain["compiler"]] + self.toolchain["flags"].split() + ["-o", str(exe)]
        cmd += self.toolchain["main"] + spec[tests] + spec["framework"] + list(reference)
        cmd += ["-Wl,--whole-archive"] + spec["depends"] + [self.toolchain["common"]]
        return cmd + ["-Wl,--no-whole-archive"] + [str(o) for o in student] + self.toolchain["libraries"]

    def worker_command(self, stage: str, student: list, exe: Path, reference=()) -> list:
        """Links a worker (a remote stage): the server's table, the submitted objects, the
        reference's objects of the stage's other files, the framework; statically."""
        spec = self.stages[stage]
        cmd = [self.toolchain["compiler"]] + self.toolchain["flags"].split() + ["-static", "-o", str(exe)]
        cmd += spec["server"] + [str(o) for o in student] + list(reference) + spec["framework"]
        cmd += ["-Wl,--start-group"] + spec["depends"] + [self.toolchain["common"], "-Wl,--end-group"]
        return cmd + self.toolchain["worker_libraries"]

    def symbols(self, path: str) -> tuple:
        """(defined: name -> nm type, undefined names) of an object or archive's global symbols."""
        if path not in self._symbols:
            listing = subprocess.run(["nm", "-P", "-g", path], capture_output=True, timeout=60,
                                     text=True, errors="replace").stdout
            defined, undefined = {}, set()
            for line in listing.splitlines():
                parts = line.split()
                if len(parts) < 2 or line.endswith(":"):
                    continue
                if parts[1] in "Uwv":
                    undefined.add(parts[0])
                else:
                    defined[parts[0]] = parts[1]
            self._symbols[path] = (defined, undefined)
        return self._symbols[path]

    def defined_by(self, paths: list) -> set:
        found = set()
        for p in paths:
            if not p.startswith("-") and os.path.exists(p):
                found |= set(self.symbols(p)[0])
        return found

    def libm(self) -> set:
        """The functions of the maths library (libm), every one of which a lab file may call."""
        if self._libm is None:
            path = subprocess.run([self.toolchain["compiler"], "-print-file-name=libm.so.6"],
                                  capture_output=True, text=True).stdout.strip()
            listing = subprocess.run(["nm", "-D", "--defined-only", path], capture_output=True,
                                     text=True, errors="replace").stdout
            self._libm = {l.split()[-1].split("@")[0] for l in listing.splitlines() if l.split()}
        return self._libm

    def framework_api(self, stage: str) -> set:
        """What a lab file of `stage` may call in the framework and earlier labs: every global
        symbol of the stage's library side, less those of object files that reach the system
        (plotting and demo output), directly or through another such file; no lab file needs them."""
        if stage not in self._api:
            spec = self.stages[stage]
            members = {}  # (library, member) -> (defined, imported)
            for path in spec["framework"] + spec["depends"] + [self.toolchain["common"]]:
                if path.startswith("-") or not os.path.exists(path):
                    continue
                listing = subprocess.run(["nm", "-P", "-A", "-g", path], capture_output=True,
                                         timeout=60, text=True, errors="replace").stdout
                for line in listing.splitlines():
                    member, _, rest = line.rpartition(": ")
                    parts = rest.split()
                    if len(parts) >= 2:
                        defined, imported = members.setdefault(member, (set(), set()))
                        (imported if parts[1] in "Uwv" else defined).add(parts[0])
            inside = set().union(*(d for d, _ in members.values()))
            outside = demangle(set().union(*(i for _, i in members.values())) - inside
                               - ALLOWED_C - self.libm())
            system = {n for n, d in outside.items() if not PHYSLAB_NAME.match(d)
                      and (not ALLOWED_STD.match(d) or FORBIDDEN_STD.match(d))}
            reaching, refused, allowed = set(), set(system), set(inside)
            while True:
                more = {m for m, (_, i) in members.items() if m not in reaching and i & refused}
                if not more:
                    break
                reaching |= more
                allowed = set().union(*(d for m, (d, _) in members.items() if m not in reaching))
                refused = system | (inside - allowed)
            self._api[stage] = allowed
        return self._api[stage]

    def exports(self) -> set:
        """Symbols the shared libraries of the link define: a student's weak definition of one
        would replace it for the whole executable (the harness included), so none is allowed."""
        if self._exports is None:
            self._exports = set()
            libs = [l for l in self.toolchain["libraries"] if ".so" in l]
            for name in SHARED_LIBRARIES:
                libs.append(subprocess.run([self.toolchain["compiler"], f"-print-file-name={name}"],
                                           capture_output=True, text=True).stdout.strip())
            for lib in libs:
                listing = subprocess.run(["nm", "-D", "--defined-only", lib], capture_output=True,
                                         text=True, errors="replace").stdout
                self._exports |= {l.split()[-1].split("@")[0] for l in listing.splitlines() if l.split()}
        return self._exports


LINE_MARKER_RE = re.compile(r'^# (\d+) "((?:[^"\\]|\\.)*)"')
LITERAL_RE = re.compile(r'R"([^ ()\\\t\n]{0,16})\((?:.|\n)*?\)\1"|"(?:[^"\\\n]|\\.)*"|\'(?:[^\'\\\n]|\\.)*\'')


def inline_assembly(preprocessed: Path, source: Path) -> str:
    """Where the student's own lines use inline assembly after preprocessing (so a macro cannot
    hide it), e.g. "asm at line 12"; "" when they do not. Lines of headers are not the student's:
    the tokens a student's macro produces are attributed to the line that uses it."""
    try:
        text = read_capped(preprocessed, COMPILE_OUTPUT)
    except OSError:
        return "its preprocessed source could not be checked"
    own, line, found, lines = False, 0, [], []
    for raw in text.splitlines():
        m = LINE_MARKER_RE.match(raw)
        if m:
            line, own = int(m.group(1)), m.group(2) == str(source)
            continue
        if own:
            lines.append((line, raw))
        line += 1
    code = LITERAL_RE.sub('""', "\n".join(raw for _, raw in lines))
    for number, kept in zip((n for n, _ in lines), code.split("\n")):
        m = ASM_KEYWORD_RE.search(kept)
        if m:
            found.append(f"{m.group(1)} at line {number}")
    return ", ".join(found[:3])


def kernel_entries(obj: Path) -> list:
    """Instructions of the object that enter the kernel (syscall, sysenter, int $n)."""
    listing = subprocess.run(["objdump", "-d", "--no-show-raw-insn", str(obj)], capture_output=True,
                             text=True, errors="replace", timeout=60).stdout
    return sorted({" ".join(m.group(1).split()) for m in KERNEL_ENTRY_RE.finditer(listing)})


def why_refused(name: str) -> str:
    if PHYSLAB_NAME.match(name):
        return "it is framework code that writes files or runs programs (plots, demo output), which no lab file needs"
    for pattern, why in FORBIDDEN_WHY:
        if pattern.search(name):
            return why
    return "it is not among the functions a lab file may use (see the Grading page)"


def sections_of(obj: Path) -> list:
    listing = subprocess.run(["readelf", "-S", "-W", str(obj)], capture_output=True, text=True,
                             errors="replace", timeout=60).stdout
    names = []
    for line in listing.splitlines():
        m = re.match(r"^\s*\[\s*(\d+)\]\s+(\S+)", line)
        if m and m.group(1) != "0":
            names.append(m.group(2))
    return names


def demangle(names) -> dict:
    names = sorted(names)
    if not names:
        return {}
    out = subprocess.run(["c++filt"], input="\n".join(names), capture_output=True, text=True).stdout
    return dict(zip(names, out.splitlines()))


def check_object(kit: Kit, stage: str, obj: Path, stub_defined: set, own_defined: set) -> list:
    """Why a student's object may not be linked (empty when it may): what it defines must be what
    the stub defines, or internal, or a weak copy of an inline function that replaces nothing.
    In a remote stage the object is linked into a worker alone, which can reach nothing but its
    pipes whatever it holds: only the first rule is kept, so that a helper's name cannot collide
    with the reference's (sandbox_notes() says what the sandbox will refuse)."""
    defined, undefined = kit.symbols(str(obj))
    if "checker" in kit.stages[stage]:
        strong = [s for s, t in defined.items() if t not in "WVuvw" and s not in stub_defined]
        names = demangle(strong)
        return [f"defines {names[s]}, which the stub does not: make helpers static or put them "
                f"in an anonymous namespace" for s in strong]
    problems = [f"section {s} is not allowed in a lab file" for s in sections_of(obj)
                if not ALLOWED_SECTIONS.match(s)]
    spec = kit.stages[stage]
    test_side = kit.defined_by(kit.toolchain["main"] + spec["tests"] + spec["hidden"])
    library_side = kit.defined_by(spec["framework"] + spec["depends"] + [kit.toolchain["common"]])
    exports = kit.exports()
    strong = [s for s, t in defined.items() if t not in "WVu" and s not in stub_defined]
    weak = [s for s, t in defined.items() if t in "WVu" and s in exports and s not in stub_defined]
    # A weak copy of a standard-library template the headers instantiate ("text" + std::string(...)
    # emits std::operator+) is ordinary C++: the notary calls no C++ library function
    weak = [s for s, d in demangle(weak).items() if not STD_INSTANCE.match(d)]
    reached = [s for s in undefined if s in test_side and s not in library_side
               and s not in own_defined and s not in exports]
    names = demangle(strong + weak + reached)
    problems += [f"defines {names[s]}, which the stub does not: make helpers static or put them "
                 f"in an anonymous namespace" for s in strong]
    problems += [f"defines {names[s]}, a library function" for s in weak]
    problems += [f"uses {names[s]}, which belongs to the test harness" for s in reached]
    return problems + import_problems(kit, stage, obj, own_defined | set(reached))


def import_problems(kit: Kit, stage: str, obj: Path, own_defined: set) -> list:
    """What the object uses that a lab file may not (the allow-list on the Grading page), and the
    instructions in it that enter the kernel; each with its reason."""
    _, undefined = kit.symbols(str(obj))
    spec = kit.stages[stage]
    library_side = kit.defined_by(spec["framework"] + spec["depends"] + [kit.toolchain["common"]])
    framework, libm = kit.framework_api(stage), kit.libm()
    imports = demangle(s for s in undefined if s not in own_defined and s not in framework
                       and s not in libm and s not in ALLOWED_C)
    refused = sorted(d for n, d in imports.items() if (PHYSLAB_NAME.match(d) and n in library_side) or
                     (not PHYSLAB_NAME.match(d) and (not ALLOWED_STD.match(d) or FORBIDDEN_STD.match(d))))
    problems = [f"uses {n}: {why_refused(n)}" for n in refused]
    return problems + [f"contains the instruction '{i}', which enters the kernel" for i in kernel_entries(obj)]


def sandbox_notes(kit: Kit, stage: str, obj: Path, own_defined: set) -> list:
    """In a remote stage: what the object calls that its sandbox refuses (files, processes, the
    network, the kernel directly), as notes; such a call fails when the code runs."""
    return [f"{p}; in the grader's sandbox that call fails" for p in import_problems(kit, stage, obj, own_defined)]


def refusals_ahead(kit: Kit, stage: str) -> list:
    """For a student's own build: the grader's import refusals of the lab files as compiled here,
    so a student learns of them before submitting rather than from a grade of 0."""
    if kit is None or stage not in kit.stages:
        return []
    build = kit.build
    objects = sorted((build / "CMakeFiles" / f"physlab_{stage}_labs.dir").rglob("*.o"))
    own = kit.defined_by([str(o) for o in objects])
    notes = []
    for obj in objects:
        if "checker" in kit.stages[stage]:
            notes += [f"{obj.name.removesuffix('.o')}: {p}" for p in sandbox_notes(kit, stage, obj, own)]
        else:
            notes += [f"the grader will refuse {obj.name.removesuffix('.o')}: {p}"
                      for p in import_problems(kit, stage, obj, own)]
    return notes


def filter_diagnostics(text: str, allowed: list, shown: dict) -> str:
    """Compiler output with the diagnostics located outside `allowed` folders left out, and the
    sandbox's paths shown as the student's (shown: real prefix -> displayed prefix)."""
    header = re.compile(r"^(?:In file included from |\s+from )?(/[^:]+):")
    kept, keep = [], True
    for line in text.splitlines():
        m = header.match(line)
        if m:
            real = os.path.realpath(m.group(1))
            keep = any(real == a or real.startswith(a.rstrip("/") + "/") for a in allowed)
            if not keep:
                kept.append("(a diagnostic in a file outside the submission and the framework is not shown)")
        if keep:
            for real, display in shown.items():
                line = line.replace(real, display)
            kept.append(line)
    return "\n".join(kept)


def dependencies(dfile: Path) -> list:
    try:
        text = dfile.read_text(errors="replace").replace("\\\n", " ")
    except OSError:
        return []
    return text.split(":", 1)[1].split() if ":" in text else []


@dataclass
class Compiled:
    obj: Path = None
    log: str = ""
    error: str = ""


class Builder:
    """Compiles lab files in the sandbox and links graded executables in the private folder."""

    def __init__(self, kit: Kit, sandbox: Sandbox, private: Path, shared: Path, deadline: Deadline,
                 compile_timeout: float):
        self.kit, self.sandbox, self.private, self.shared = kit, sandbox, private, shared
        self.deadline, self.compile_timeout = deadline, compile_timeout
        self.include = shared / "include"
        self.system = [os.path.realpath(d) for d in kit.toolchain["system_include"]]
        self.system += ["/usr/include", "/usr/lib/gcc", "/usr/local/include"]

    def compile(self, stage: str, name: str, source: bytes, prefix: str = "") -> Compiled:
        key = hashlib.sha256(self.kit.digest.encode() + stage.encode() + name.encode() + source).hexdigest()
        cached, cached_log = self.kit.cache / f"{key}.o", self.kit.cache / f"{key}.log"
        target = self.private / stage / (prefix + name.replace(".cpp", ".o"))
        target.parent.mkdir(parents=True, exist_ok=True)
        if cached.exists() and cached_log.exists():
            shutil.copyfile(cached, target)
            return Compiled(target, cached_log.read_text())
        budget = min(self.compile_timeout, self.deadline.left())
        if budget <= 1.0:
            return Compiled(error=f"{name}: not compiled: the grading deadline was reached")
        slot = self.sandbox.acquire()
        work = Path(tempfile.mkdtemp(dir=self.shared, prefix="compile-"))
        try:
            (work / name).write_bytes(source)
            ids = self.sandbox.ids(slot)
            if ids:
                os.chown(work, *ids)
            os.chmod(work, 0o700)
            log_path = self.private / stage / f"{prefix}{name}.log"
            log_fd = os.open(log_path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
            obj = work / name.replace(".cpp", ".o")
            preprocessed = work / name.replace(".cpp", ".ii")
            # Inline assembly is refused where the file's code runs beside the tests; a worker's
            # sandbox holds whatever instructions it runs, so a remote lab's file skips the scan
            remote = "checker" in self.kit.stages.get(stage, {})
            isolation = self.sandbox.isolation
            header = self.kit.precompiled(stage)
            jail = (lambda cmd: isolation.compiling(cmd, work, self.include, header and header.parent)) \
                if isolation else (lambda cmd: cmd)
            try:
                if not remote:
                    self.sandbox.run(jail(self.kit.preprocess_command(self.include, work / name, preprocessed)),
                                     slot=slot, cwd=work, timeout=budget, memory=COMPILE_MEMORY,
                                     stdout=subprocess.DEVNULL, fsize=COMPILE_OUTPUT)
                    budget = min(self.compile_timeout, self.deadline.left())
                code, _ = self.sandbox.run(jail(self.kit.compile_command(self.include, work / name, obj, header)),
                                           slot=slot, cwd=work, timeout=budget,
                                           memory=COMPILE_MEMORY, stdout=log_fd, fsize=COMPILE_OUTPUT)
            finally:
                os.close(log_fd)
            outside = [d for d in dependencies(obj.with_suffix(".d"))
                       if not self.allowed(os.path.realpath(work / d))]
            if outside:
                return Compiled(error=f"{name} includes files outside the submission and the "
                                      f"framework headers: {', '.join(sorted(set(outside))[:5])}")
            log = filter_diagnostics(read_capped(log_path, 1 << 20),
                                     [str(work), str(self.include)] + self.system,
                                     {f"{work}/": f"labs/{stage}/", f"{self.include}/": "common/include/"})
            if code is None:
                return Compiled(error=f"{name}: compilation stopped after {budget:.0f} s")
            if code in KILLED or KILLED_PASS_RE.search(log):  # not our time limit (code None) nor a limit of the file's making
                raise GradingFailure(f"the compiler of {name} was killed from outside (status {code})")
            if code != 0 or not obj.exists():
                return Compiled(log=log, error=f"{name} did not compile")
            assembly = "" if remote else inline_assembly(preprocessed, work / name)
            if assembly:
                return Compiled(error=f"{name}: refused: inline assembly ({assembly}); lab code "
                                      f"is C++ only")
            shutil.copyfile(obj, target)
            # Atomically: another submission graded at once may read the same entry
            partial = cached.with_name(f".{key}.{threading.get_ident()}.tmp")
            shutil.copyfile(target, partial)
            os.replace(partial, cached)
            write_atomically(cached_log, log)
            return Compiled(target, log)
        finally:
            shutil.rmtree(work, ignore_errors=True)
            self.sandbox.release(slot)

    def allowed(self, real: str) -> bool:
        roots = [str(self.shared), os.path.realpath(PRECOMPILED)] + self.system
        return any(real == r or real.startswith(r.rstrip("/") + "/") for r in roots)

    def link(self, stage: str, tests: str, objects: list, exe: Path, reference: list = ()) -> str:
        """Links the student's `objects` (and the instructor's `reference` objects of the stage's
        other files) with the `tests` ("tests", "hidden") or, for "worker", into the worker of a
        remote stage; returns '' or an explanation naming the missing or doubly defined functions."""
        budget = min(120.0, self.deadline.left())
        command = (self.kit.worker_command(stage, objects, exe, reference) if tests == "worker"
                   else self.kit.link_command(stage, tests, objects, exe, reference))
        try:
            proc = subprocess.run(command, capture_output=True,
                                  text=True, errors="replace", timeout=max(budget, 1.0))
        except subprocess.TimeoutExpired:
            return "linking stopped at the grading deadline"
        if proc.returncode == 0:
            return ""
        text = proc.stdout + proc.stderr
        missing = sorted(set(re.findall(r"undefined reference to [`']([^']+)'", text)))
        twice = sorted(set(re.findall(r"multiple definition of [`']([^']+)'", text)))
        lines = [f"missing function: {m} (no definition in your files; is it written, with the "
                 f"header's exact signature?)" for m in missing]
        lines += [f"defined twice: {t}" for t in twice]
        return "\n".join(lines) or "the lab did not link"


# Where the precompiled framework headers live (Kit.precompiled()): one folder per user of the
# grader, readable by every user, writable by that user alone.
PRECOMPILED = Path("/var/tmp" if os.path.isdir("/var/tmp") else tempfile.gettempdir()) / f"physlab-pch-{os.geteuid()}"
UNUSED_PRECOMPILED = 2 * 86400  # seconds unused after which another build's headers are removed


def precompiled_folder():
    """PRECOMPILED, made if needed; None unless it is ours and no one else may write to it (a
    header planted there would compile into every submission)."""
    try:
        PRECOMPILED.mkdir(mode=0o755, exist_ok=True)
        info = os.lstat(PRECOMPILED)
    except OSError:
        return None
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.geteuid() or info.st_mode & 0o022:
        return None
    return PRECOMPILED


def prune_precompiled(folder: Path) -> None:
    """Removes the headers of builds no grade has used for UNUSED_PRECOMPILED (each is ~120 MB)."""
    for entry in folder.iterdir():
        try:
            if time.time() - entry.stat().st_mtime > UNUSED_PRECOMPILED:
                shutil.rmtree(entry, ignore_errors=True)
        except OSError:
            pass


def open_folder(root: Path, parts: tuple) -> int:
    """A descriptor of the folder root/parts, reached without following any link below root;
    raises LinkError naming the first component that is a link, OSError when it is missing."""
    fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY)
    try:
        for depth, part in enumerate(parts):
            shown = "/".join(parts[:depth + 1])
            if stat.S_ISLNK(os.stat(part, dir_fd=fd, follow_symlinks=False).st_mode):
                raise LinkError(shown)
            inner = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=fd)
            os.close(fd)
            fd = inner
        return fd
    except BaseException:
        os.close(fd)
        raise


class LinkError(OSError):
    """A component of a submitted path is a symbolic link; its `path` is shown in the report."""

    def __init__(self, path: str):
        super().__init__(f"{path} is a symbolic link")
        self.path = path


def read_regular(folder: int, name: str, shown: str) -> bytes:
    """The bytes of the regular file `name` in the open folder, never through a link; raises
    OSError (LinkError for a link) with the reason the file cannot be used."""
    if stat.S_ISLNK(os.stat(name, dir_fd=folder, follow_symlinks=False).st_mode):
        raise LinkError(shown)
    fd = os.open(name, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK, dir_fd=folder)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise OSError(f"{shown} is not a regular file")
        if info.st_size > SOURCE_LIMIT:
            raise OSError(f"{shown} is larger than {SOURCE_LIMIT >> 10} KiB")
        with os.fdopen(os.dup(fd), "rb") as f:
            return f.read(SOURCE_LIMIT)
    finally:
        os.close(fd)


@dataclass
class Submitted:
    """Where a submission's lab folders are: root/parts/NN_name (parts is ("labs",) or ())."""
    root: Path
    parts: tuple


def submitted_sources(labs: Submitted, stage: str, notes: list) -> dict:
    """name -> bytes of the lab files to grade: the submission's regular files named as the stub's
    files of the stage, each reached without following a link at any level below the submission's
    root; the stub where the submission has none, with a note naming the link or the reason."""
    stubs = {p.name: p for p in sorted((ROOT / "labs" / stage).glob("*.cpp"))}
    parts = labs.parts + (stage,)
    try:
        folder = open_folder(labs.root, parts)
    except LinkError as link:
        notes.append(f"{link.path} is a symbolic link: links are not followed, so this lab is "
                     f"graded with the stubs")
        return {name: stub.read_bytes() for name, stub in stubs.items()}
    except OSError:
        notes.append(f"{'/'.join(parts)} is not in the submission: graded with the stubs")
        return {name: stub.read_bytes() for name, stub in stubs.items()}
    sources = {}
    try:
        for name, stub in stubs.items():
            shown = "/".join(parts + (name,))
            try:
                sources[name] = read_regular(folder, name, shown)
            except LinkError:
                notes.append(f"{shown} is a symbolic link: links are not followed, so it is graded "
                             f"with the stub")
            except FileNotFoundError:
                notes.append(f"{name} is not in the submission: graded with the stub")
            except OSError as error:
                notes.append(f"{error.strerror or error}: graded with the stub")
            if name not in sources:
                sources[name] = stub.read_bytes()
        extra = sorted(n for n in os.listdir(folder) if n not in sources)
        if extra:
            notes.append(f"ignored (only the stub's files are graded): {', '.join(extra[:10])}")
    finally:
        os.close(folder)
    return sources


def find_labs(submission: Path):
    """Where the lab folders of a submission (a labs/ copy or a whole repo) are, or None. A linked
    labs/ is not followed: its labs are then reported as links, one note each."""
    for parts in (("labs",), ()):
        try:
            fd = open_folder(submission, parts)
        except LinkError:
            return Submitted(submission, parts)
        except OSError:
            continue
        try:
            if any(STAGE_RE.match(n) for n in os.listdir(fd)):
                return Submitted(submission, parts)
        finally:
            os.close(fd)
    return None


def build_stage(builder: Builder, kit: Kit, labs: Submitted, result: StageResult, hidden: list,
                run_dir: Path):
    """Compiles, checks and links one stage. Returns its executables, {"tests": {unit: path},
    "hidden": {unit: path}} where unit None is every student file of the lab and a file's name its
    own executable (link_own_files), the visible ones copied to run_dir; or None when the lab did
    not compile or link."""
    stage = result.stage
    sources = submitted_sources(labs, stage, result.notes)
    stubs = {n: (ROOT / "labs" / stage / n).read_bytes() for n in sources}
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(builder.sandbox.slots)) as pool:
        done = dict(zip(sources, pool.map(lambda n: builder.compile(stage, n, sources[n]), sources)))
        stub_objs = dict(zip(stubs, pool.map(lambda n: builder.compile(stage, n, stubs[n], "stub-"), stubs)))
    errors = [c.error + ("\n" + c.log if c.log else "") for c in done.values() if c.error]
    if any(s.error for s in stub_objs.values()):
        raise GradingFailure(f"the instructor's stubs of {stage} did not compile here: "
                             f"{next(c.error for c in stub_objs.values() if c.error)}")
    if errors:
        result.compile_error = "\n".join(errors)
        return None
    stub_defined = kit.defined_by([str(s.obj) for s in stub_objs.values()])
    own_defined = kit.defined_by([str(c.obj) for c in done.values()])
    problems = []
    for name, c in done.items():
        problems += [f"{name}: {p}" for p in check_object(kit, stage, c.obj, stub_defined, own_defined)]
        if "checker" in kit.stages[stage]:
            result.notes += [f"{name}: {p}" for p in sandbox_notes(kit, stage, c.obj, own_defined)]
    if problems:
        result.compile_error = "refused:\n" + "\n".join(problems[:30])
        return None
    warnings = "\n".join(c.log for c in done.values() if c.log.strip())
    if warnings:
        result.notes.append("compiler warnings:\n" + warnings[-OUTPUT_LIMIT:])
    objects = {name[:-len(".cpp")]: c.obj for name, c in done.items()}
    if "checker" in kit.stages[stage]:
        return build_remote_stage(builder, kit, result, objects, hidden, run_dir)
    exe = builder.private / stage / f"test_{stage}"
    error = builder.link(stage, "tests", list(objects.values()), exe)
    if error:
        result.compile_error = error
        return None
    exes = {"tests": {None: exe}, "hidden": {}}
    if hidden:
        hidden_exe = builder.private / stage / f"test_{stage}_hidden"
        if builder.link(stage, "hidden", list(objects.values()), hidden_exe):
            for case in hidden:
                case.status, case.output = "not compiled", "the hidden tests did not link"
        else:
            exes["hidden"][None] = hidden_exe
    link_own_files(builder, kit, result, objects, exes)
    for unit, path in exes["tests"].items():
        exes["tests"][unit] = Program(runnable(path, run_dir))
    for unit, path in exes["hidden"].items():
        exes["hidden"][unit] = Program(path)
    return exes


def runnable(path: Path, run_dir: Path) -> Path:
    """A copy of `path` in the run folder, where the sandbox's identities may execute it."""
    copy = run_dir / path.name
    shutil.copyfile(path, copy)
    os.chmod(copy, 0o755)
    return copy


def build_remote_stage(builder: Builder, kit: Kit, result: StageResult, objects: dict, hidden: list,
                       run_dir: Path) -> dict:
    """build_stage() for a remote stage: the instructor's checkers run the tests, and the
    submitted objects are linked into a worker only, in the run folder. Partial credit is
    second_chances(): exes["alone"] names the files whose tests may run again."""
    stage, spec = result.stage, kit.stages[result.stage]
    worker = run_dir / f"worker_{stage}"
    error = builder.link(stage, "worker", list(objects.values()), worker)
    if error:
        result.compile_error = error
        return None
    os.chmod(worker, 0o755)
    checkers = {"tests": runnable(Path(spec["checker"]), run_dir)}
    if hidden and spec.get("checker_hidden"):
        checkers["hidden"] = Path(spec["checker_hidden"])  # copied to the run folder after the visible tests
    exes = {kind: {None: Program(checker, worker, batch=True)} for kind, checker in checkers.items()}
    exes.setdefault("hidden", {})
    reference = spec.get("reference", {})
    exes["alone"] = {unit: objects[unit] for unit in objects if unit in reference}
    return exes


def second_chances(builder: Builder, kit: Kit, plans: list, built: list, run_dir: Path) -> list:
    """Partial credit in a remote lab: a test of one lab file that failed with all of the
    student's files runs again with that file and the reference's objects of the lab's other
    files, so a finished file earns its points whatever else is unwritten. Links a worker per
    such file (a file that does not link alone is noted, and its tests keep their first run) and
    returns [(program, fresh copy of the case, the case)] to run, the program's checker as in
    `exes` (a hidden one not yet in the run folder); a submission whose tests all pass links none."""
    wanted = {}
    for (result, _, hidden), exes in zip(plans, built):
        if exes is None or "alone" not in exes:
            continue
        for case in result.tests:
            kind = "hidden" if any(case is h for h in hidden) else "tests"
            if case.unit in exes["alone"] and None in exes[kind] and \
                    case.status not in ("passed", "not run", "not compiled"):
                key = (id(result), case.unit)
                wanted.setdefault(key, (result, case.unit, exes["alone"][case.unit], []))[3].append(
                    (exes[kind][None].exe, case))

    def link(want):
        result, unit, obj, _ = want
        reference = kit.stages[result.stage]["reference"]
        path = run_dir / f"worker_{result.stage}_{unit}"
        others = [reference[u] for u in sorted(reference) if u != unit]
        return builder.link(result.stage, "worker", [obj], path, others), path

    with concurrent.futures.ThreadPoolExecutor(max_workers=len(builder.sandbox.slots)) as pool:
        linked = list(pool.map(link, wanted.values()))
    jobs = []
    for (result, unit, _, cases), (error, path) in zip(wanted.values(), linked):
        if error:
            result.notes.append(alone_note(unit, error))
            continue
        os.chmod(path, 0o755)
        for checker, case in cases:
            fresh = TestCase(case.stage, case.name, case.tags, course_points=case.course_points,
                             course_hidden=case.course_hidden)
            jobs.append((Program(checker, path, batch=True), fresh, case))
    return jobs


def take_second_chances(chances: list) -> None:
    """A test passes when it passed with all of the student's files or with its own file alone;
    a test that failed both ways reports its second run (its file alone, as its note says)."""
    for _, fresh, case in chances:
        fresh.seconds += case.seconds
        case.status, case.output, case.seconds = fresh.status, fresh.output, fresh.seconds
        case.checks, case.captured = fresh.checks, fresh.captured


def alone_note(unit: str, error: str) -> str:
    reason = re.sub(r"(\w)\((?:[^()]|\([^()]*\))*\)", r"\1()", error.splitlines()[0])  # names, not signatures
    return (f"{unit}.cpp does not link with the reference of this lab's other files ({reason}): its "
            f"tests ran with all of your files of the lab, so they need those written too")


def link_own_files(builder: Builder, kit: Kit, result: StageResult, objects: dict, exes: dict) -> None:
    """Partial credit: a test of one lab file runs with the student's object of that file and the
    reference's objects of the lab's other files, so a finished file earns its points whatever
    else is unwritten. A file that needs another of the student's files (or defines a name the
    reference defines too) does not link alone: its tests then run with all of them, as noted."""
    stage = result.stage
    reference = kit.stages[stage].get("reference", {})
    wanted = sorted({("hidden" if c.hidden else "tests", c.unit) for c in result.tests
                     if c.unit in objects and c.unit in reference})
    wanted = [(kind, unit) for kind, unit in wanted if None in exes[kind]]

    def link(job):
        kind, unit = job
        path = builder.private / stage / f"test_{stage}{'_hidden' if kind == 'hidden' else ''}_{unit}"
        others = [reference[u] for u in sorted(reference) if u != unit]
        return builder.link(stage, kind, [objects[unit]], path, others), path

    with concurrent.futures.ThreadPoolExecutor(max_workers=len(builder.sandbox.slots)) as pool:
        linked = list(pool.map(link, wanted))
    alone = set()
    for (kind, unit), (error, path) in zip(wanted, linked):
        if not error:
            exes[kind][unit] = path
        elif unit not in alone:
            alone.add(unit)
            result.notes.append(alone_note(unit, error))


def in_course(course, stage: str, cases: list) -> list:
    """The cases of the course (all without one), with the course's points and visibility."""
    if course is None:
        return cases
    kept = []
    for case in cases:
        test = course.test(stage, case.name)
        if test is not None:
            case.course_points, case.course_hidden = test.points, test.hidden and not case.hidden
            kept.append(case)
    return kept


def grade_one(args, kit: Kit, sandbox: Sandbox, submission: Path, out: Path, course=None,
              quiet: bool = False) -> tuple:
    """Grades one submission into `out`; returns (results.json's data, the lab results). Never
    raises: whatever the submission does, report.txt and results.json are written, last and
    atomically. `quiet`: no report on the terminal (a class prints a progress line instead)."""
    start = time.monotonic()
    deadline = Deadline(args.deadline)
    title = f"PhysLab grade of {submission.name}"
    private = Path(tempfile.mkdtemp(prefix="physlab-grade-"))
    shared = Path(tempfile.mkdtemp(prefix="physlab-sandbox-"))
    workers = len(sandbox.slots)
    results = []
    try:
        stages = graded_stages(args.labs, course)
        labs = find_labs(submission) if submission.is_dir() else None
        if labs is None:
            raise SubmissionError("no labs/ folder with NN_name stages in the submission")
        if sandbox.gid is not None:
            # Only this submission's sandbox users (its group) may enter: others graded at the same
            # time cannot reach its hidden tests
            os.chown(shared, 0, sandbox.gid)
            os.chmod(shared, 0o710)
        else:
            os.chmod(shared, 0o711)
        shutil.copytree(ROOT / "common" / "include", shared / "include")
        run_dir = shared / "run"
        run_dir.mkdir(mode=0o711)
        for path in [shared / "include"] + list((shared / "include").rglob("*")):
            os.chmod(path, 0o755 if path.is_dir() else 0o644)
        builder = Builder(kit, sandbox, private, shared, deadline, args.compile_timeout)
        remote = [stage for stage in stages if "checker" in kit.stages.get(stage, {})]
        if any("checker" in spec for spec in kit.stages.values()):
            sandbox.isolation = Isolation(kit, run_dir, sandbox)
        visible_jobs, hidden_jobs, plans = [], [], []
        for stage in stages:
            visible = in_course(course, stage, list_tests(kit.build / f"test_{stage}", stage))
            hidden_ref = kit.build / f"test_{stage}_hidden"
            hidden = in_course(course, stage, list_tests(hidden_ref, stage) if hidden_ref.exists() else [])
            if stage in remote:  # a framework test grades nothing, and its scenes are slow across the wire
                visible, hidden = [c for c in visible if c.graded], [c for c in hidden if c.graded]
            result = StageResult(stage, visible + hidden)
            if stage in remote:
                result.notes.append(sandbox.isolation.describe())
            plans.append((result, visible, hidden))
        # Every lab at once: their compiles share the sandbox's slots, so no slot waits for one
        # lab's last file while another lab's files are still to compile
        with concurrent.futures.ThreadPoolExecutor(max_workers=len(plans) or 1) as pool:
            built = list(pool.map(lambda plan: build_stage(builder, kit, labs, plan[0], plan[2], run_dir), plans))
        for (result, visible, hidden), exes in zip(plans, built):
            if exes is None:
                for case in result.tests:
                    case.status, case.output = "not compiled", result.compile_error[-OUTPUT_LIMIT:]
            else:
                visible_jobs += [(exes["tests"].get(c.unit, exes["tests"][None]), c) for c in visible]
                if None in exes["hidden"]:
                    hidden_jobs += [(exes["hidden"].get(c.unit, exes["hidden"][None]), c) for c in hidden]
            results.append(result)
        phases = {"build": time.monotonic() - start}  # seconds, in results.json's extra_data

        copies = {}  # a hidden checker -> its copy in the run folder

        def hidden_copies(jobs) -> list:
            moved = []
            for program, case in jobs:
                if program.exe.parent != run_dir and program.exe not in copies:
                    copies[program.exe] = runnable(program.exe, run_dir)
                moved.append((Program(copies.get(program.exe, program.exe), program.worker, program.batch), case))
            return moved

        make_homes(sandbox, shared)
        if all(program.batch for program, _ in visible_jobs + hidden_jobs):
            # Only checkers, which never load submitted code, and their workers, which can reach
            # no file, process or other worker: a hidden test's inputs cannot reach a visible
            # test's output, so both kinds run at once, hidden first (its few long tests then
            # overlap the many short visible ones)
            run_cases(sandbox, hidden_copies(hidden_jobs) + visible_jobs, args.seed, args.timeout, deadline,
                      private, shared, workers)
            phases["tests"] = time.monotonic() - start - sum(phases.values())
            chances = second_chances(builder, kit, plans, built, run_dir)
            if chances:
                run_cases(sandbox, hidden_copies([(p, fresh) for p, fresh, _ in chances]), args.seed,
                          args.timeout, deadline, private, shared, workers)
                take_second_chances(chances)
                phases["partial credit"] = time.monotonic() - start - sum(phases.values())
            sandbox.finish()
        else:
            # Every visible test first; hidden tests only after every process of those runs is
            # gone and their files removed, so no student process can carry a hidden test's text
            # into a visible output.
            run_cases(sandbox, visible_jobs, args.seed, args.timeout, deadline, private, shared, workers)
            phases["visible tests"] = time.monotonic() - start - sum(phases.values())
            sandbox.finish()
            make_homes(sandbox, shared)
            run_cases(sandbox, hidden_copies(hidden_jobs), args.seed, args.timeout, deadline, private, shared, workers)
            sandbox.finish()
            phases["hidden tests"] = time.monotonic() - start - sum(phases.values())
        ungraded = [c for r in results for c in r.tests if c.status == "not graded"]
        if ungraded:
            raise GradingFailure(f"{len(ungraded)} tests could not start the sandbox of the submitted "
                                 f"code ({ungraded[0].output or ungraded[0].name})")
        text = report(results, args.seed, title)
        data = gradescope_json(results, time.monotonic() - start)
        data["extra_data"] = {"seconds": {k: round(v, 2) for k, v in phases.items()}}
        write_outputs(out, text, data)
    except SubmissionError as error:  # the submission's own fault: a score of 0 that says why
        sandbox.finish()
        text = f"{title}\n\nGRADING FAILED: {error}"
        data = failure_outputs(out, title, str(error), time.monotonic() - start)
        results = []
    except Exception as error:  # the grading's own failure is never a score; a report is still written
        try:
            sandbox.finish()
        except Exception as cleanup:
            error = f"{error}; then, ending the sandbox: {cleanup}"
        why = str(error) if isinstance(error, GradingFailure) else f"the grader failed: {type(error).__name__}: {error}"
        text = f"{title}\n\nNOT GRADED: {why}"
        data = not_graded_outputs(out, title, why, time.monotonic() - start)
        results = []
    finally:
        shutil.rmtree(private, ignore_errors=True)
        shutil.rmtree(shared, ignore_errors=True)
    if not quiet:
        print(text)
        print(f"\nwrote {out / 'report.txt'} and {out / 'results.json'}")
    return data, results


def make_homes(sandbox: Sandbox, shared: Path) -> None:
    """Fresh, empty working folders for the sandbox users (finish() removes their files)."""
    for slot in sandbox.slots:
        home = shared / f"home-{slot}"
        shutil.rmtree(home, ignore_errors=True)
        home.mkdir(mode=0o700)
        if sandbox.ids(slot):
            os.chown(home, *sandbox.ids(slot))


def make_private(path: Path) -> None:
    """Takes other users' access away (as root, before student code runs as a sandbox user)."""
    if path.exists():
        os.chmod(path, stat.S_IMODE(os.stat(path).st_mode) & ~0o077)


def submission_problems(paths: list) -> list:
    """What makes a submission ungradable before anything starts: missing, not a folder, empty."""
    problems = []
    for p in paths:
        path = Path(p)
        if not path.exists() and not path.is_symlink():
            problems.append(f"submission {p}: no such folder")
        elif path.is_symlink() or not path.is_dir():
            problems.append(f"submission {p}: not a folder (a student's labs/ folder or a copy of the repository)")
        elif not any(path.iterdir()):
            problems.append(f"submission {p}: the folder is empty")
    names = [Path(p).absolute().name for p in paths]
    twice = sorted({n for n in names if names.count(n) > 1})
    if len(paths) > 1 and twice:
        problems.append(f"two submissions named {twice[0]}: each is graded into --out/<name>/")
    return problems


def limits_of(args, course) -> None:
    """The time limits: the command line's, else the course file's, else the defaults."""
    limits = course.limits if course is not None else course_file.DEFAULT_LIMITS
    for option, key in (("deadline", "deadline"), ("timeout", "test"), ("compile_timeout", "compile")):
        if getattr(args, option) is None:
            setattr(args, option, limits[key])


def cmd_grade(args) -> int:
    """Grade one submission into --out, or several (a class, in parallel) into --out/<name>/ plus
    scores.csv, tests.csv and class.html. The course file and the submissions are checked before
    anything is graded."""
    out = Path(args.out).resolve()
    problems = submission_problems(args.submissions)
    course = None
    if args.course:
        try:
            course = course_file.load(args.course)
        except course_file.CourseError as error:
            problems.insert(0, f"course file {error}")
    if course is not None and args.labs:
        wanted = select_stages(discover_stages(ROOT), args.labs)
        problems += [f"--labs {s}: lab {s} is not in the course {args.course}" for s in wanted if s not in course.labs]
    if problems:
        for problem in problems:
            print(f"grader: {problem}", file=sys.stderr)
        if len(args.submissions) == 1:  # Gradescope: the student's result says why
            failure_outputs(out, f"PhysLab grade of {Path(args.submissions[0]).name}",
                            "; ".join(problems), 0.0)
        print("grader: nothing graded", file=sys.stderr)
        return 2
    limits_of(args, course)
    out.mkdir(parents=True, exist_ok=True)
    single = len(args.submissions) == 1
    # A class is graded several submissions at once, each with sandbox users of its own; as the
    # current user (not root) nothing keeps two submissions' processes apart: one at a time.
    root = os.geteuid() == 0
    parallel = 1 if single or not root else max(1, min(len(args.submissions), os.cpu_count() or 1, args.jobs))
    jobs_each = max(1, args.jobs // parallel)
    sandboxes = [Sandbox(jobs_each, switch_user=True, first=k * jobs_each,
                         group=None if single else 255 - k) for k in range(parallel)]
    if sandboxes[0].root:
        for path in (ROOT, Path(args.build).resolve(), out):
            make_private(path)
    try:
        kit = Kit(Path(args.build).resolve())
        kit.require_notary()
    except Exception as error:  # no usable instructor build: every submission still gets its files
        for sub_path in args.submissions:
            target = out if single else out / Path(sub_path).absolute().name
            failure_outputs(target, f"PhysLab grade of {Path(sub_path).name}", str(error), 0.0)
        print(f"grader: {error}", file=sys.stderr)
        return 1
    if course is not None:
        print(course.summary())
    if single:
        data, _ = grade_one(args, kit, sandboxes[0], Path(args.submissions[0]).absolute(), out, course)
        if not_graded(data):
            print(f"grader: not graded: {not_graded(data)}", file=sys.stderr)
            return EXIT_NOT_GRADED
        return 0
    graded = grade_class(args, kit, sandboxes, out, course)
    rows = ["submission,score,max_score"]
    rows += [f"{name},not graded ({csv_text(not_graded(data))}),"
             if not_graded(data) else f"{name},{data['score']:g},{data['max_score']:g}"
             for name, (data, _, _) in graded.items()]
    write_atomically(out / "scores.csv", "\n".join(rows) + "\n")
    import class_report  # the class's tables and page: only an instructor grading a class needs them
    class_report.write(out, graded, course)
    for name, (data, _, seconds) in graded.items():
        score = f"not graded ({not_graded(data)})" if not_graded(data) else f"{data['score']:g},{data['max_score']:g}"
        print(f"{name},{score}  ({seconds:.0f} s)")
    times = [seconds for _, _, seconds in graded.values()]
    print(f"{len(times)} submissions, {parallel} at a time: {sum(times) / len(times):.0f} s each on "
          f"average (slowest {max(times):.0f} s)")
    print(f"wrote {out / 'scores.csv'}, {out / 'tests.csv'} and {out / 'class.html'}")
    failed = [name for name, (data, _, _) in graded.items() if not_graded(data)]
    if failed:
        print(f"grader: {len(failed)} not graded (tried twice): {', '.join(failed)}", file=sys.stderr)
        return EXIT_NOT_GRADED
    return 0


def csv_text(text: str) -> str:
    """Text for a field of scores.csv: no comma, quote or line break."""
    return re.sub(r'[,"\n\r]+', " ", text)[:200]


def grade_class(args, kit: Kit, sandboxes: list, out: Path, course) -> dict:
    """Grades the submissions, len(sandboxes) at a time, with a progress line after each; returns
    {name: (results.json's data, lab results, seconds)} in the order given."""
    paths = [Path(p).absolute() for p in args.submissions]
    waiting = list(reversed(paths))
    graded, lock = {}, threading.Lock()
    start = time.monotonic()

    def worker(sandbox: Sandbox) -> None:
        while True:
            with lock:
                if not waiting:
                    return
                path = waiting.pop()
            began = time.monotonic()
            data, results = grade_one(args, kit, sandbox, path, out / path.name, course, quiet=True)
            if not_graded(data):  # the grading failed, not the code: once more
                data, results = grade_one(args, kit, sandbox, path, out / path.name, course, quiet=True)
            seconds = time.monotonic() - began
            with lock:
                graded[path.name] = (data, results, seconds)
                done, total = len(graded), len(paths)
                left = (time.monotonic() - start) / done * (total - done)
                score = "not graded" if not_graded(data) else f"{data['score']:g}/{data['max_score']:g}"
                print(f"graded {done}/{total}: {path.name} {score} "
                      f"in {seconds:.0f} s; about {left / 60:.1f} min left", file=sys.stderr, flush=True)

    threads = [threading.Thread(target=worker, args=(sandbox,)) for sandbox in sandboxes]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return {p.name: graded[p.name] for p in paths}


# ---- Gradescope --------------------------------------------------------------------------------

# What grading needs, and all the autograder zip holds (the Grading page, "The Gradescope zip"):
# the driver and the CMake files that configure the tree (PhysLabDocs.cmake reads Doxyfile.in when
# Doxygen is installed), the framework, the reference, the stubs (the grader compiles a
# submission's missing files from them), the visible and hidden tests with their support, the
# handouts (a failed test's report names a section) and this grader. No mutant catalogue, no
# hostile submissions, no demos or benchmarks (their folders are globbed: absent, they add no
# target), no other tool.
GRADING_FILES = re.compile(r"^(physlab|CMakeLists\.txt|cmake/PhysLab(Dependencies|Docs)?\.cmake|"
                           r"common/.*|solutions/.*|labs/.*|tests/(?!hidden/(mutants|adversarial)/).*|"
                           r"docs/lab\d\d_[a-z0-9_]+\.md|docs/Doxyfile\.in|tools/(grader|course|remote_gen)\.py)$")


def cmd_gradescope(args) -> int:
    """Writes the Gradescope autograder zip: the tracked files grading needs (GRADING_FILES) under
    physlab/, with setup.sh and run_autograder at its top level; with a course file, that file as
    physlab/course.toml, which run_autograder then grades with."""
    course = None
    if args.course:
        try:
            course = course_file.load(args.course)
        except course_file.CourseError as error:
            print(f"grader: course file {error}; no zip written", file=sys.stderr)
            return 2
        print(course.summary())
    listing = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True)
    if listing.returncode != 0:  # not a checkout, or one git will not read (owned by another user)
        why = listing.stderr.decode(errors="replace").strip().splitlines()
        print(f"grader: gradescope: the zip holds the files git tracks, and git cannot list them in {ROOT}: "
              f"{why[0] if why else 'status ' + str(listing.returncode)}"
              + (f"\n  if you trust this folder: git config --global --add safe.directory {ROOT}"
                 if any("safe.directory" in line for line in why) else "") + "\nno zip written", file=sys.stderr)
        return 2
    tracked = listing.stdout.decode().split("\0")
    files = [f for f in tracked if GRADING_FILES.match(f)]
    out = Path(args.out).resolve()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        for name in files:
            z.write(ROOT / name, f"physlab/{name}")
        for script in ("setup.sh", "run_autograder"):
            info = zipfile.ZipInfo(script)
            info.external_attr = 0o755 << 16
            z.writestr(info, (ROOT / "tools" / "gradescope" / script).read_text())
        if course is not None:
            z.write(Path(args.course), "physlab/course.toml")
    print(f"wrote {out} ({len(files)} of the {len([f for f in tracked if f])} tracked files"
          f"{', and the course file' if course else ''}, {out.stat().st_size // 1024} KiB)")
    return 0


def cmd_stages(args) -> int:
    """The labs `grade` with the same --labs and --course needs built: a bad lab or course file
    falls back to every lab, so that the grade itself refuses it with its own message."""
    every = discover_stages(ROOT)
    try:
        chosen = graded_stages(args.labs, course_file.load(args.course) if args.course else None)
    except (SystemExit, course_file.CourseError):
        chosen = every
    print("\n".join(chosen or every))
    return 0


class Parser(argparse.ArgumentParser):
    """Option errors in one line that names the option and the value, without the grader's
    internal usage (people meet it through ./physlab, whose --help is theirs)."""

    def error(self, message):
        self.exit(2, f"physlab: {self.prog.split()[-1]}: {message}\n")


def whole_number(text: str) -> int:
    if not text.isdigit():
        raise argparse.ArgumentTypeError(f"needs a whole number (e.g. 42), got '{text}'")
    return int(text)


def seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = 0.0
    if not value > 0:
        raise argparse.ArgumentTypeError(f"needs a positive number of seconds, got '{text}'")
    return value


def main() -> int:
    parser = Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    common = Parser(add_help=False)
    common.add_argument("--labs", nargs="*", default=[], help="lab numbers or names (default: all)")
    common.add_argument("--seed", type=whole_number, default=int.from_bytes(os.urandom(3), "big"),
                        help="Catch2 --rng-seed for every test (default: random, printed)")
    common.add_argument("--timeout", type=seconds, default=None,
                        help="seconds per test case (default 30, or the course file's; the slowest "
                             "reference test takes about 1 s)")
    common.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    run = sub.add_parser("run", parents=[common], help="run built tests and report")
    run.add_argument("--build", required=True, help="the CMake build folder")
    run.add_argument("--variant", choices=["solutions", "labs"], default="labs")
    run.add_argument("--out", help="also write report.txt and results.json here")
    run.add_argument("--expect", choices=["pass", "fail"], default="pass",
                     help="fail: the stub check (every graded test must fail, not implemented)")
    run.add_argument("--summary", help="write 'passed failed' counts to this file")
    run.set_defaults(func=cmd_run)
    grade = sub.add_parser("grade", parents=[common], help="grade submissions")
    grade.add_argument("submissions", nargs="+", metavar="SUBMISSION",
                       help="a student's labs/ folder or a copy of the repo (several: one folder each)")
    grade.add_argument("--out", required=True,
                       help="folder for report.txt and results.json (several: DIR/<name>/ and scores.csv)")
    grade.add_argument("--build", required=True, help="the instructor's built tree")
    grade.add_argument("--deadline", type=float, default=None,
                       help="seconds for the whole grade of one submission (default 540, or the "
                            "course file's; Gradescope allows 600)")
    grade.add_argument("--compile-timeout", type=float, default=None,
                       help="seconds to compile one lab file (default 120, or the course file's)")
    grade.add_argument("--course", help="the course file (the Grading page): its labs, sections, "
                                        "points, hidden tests and time limits")
    grade.set_defaults(func=cmd_grade)
    package = sub.add_parser("gradescope", help="write the Gradescope autograder zip")
    package.add_argument("--out", required=True, help="the zip file to write")
    package.add_argument("--course", help="the course file the zip grades with (physlab/course.toml)")
    package.set_defaults(func=cmd_gradescope)
    stages = sub.add_parser("stages", help="the labs a grade with these arguments builds, one per line "
                                           "(every lab when they name none or cannot be read)")
    stages.add_argument("--labs", nargs="*", default=[])
    stages.add_argument("--course")
    stages.set_defaults(func=cmd_stages)
    args, unknown = parser.parse_known_args()
    if unknown and args.command != "stages":
        parser.error("unrecognized arguments: " + " ".join(unknown))
    return args.func(args)


if __name__ == "__main__":
    sys.exit(main())
