"""`./physlab test`: the tree's own test executables, the course's points in a student copy, the
remote stages' checkers run with the reference's worker, and the stub check.
"""

import json
from pathlib import Path

import course as course_file  # tools/course.py, beside the package

from .common import ROOT, Program, StageResult, TestCase
from .isolation import Isolation
from .kit import Kit
from .runner import list_tests
from .sandbox import Sandbox


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
