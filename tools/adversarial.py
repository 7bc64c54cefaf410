#!/usr/bin/env python3
"""Grades hostile submissions and checks that the grader holds.

Each case in tests/hidden/adversarial/*.cpp is an attack on the grader built on the untouched
stubs, so it has earned nothing. Its header says how it enters the submission:
    // adversarial: <what it tries>
    // mode: append | replace     (after the stub of FILE, or instead of it)
    // file: labs/NN_name/x.cpp   (default labs/01_particles/diagnostics.cpp)
    // symlink: PATH -> TARGET    (a link in the submission instead of a file or folder)
    // relative                   (make those links relative to where they sit)
    // grade: <extra ./physlab grade options>
    // secret: <text that must appear in no output>
    // quick                      (part of the set CI runs)
{ROOT} stands for the instructor's tree. For every case the grader must: give 0 points, write a
valid results.json and report.txt within its deadline, keep them unchanged afterwards, show no
line of a solution or hidden test (hidden lines only in hidden tests' results), leave no process
behind, and leave the instructor's executables and tracked files as they were.
"""

import argparse
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from grader.sandbox import grader_of, is_identity  # noqa: E402  (the identities of submitted code)

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "tests" / "hidden" / "adversarial"
DEFAULT_FILE = "labs/01_particles/diagnostics.cpp"
SLACK = 30.0  # seconds past the deadline for cleanup and writing the report


def header(path: Path) -> dict:
    meta = {"file": DEFAULT_FILE, "mode": "append", "symlinks": [], "grade": [], "secrets": []}
    for line in path.read_text().splitlines():
        m = re.match(r"^// (\w+)(?:: (.*))?$", line)
        if not m:
            break
        key, value = m.group(1), (m.group(2) or "").replace("{ROOT}", str(ROOT))
        if key == "symlink":
            meta["symlinks"].append(tuple(v.strip() for v in value.split("->")))
        elif key == "grade":
            meta["grade"] += value.split()
        elif key == "secret":
            meta["secrets"].append(value)
        else:
            meta[key] = value if value else True
    return meta


def markers(folders: list) -> set:
    """Lines distinctive enough that finding one in an output means the file leaked."""
    public = set()
    for p in list((ROOT / "labs").rglob("*.cpp")) + list((ROOT / "tests").glob("[0-9][0-9]_*/*.cpp")):
        public |= {l.strip() for l in p.read_text(errors="replace").splitlines()}
    found = set()
    for folder in folders:
        for p in folder.rglob("*.cpp"):
            for line in p.read_text(errors="replace").splitlines():
                line = line.strip()
                if len(line) >= 40 and line not in public and not line.startswith("TEST_CASE"):
                    found.add(line)
    return found


def leftover_processes() -> list:
    """Processes a finished grade left behind. As root a grade runs submitted code under
    identities that name its grader's process id (identity() in tools/grader/sandbox.py): a process
    of an identity whose grader has ended is left behind, while other grades on the machine (with
    graders still running) are not counted. Without root, processes in a grade's folders."""
    left = []
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            uid = entry.stat().st_uid
            cmdline = Path(f"/proc/{entry.name}/cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if os.geteuid() == 0:
            if is_identity(uid) and not Path(f"/proc/{grader_of(uid)}").exists():
                left.append(f"{entry.name}: {cmdline[:80]}")
        elif "physlab-sandbox-" in cmdline or "physlab-grade-" in cmdline:
            left.append(f"{entry.name}: {cmdline[:80]}")
    return left


def digests(build: Path) -> dict:
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(build.glob("test_*"))
            if p.is_file()}


def tracked_state() -> str:
    """git's list of changed tracked files; stops the run where git cannot read the tree (an
    empty list before and after would pass the check while checking nothing)."""
    status = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=ROOT,
                            capture_output=True, text=True)
    if status.returncode != 0:
        why = (status.stderr.strip().splitlines() or [f"status {status.returncode}"])[0]
        hint = (f"; if you trust this folder: git config --global --add safe.directory {ROOT}"
                if "dubious ownership" in status.stderr else "")
        sys.exit(f"adversarial: git cannot read {ROOT} ({why}){hint}")
    return status.stdout


