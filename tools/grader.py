#!/usr/bin/env python3
"""PhysLab's test runner and autograder.

Runs every Catch2 test case of the chosen stages in its own process with a time limit, so a
crash, a hang or an exception costs that test only, and writes a readable report plus
Gradescope's results.json. Called by ./physlab (test, grade); see `grader.py --help`.
"""

import argparse
import concurrent.futures
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
STAGE_RE = re.compile(r"^(\d\d)_[a-z0-9_]+$")
OUTPUT_LIMIT = 8000  # characters of compiler or test output kept per test in results.json


@dataclass
class TestCase:
    """One Catch2 TEST_CASE of one stage, and what running it gave."""

    stage: str
    name: str
    tags: list
    status: str = "not run"  # passed | failed | not implemented | timed out | crashed | not compiled
    output: str = ""
    seconds: float = 0.0

    @property
    def points(self) -> float:
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
        return "hidden" in self.tags

    @property
    def passed(self) -> bool:
        return self.status == "passed"


@dataclass
class StageResult:
    stage: str
    tests: list = field(default_factory=list)
    compile_error: str = ""


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
        matches = [s for s in all_stages if s == w or s[:2] == w.zfill(2)]
        if not matches:
            raise SystemExit(f"grader: no lab '{w}' (labs: {', '.join(all_stages)})")
        chosen += [m for m in matches if m not in chosen]
    return chosen


def escape_spec(name: str) -> str:
    """A test name as a Catch2 test spec that matches exactly that test."""
    return re.sub(r'([\\,\[\]*"~])', r"\\\1", name)


def list_tests(exe: Path, stage: str) -> list:
    names = subprocess.run([str(exe), "--list-test-names-only"], capture_output=True,
                           text=True, timeout=60).stdout.splitlines()  # exit code = count
    cases = []
    for name in (n.strip() for n in names):
        if not name:
            continue
        listing = subprocess.run([str(exe), "--list-tests", escape_spec(name)],
                                 capture_output=True, text=True, timeout=60).stdout
        tags = re.findall(r"\[([^\]]+)\]", " ".join(
            line for line in listing.splitlines() if line.lstrip().startswith("[")))
        cases.append(TestCase(stage=stage, name=name, tags=tags))
    return cases


def describe_failure(xml_text: str) -> tuple:
    """(status, explanation) from Catch2's XML report of one test case."""
    try:
        tree = ET.fromstring(xml_text)
    except ET.ParseError:
        return "crashed", "the test process ended before finishing its report"
    lines = []
    status = "failed"
    nested = {id(e) for x in tree.iter("Expression") for e in x.findall("Exception")}
    for node in tree.iter():
        if id(node) in nested:
            continue  # already reported with the assertion it interrupted
        if node.tag == "Expression" and node.get("success") == "false":
            where = f"{Path(node.get('filename', '?')).name}:{node.get('line', '?')}"
            original = (node.findtext("Original") or "").strip()
            expanded = (node.findtext("Expanded") or "").strip()
            lines.append(f"{node.get('type', 'CHECK')}( {original} ) failed at {where}")
            if expanded and expanded != original:
                lines.append(f"  actual: {expanded}")
            for info in node.findall("Info"):
                lines.append(f"  note: {(info.text or '').strip()}")
            exc = node.findtext("Exception")
            if exc:
                lines.append(f"  threw: {exc.strip()}")
        elif node.tag == "Exception":
            text = (node.text or "").strip()
            if "not implemented" in text:
                status = "not implemented"
            lines.append(f"threw: {text}")
        elif node.tag == "FatalErrorCondition":
            status = "crashed"
            lines.append(f"fatal: {(node.text or '').strip()}")
    if status == "failed" and any("not implemented" in l for l in lines):
        status = "not implemented"
    return status, "\n".join(lines)


def run_one(exe: Path, case: TestCase, seed: int, timeout: float) -> TestCase:
    start = time.monotonic()
    cmd = [str(exe), escape_spec(case.name), "-r", "xml", "--rng-seed", str(seed)]
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                              errors="replace")
    except subprocess.TimeoutExpired:
        case.status, case.output = "timed out", f"killed after {timeout:g} s"
        case.seconds = time.monotonic() - start
        return case
    case.seconds = time.monotonic() - start
    if proc.returncode < 0:
        sig = signal.Signals(-proc.returncode).name
        _, detail = describe_failure(proc.stdout)
        case.status = "crashed"
        case.output = f"crashed ({sig})" + (f"\n{detail}" if detail else "")
    elif proc.returncode == 0 and 'success="true"' in proc.stdout:
        case.status = "passed"
    else:
        case.status, case.output = describe_failure(proc.stdout)
        if not case.output:
            case.output = (proc.stderr or proc.stdout)[-OUTPUT_LIMIT:]
    return case


def executable(build: Path, stage: str, variant: str) -> Path:
    return build / (f"test_{stage}" + ("_labs" if variant == "labs" else ""))


