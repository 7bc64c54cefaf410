#!/usr/bin/env python3
"""How long grading and the student's loop take here: `./physlab bench grade [--quick]`.

Times whole commands, as an instructor and a student meet them, on the reference's files:
  full, new     a grade of all six labs whose files are new to the grader's object cache (each
                file gets a comment of its own, so nothing compiled before is reused);
  full, cached  the same submission graded again (every object from the cache);
  one lab, new  a grade of Lab 5 alone, its files new;
  loop NN       `./physlab test NN --solutions` after one of the lab's files was saved (its time
                stamp renewed): the build recompiles that file and relinks, then the tests run;
                time to the first result line and to the end.
and, as the anchor measured in the same run, the least that work can take on this machine: the
lab files compiled directly, as many at a time as the grader compiles, with no sandbox and no
checks. Each figure is the median of several runs (one with --quick); the table goes to
charts/bench/grade.txt, and the goal lines (docs/grading.md, "Speed") end the output.
"""

import argparse
import concurrent.futures
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# The goals, in seconds on 2 cores (docs/grading.md, "Speed")
GOAL_FULL, GOAL_LAB, GOAL_LOOP = 30.0, 8.0, 10.0
RESULT_RE = re.compile(r"^\s*(PASS|FAIL|TODO|TIME|CRSH|COMP|NGRD|----)\b")


def stages() -> list:
    return sorted(p.name for p in (ROOT / "solutions").iterdir() if re.match(r"^\d\d_", p.name))


def salted_copy(into: Path, labs: list, salt: str) -> Path:
    """A repository-like copy holding labs/ with the reference's files of `labs`, each ending
    in a comment of its own: new to the grader's cache."""
    if into.exists():
        shutil.rmtree(into)
    for stage in labs:
        shutil.copytree(ROOT / "solutions" / stage, into / "labs" / stage)
        for f in (into / "labs" / stage).glob("*.cpp"):
            with open(f, "a") as out:
                out.write(f"// bench {salt} {f.name}\n")
    return into


def timed(cmd: list, env=None) -> tuple:
    """(seconds to the first result line or None, seconds to the end, output) of a command."""
    start, first, lines = time.monotonic(), None, []
    proc = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            errors="replace", env=env)
    for line in proc.stdout:
        if first is None and RESULT_RE.match(line):
            first = time.monotonic() - start
        lines.append(line)
    proc.wait()
    if proc.returncode not in (0, 1):
        sys.exit(f"bench grade: {' '.join(cmd)} ended with status {proc.returncode}:\n{''.join(lines[-20:])}")
    return first, time.monotonic() - start, "".join(lines)


def grade(submission: Path, out: Path, labs=()) -> float:
    cmd = ["./physlab", "grade", str(submission), "--out", str(out)]
    if labs:
        cmd += ["--labs", *labs]
    _, seconds, _ = timed(cmd)  # a submission not graded ends with status 3: timed() stops there
    return seconds


def loop(stage: str) -> tuple:
    """A save of the lab's largest file (the one a student spends longest in), then the lab's
    tests: (first result, whole) in seconds."""
    largest = max((ROOT / "solutions" / stage).glob("*.cpp"), key=lambda f: f.stat().st_size)
    os.utime(largest)
    first, whole, _ = timed(["./physlab", "test", stage[:2], "--solutions"])
    return first if first is not None else whole, whole


def anchor(jobs: int) -> float:
    """The reference's files compiled directly, `jobs` at a time, as the build compiles them."""
    toolchain = json.loads((ROOT / "build" / "grading" / "toolchain.json").read_text())
    base = [toolchain["compiler"], *toolchain["flags"].split(), "-I", toolchain["include"]]
    for d in toolchain["system_include"]:
        base += ["-isystem", d]
    files = sorted((ROOT / "solutions").glob("*/*.cpp"), key=lambda f: -f.stat().st_size)
    with tempfile.TemporaryDirectory(prefix="physlab-bench-") as work:
        def one(f: Path):
            subprocess.run(base + ["-c", str(f), "-o", f"{work}/{f.parent.name}-{f.stem}.o"], check=True)
        start = time.monotonic()
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            list(pool.map(one, files))
        return time.monotonic() - start