def run_case(path: Path, build: Path, solution_lines: set, hidden_lines: set) -> list:
    """Grades one case; returns what went wrong (empty when the grader held)."""
    meta = header(path)
    work = Path(tempfile.mkdtemp(prefix="physlab-adversarial-"))
    submission, out = work / "submission", work / "out"
    shutil.copytree(ROOT / "labs", submission / "labs")
    for link, target in meta["symlinks"]:
        path = submission / link
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        else:
            path.unlink()
        os.symlink(os.path.relpath(target, path.parent) if meta.get("relative") else target, path)
    if not meta["symlinks"]:
        code = path.read_text().replace("{ROOT}", str(ROOT))
        target = submission / meta["file"]
        target.write_text((target.read_text() + "\n" if meta["mode"] == "append" else "") + code)
    deadline = 120.0
    if "--deadline" in meta["grade"]:
        deadline = float(meta["grade"][meta["grade"].index("--deadline") + 1])
    args = ["--labs", meta["file"].split("/")[1][:2], "--deadline", str(deadline)] + meta["grade"]
    before, state = digests(build), tracked_state()
    start = time.monotonic()
    problems = []
    try:
        subprocess.run([str(ROOT / "physlab"), "grade", str(submission), "--out", str(out)] + args,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=deadline + 5 * SLACK)
    except subprocess.TimeoutExpired:
        problems.append("the grader did not finish")
    elapsed = time.monotonic() - start
    if elapsed > deadline + SLACK:
        problems.append(f"took {elapsed:.0f} s with a deadline of {deadline:.0f} s")
    try:
        results_text = (out / "results.json").read_text()
        results = json.loads(results_text)
        report_text = (out / "report.txt").read_text()
    except (OSError, ValueError) as error:
        problems.append(f"no valid results.json and report.txt: {error}")
        results, results_text, report_text = {}, "", ""
    if results.get("score", 0) != 0 or any(t.get("score", 0) != 0 for t in results.get("tests", [])):
        problems.append(f"earned {results.get('score')} points")
    time.sleep(3.0)
    if (out / "results.json").exists() and (out / "results.json").read_text() != results_text:
        problems.append("results.json changed after the grader finished")
    left = leftover_processes()
    if left:
        problems.append(f"processes left behind: {left[:3]}")
    if digests(build) != before:
        problems.append("the instructor's test executables changed")
    if tracked_state() != state:
        problems.append("tracked files of the instructor's tree changed")
    visible = results.get("output", "") + "".join(
        t.get("output", "") for t in results.get("tests", []) if t.get("visibility") != "after_published")
    everything = report_text + results_text
    for line in solution_lines:
        if line in everything:
            problems.append(f"a solution line leaked: {line[:60]}")
            break
    for line in hidden_lines:
        if line in visible:
            problems.append(f"a hidden test line leaked: {line[:60]}")
            break
    for secret in meta["secrets"]:
        if secret in everything:
            problems.append(f"'{secret}' leaked")
    if "\x1b" in everything:
        problems.append("an escape sequence reached the report")
    shutil.rmtree(work, ignore_errors=True)
    return problems


CONCURRENT_LABS = ["01", "03"]  # a lab with callbacks (handles) and one whose objects cross as state