def run_stages(build: Path, stages: list, variant: str, seed: int, timeout: float,
               jobs: int, compile_errors: dict) -> list:
    results = []
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=jobs)
    for stage in stages:
        result = StageResult(stage)
        exe = executable(build, stage, variant)
        listing_exe = exe if exe.exists() else executable(build, stage, "solutions")
        if stage in compile_errors or not exe.exists():
            result.compile_error = compile_errors.get(stage, f"{exe.name} was not built")
            if listing_exe.exists() and listing_exe != exe:
                result.tests = list_tests(listing_exe, stage)
            for case in result.tests:
                case.status, case.output = "not compiled", result.compile_error[-OUTPUT_LIMIT:]
        else:
            result.tests = list_tests(exe, stage)
            futures = [pool.submit(run_one, exe, c, seed, timeout) for c in result.tests]
            concurrent.futures.wait(futures)
        results.append(result)
    pool.shutdown()
    return results


SYMBOL = {"passed": "PASS", "failed": "FAIL", "not implemented": "TODO", "timed out": "TIME",
          "crashed": "CRSH", "not compiled": "COMP", "not run": "----"}


def report(results: list, seed: int, title: str) -> str:
    out = [title, f"random seed: {seed} (rerun one test: build/test_NN_name_labs \"<test name>\" "
                  f"--rng-seed {seed})", ""]
    total = earned = 0.0
    for r in results:
        graded = [t for t in r.tests if t.graded]
        got = sum(t.points for t in graded if t.passed)
        possible = sum(t.points for t in graded)
        total += possible
        earned += got
        out.append(f"== lab {r.stage}: {got:g} / {possible:g} points ==")
        if r.compile_error:
            out.append("   did not compile; every test of this lab scores 0. Compiler says:")
            out += ["   | " + l for l in r.compile_error.strip().splitlines()[-25:]]
        for t in r.tests:
            pts = f"{t.points if t.passed else 0:g}/{t.points:g}" if t.graded else "  - "
            extra = " [hidden]" if t.hidden else (" [framework]" if not t.graded else "")
            out.append(f" {SYMBOL[t.status]} {pts:>6}  {t.name}{extra}")
            if not t.passed and t.status != "not compiled":
                out += ["            " + l for l in t.output.splitlines()[:12]]
        out.append("")
    out.append(f"TOTAL: {earned:g} / {total:g} points")
    return "\n".join(out)


def gradescope_json(results: list, elapsed: float) -> dict:
    tests = []
    for lab_index, r in enumerate(results, start=1):
        for i, t in enumerate((t for t in r.tests if t.graded), start=1):
            tests.append({
                "name": f"lab {r.stage}: {t.name}",
                "number": f"{lab_index}.{i}",
                "score": t.points if t.passed else 0.0,
                "max_score": t.points,
                "status": "passed" if t.passed else "failed",
                "output": (t.status if t.passed else f"{t.status}\n{t.output}")[:OUTPUT_LIMIT],
                "visibility": "after_published" if t.hidden else "visible",
                "tags": t.tags,
            })
    return {
        "score": sum(t["score"] for t in tests),
        "max_score": sum(t["max_score"] for t in tests),
        "execution_time": round(elapsed, 2),
        "output": "Per-test results below; the full report is report.txt.",
        "tests": tests,
    }


def write_outputs(out: Path, text: str, data: dict) -> None:
    out.mkdir(parents=True, exist_ok=True)
    (out / "report.txt").write_text(text + "\n")
    with open(out / "results.json", "w") as f:
        json.dump(data, f, indent=2)


def summary_line(results: list) -> tuple:
    cases = [t for r in results for t in r.tests]
    passed = sum(t.passed for t in cases)
    return passed, len(cases) - passed


# ---- commands -------------------------------------------------------------------------------

def cmd_run(args) -> int:
    """Run already built tests; print the report; optionally write results.json."""
    start = time.monotonic()
    stages = select_stages(discover_stages(ROOT), args.labs)
    results = run_stages(Path(args.build), stages, args.variant, args.seed, args.timeout,
                         args.jobs, {})
    if args.variant == "solutions" and (Path(args.build) / "test_common").exists():
        common = StageResult("common")
        common.tests = list_tests(Path(args.build) / "test_common", "common")
        for c in common.tests:
            run_one(Path(args.build) / "test_common", c, args.seed, args.timeout)
        results.append(common)
    title = f"PhysLab tests against {args.variant}/"
    text = report(results, args.seed, title)
    if args.out:
        write_outputs(Path(args.out), text, gradescope_json(results, time.monotonic() - start))
    if args.expect == "fail":
        passed, failed = stub_check(results)
    else:
        print(text)
        passed, failed = summary_line(results)
        print(f"\n{passed} passed, {failed} failed")
    if args.summary:
        graded = [t for r in results for t in r.tests if t.graded]
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