def median(runs: list) -> float:
    return statistics.median(runs)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="one run of each (CI); the goals need three")
    parser.add_argument("--runs", type=int, default=3, help="runs of each figure (default 3)")
    parser.add_argument("--out", type=Path, default=ROOT / "charts" / "bench", help="where grade.txt goes")
    args = parser.parse_args()
    runs = 1 if args.quick else args.runs
    if runs < 1:
        parser.error(f"--runs must be at least 1 (got {args.runs})")
    jobs = int(os.environ.get("PHYSLAB_JOBS") or os.cpu_count() or 2)
    labs = stages()
    figures = {}
    scratch = Path(tempfile.mkdtemp(prefix="physlab-bench-grade-"))
    try:
        print("bench grade: warm-up (a grade of every lab: the grading build and its precompiled headers)", flush=True)
        grade(salted_copy(scratch / "warm", labs, "warm"), scratch / "warm-out")
        full, cached, lab, anchors = [], [], [], []
        for r in range(runs):
            salt = f"{os.getpid()}-{time.time_ns()}-{r}"
            submission = salted_copy(scratch / "full", labs, salt)
            full.append(grade(submission, scratch / "full-out"))
            cached.append(grade(submission, scratch / "cached-out"))
            lab.append(grade(salted_copy(scratch / "lab", ["05_impulses"], salt), scratch / "lab-out", ["05"]))
            anchors.append(anchor(jobs))
            print(f"bench grade: run {r + 1} of {runs}: full {full[-1]:.1f} s, cached {cached[-1]:.1f} s, "
                  f"Lab 5 {lab[-1]:.1f} s, direct compile {anchors[-1]:.1f} s", flush=True)
        figures["full, files new"] = median(full)
        figures["full, files cached"] = median(cached)
        figures["Lab 5 alone, files new"] = median(lab)
        anchor_name = f"direct compile of the {len(list((ROOT / 'solutions').glob('*/*.cpp')))} files (anchor)"
        figures[anchor_name] = median(anchors)
        loops = {}
        for stage in labs:
            timings = [loop(stage) for _ in range(runs)]
            loops[stage] = (median([t[0] for t in timings]), median([t[1] for t in timings]))
            print(f"bench grade: loop {stage}: first result {loops[stage][0]:.1f} s, whole {loops[stage][1]:.1f} s",
                  flush=True)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    lines = [f"Grading and the student's loop, {jobs} processors, median of {runs} run(s) [s]", "",
             "| what | seconds | against the direct compile |", "|---|---|---|"]
    base = figures[anchor_name]
    lines += [f"| {what} | {s:.1f} | {s / base:.2f} |" for what, s in figures.items()]
    lines += ["", "| lab | save to first result | save to the end |", "|---|---|---|"]
    lines += [f"| {stage} | {first:.1f} | {whole:.1f} |" for stage, (first, whole) in loops.items()]
    text = "\n".join(lines) + "\n"
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "grade.txt").write_text(text)
    print(text)
    worst = max(loops, key=lambda s: loops[s][0])
    if args.quick:
        print("goals: measured by a full run only (three runs of each)")
    else:
        for what, ours, target in (("a full grade, files new", figures["full, files new"], GOAL_FULL),
                                   ("one lab's grade (Lab 5), files new", figures["Lab 5 alone, files new"], GOAL_LAB),
                                   (f"save to first result, slowest lab ({worst})", loops[worst][0], GOAL_LOOP)):
            print(f"goal: {what}: ours {ours:.1f} s, target {target:.0f} s, {'met' if ours <= target else 'not met'}")
    print(f"wrote {args.out / 'grade.txt'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