def concurrent_grades(build: Path) -> list:
    """Two grades of the reference at once (two terminals, two courses on one machine) must score
    test for test as one grade alone: neither run's clean-up may reach the other's processes.
    Returns what went wrong."""
    work = Path(tempfile.mkdtemp(prefix="physlab-adversarial-"))
    submission = work / "submission"
    shutil.copytree(ROOT / "solutions", submission / "labs")

    def grade(out: str) -> subprocess.Popen:
        return subprocess.Popen([str(ROOT / "physlab"), "grade", str(submission), "--out", str(work / out),
                                 "--seed", "7", "--labs"] + CONCURRENT_LABS,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def scores(out: str) -> dict:
        try:
            data = json.loads((work / out / "results.json").read_text())
        except (OSError, ValueError) as error:
            return {"results.json": str(error)}
        return {t["name"]: t["score"] for t in data.get("tests", [])} | {"total": data.get("score")}

    problems = []
    alone = grade("alone")
    alone.wait()
    together = [grade("first"), grade("second")]
    codes = [p.wait() for p in together]
    expected = scores("alone")
    if alone.returncode != 0 or any(codes):
        problems.append(f"exit statuses: alone {alone.returncode}, together {codes}")
    for out in ("first", "second"):
        got = scores(out)
        differ = sorted(k for k in set(expected) | set(got) if expected.get(k) != got.get(k))
        if differ:
            problems.append(f"the {out} of two grades at once differs from a grade alone on {len(differ)} "
                            f"tests, e.g. {differ[0]}: {got.get(differ[0])} against {expected.get(differ[0])}")
    left = leftover_processes()
    if left:
        problems.append(f"processes left behind: {left[:3]}")
    shutil.rmtree(work, ignore_errors=True)
    return problems


def killed_compile() -> list:
    """A compile killed from outside (here: its cc1plus, SIGKILL) is a failure of the grading, not
    a score: the submission is "not graded", with why, and `grade` exits 3."""
    work = Path(tempfile.mkdtemp(prefix="physlab-adversarial-"))
    submission, out = work / "submission", work / "out"
    shutil.copytree(ROOT / "solutions", submission / "labs")
    source = submission / "labs" / "02_springs" / "implicit.cpp"
    source.write_text(source.read_text() + f"\n// {time.time_ns()}: new to the object cache\n")
    grade = subprocess.Popen([str(ROOT / "physlab"), "grade", str(submission), "--out", str(out), "--labs", "02"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    killed = False
    while grade.poll() is None and not killed:
        for entry in os.scandir("/proc"):
            try:
                cmdline = Path(f"/proc/{entry.name}/cmdline").read_bytes().split(b"\0")
            except OSError:
                continue
            if cmdline and cmdline[0].endswith(b"cc1plus") and b"-E" not in cmdline \
                    and any(a.endswith(b"implicit.cpp") for a in cmdline):
                os.kill(int(entry.name), signal.SIGKILL)
                killed = True
                break
        time.sleep(0.05)
    code = grade.wait()
    problems = [] if killed else ["the compile ended before it could be killed"]
    try:
        data = json.loads((out / "results.json").read_text())
    except (OSError, ValueError) as error:
        data = {}
        problems.append(f"no valid results.json: {error}")
    if killed and (code != 3 or "killed from outside" not in data.get("extra_data", {}).get("not_graded", "")):
        problems.append(f"grade exited {code} with {str(data)[:160]}, not 3 and 'not graded'")
    shutil.rmtree(work, ignore_errors=True)
    return problems


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", required=True, help="the instructor's build folder")
    parser.add_argument("--quick", action="store_true", help="only the cases marked quick (CI)")
    parser.add_argument("cases", nargs="*", help="case names (default: all)")
    args = parser.parse_args()
    cases = sorted(CASES.glob("*.cpp"))
    if args.cases:
        cases = [c for c in cases if c.stem in args.cases]
    if args.quick:
        cases = [c for c in cases if header(c).get("quick")]
    if not cases and (args.quick or not set(args.cases) & {"concurrent_grades", "killed_compile"}):
        raise SystemExit("adversarial: no such case")
    solution_lines = markers([ROOT / "solutions"])
    hidden_lines = markers([p for p in (ROOT / "tests" / "hidden").glob("[0-9][0-9]_*")])
    held = failed = 0
    for case in cases:
        start = time.monotonic()
        problems = run_case(case, Path(args.build).resolve(), solution_lines, hidden_lines)
        verdict = "held" if not problems else "BROKEN"
        print(f"{verdict:6} {case.stem:22} {time.monotonic() - start:5.0f} s  {header(case).get('adversarial', '')}")
        for p in problems:
            print(f"         {p}")
        held += not problems
        failed += bool(problems)
    checks = {"concurrent_grades": ("two grades of the reference at once score as one alone",
                                    lambda: concurrent_grades(Path(args.build).resolve())),
              "killed_compile": ("a compile killed from outside is 'not graded', and grade exits 3",
                                 killed_compile)}
    for name, (what, check) in checks.items():  # not submissions: the grading's own robustness
        if args.quick or (args.cases and name not in args.cases):
            continue
        start = time.monotonic()
        problems = check()
        print(f"{'held' if not problems else 'BROKEN':6} {name:22} {time.monotonic() - start:5.0f} s  {what}")
        for p in problems:
            print(f"         {p}")
        held += not problems
        failed += bool(problems)
    print(f"adversarial: {held} passed, {failed} failed")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
