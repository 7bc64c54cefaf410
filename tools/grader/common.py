"""What every part of the grader shares: the tree's root and labs, the limits on what submitted code
may use, text made safe for a report, files read capped and written atomically, and the records of
tests and their results (TestCase, Program, StageResult) with the grader's two exceptions.
"""

import functools
import os
import re
import threading
from dataclasses import dataclass, field
from pathlib import Path

import course as course_file  # tools/course.py, beside the package

ROOT = Path(__file__).resolve().parent.parent.parent
STAGE_RE = re.compile(r"^(\d\d)_[a-z0-9_]+$")
OUTPUT_LIMIT = 8000          # characters of a test's explanation kept in results.json
OUTPUT_FILE_LIMIT = 4 << 20  # bytes a test process may write to stdout and stderr together
SOURCE_LIMIT = 1 << 20       # bytes of one submitted source file
TEST_MEMORY = 2 << 30        # address space of a test process; the largest test uses ~100 MB
COMPILE_MEMORY = 4 << 30     # address space of the compiler on one lab file
COMPILE_OUTPUT = 256 << 20   # bytes of one object file (ours are under 2 MB)
SANDBOX_PROCESSES = 64       # processes a sandbox user may have at once

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


def write_atomically(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{threading.get_ident()}.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


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