def find_labs(submission: Path):
    """The labs/ folder inside a submission (a labs/ copy or a whole repo), or None."""
    for candidate in (submission / "labs", submission):
        if candidate.is_dir() and any(STAGE_RE.match(p.name) for p in candidate.iterdir()):
            return candidate
    return None


def cmd_grade(args) -> int:
    """Grade one submission into --out, or several into --out/<name>/ plus scores.csv."""
    if len(args.submissions) == 1:
        grade_one(args, Path(args.submissions[0]), Path(args.out))
        return 0
    rows = ["submission,score,max_score"]
    for sub_path in args.submissions:
        data = grade_one(args, Path(sub_path), Path(args.out) / Path(sub_path).resolve().name)
        rows.append(f"{Path(sub_path).resolve().name},{data['score']:g},{data['max_score']:g}")
    (Path(args.out) / "scores.csv").write_text("\n".join(rows) + "\n")
    print("\n".join(rows))
    print(f"wrote {Path(args.out) / 'scores.csv'}")
    return 0


def grade_one(args, submission: Path, out: Path) -> dict:
    """Build a submission's labs/ against the instructor's tests, run, report. Never raises:
    whatever goes wrong, report.txt and results.json are written."""
    start = time.monotonic()
    out = out.resolve()
    stages = select_stages(discover_stages(ROOT), args.labs)
    submission = submission.resolve()
    try:
        labs = find_labs(submission) if submission.is_dir() else None
        if labs is None:
            raise RuntimeError(f"no labs/ folder with NN_name stages in {submission}")
        build = Path(args.build).resolve() if args.build else Path(tempfile.mkdtemp(prefix="physlab-grade-"))
        configure = subprocess.run(
            ["cmake", "-S", str(ROOT), "-B", str(build), f"-DPHYSLAB_LABS_DIR={labs}",
             "-DCMAKE_BUILD_TYPE=Release"], capture_output=True, text=True)
        if configure.returncode != 0:
            raise RuntimeError("configuration failed:\n" + configure.stdout[-3000:] +
                               configure.stderr[-3000:])
        compile_errors = {}
        for stage in stages:
            # The reference build lists the tests of a lab whose student code does not compile.
            targets = [f"test_{stage}", f"test_{stage}_labs"]
            proc = subprocess.run(["cmake", "--build", str(build), "-j", str(args.jobs),
                                   "--target", *targets], capture_output=True, text=True)
            if proc.returncode != 0 or not executable(build, stage, "labs").exists():
                errors = [l for l in (proc.stdout + proc.stderr).splitlines()
                          if "error" in l or "Error" in l or "note:" in l]
                compile_errors[stage] = "\n".join(errors[-60:]) or proc.stderr[-OUTPUT_LIMIT:]
        results = run_stages(build, stages, "labs", args.seed, args.timeout, args.jobs,
                             compile_errors)
        text = report(results, args.seed, f"PhysLab grade of {submission}")
        data = gradescope_json(results, time.monotonic() - start)
        if not args.build:
            shutil.rmtree(build, ignore_errors=True)
    except Exception as error:  # the grader must always leave a report behind
        text = f"PhysLab grade of {submission}\n\nGRADING FAILED: {error}\nscore: 0"
        data = {"score": 0.0, "max_score": 0.0, "execution_time": round(time.monotonic() - start, 2),
                "output": f"Grading failed: {error}", "tests": []}
    write_outputs(out, text, data)
    print(text)
    print(f"\nwrote {out / 'report.txt'} and {out / 'results.json'}")
    return data


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--labs", nargs="*", default=[], help="lab numbers or names (default: all)")
    common.add_argument("--seed", type=int, default=int.from_bytes(os.urandom(3), "big"),
                        help="Catch2 --rng-seed for every test (default: random, printed)")
    common.add_argument("--timeout", type=float, default=30.0,
                        help="seconds per test case (the slowest reference test takes about 1 s)")
    common.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    run = sub.add_parser("run", parents=[common], help="run built tests and report")
    run.add_argument("--build", required=True, help="the CMake build folder")
    run.add_argument("--variant", choices=["solutions", "labs"], default="labs")
    run.add_argument("--out", help="also write report.txt and results.json here")
    run.add_argument("--expect", choices=["pass", "fail"], default="pass",
                     help="fail: the stub check (every graded test must fail, not implemented)")
    run.add_argument("--summary", help="write 'passed failed' counts to this file")
    run.set_defaults(func=cmd_run)
    grade = sub.add_parser("grade", parents=[common], help="grade one submission")
    grade.add_argument("submissions", nargs="+", metavar="SUBMISSION",
                       help="a student's labs/ folder or a copy of the repo (several: one folder each)")
    grade.add_argument("--out", required=True,
                       help="folder for report.txt and results.json (several: DIR/<name>/ and scores.csv)")
    grade.add_argument("--build", help="build folder to use and keep (default: a temporary one)")
    grade.set_defaults(func=cmd_grade)
    args = parser.parse_args()
    return args.func(args)


if __name__ == "__main__":
    sys.exit(main())
