#!/usr/bin/env python3
"""A made-up class to try the grader's class report on: submissions built from the reference with
realistic bugs (the mutants of tests/hidden/mutants), as students hand them in.

    make_class.py OUT [--count N] [--labs 01 02 ...] [--seed S]

writes OUT/student-01 ... OUT/student-N, each a repository copy holding labs/NN_name/*.cpp: per
lab, the reference with one to three mutants applied (most students), the reference untouched (a
few), the stubs (a lab not started) or a file that does not compile. The same seed gives the same
class. Instructors only: it reads solutions/ and the mutant catalogue.
"""

import argparse
import random
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MUTANTS = ROOT / "tests" / "hidden" / "mutants"
STAGE_RE = re.compile(r"^\d\d_[a-z0-9_]+$")


def lab_stages(wanted: list) -> list:
    stages = sorted(p.name for p in (ROOT / "solutions").iterdir() if STAGE_RE.match(p.name))
    if not wanted:
        return stages
    chosen = [s for s in stages if any(s == w or (w.isdigit() and s[:2] == w.zfill(2)) for w in wanted)]
    if len(chosen) != len(wanted):
        sys.exit(f"make_class: unknown lab in {wanted} (labs: {', '.join(stages)})")
    return chosen


def apply(patch: Path, labs: Path) -> bool:
    """Applies a mutant (a diff against solutions/NN_name/file.cpp) to the submission's labs/."""
    proc = subprocess.run(["patch", "-s", "-p2", "-d", str(labs), "-i", str(patch)],
                          capture_output=True, text=True)
    return proc.returncode == 0


def make(out: Path, count: int, stages: list, seed: int) -> list:
    rng = random.Random(seed)
    made = []
    for n in range(1, count + 1):
        sub = out / f"student-{n:02d}"
        labs = sub / "labs"
        bugs = []
        for stage in stages:
            shutil.copytree(ROOT / "solutions" / stage, labs / stage)
            roll = rng.random()
            if roll < 0.08:
                shutil.rmtree(labs / stage)
                shutil.copytree(ROOT / "labs" / stage, labs / stage)
                bugs.append(f"{stage}: not started (the stubs)")
            elif roll < 0.12:
                victim = rng.choice(sorted((labs / stage).glob("*.cpp")))
                victim.write_text(victim.read_text() + "\nint unfinished(  // the student's last edit\n")
                bugs.append(f"{stage}: {victim.name} does not compile")
            elif roll < 0.22:
                bugs.append(f"{stage}: the reference")
            else:
                patches = sorted((MUTANTS / stage).glob("*.patch"))
                for patch in rng.sample(patches, min(len(patches), rng.choice((1, 1, 2, 3)))):
                    if apply(patch, labs):
                        bugs.append(f"{stage}: {patch.stem}")
        (sub / "BUGS.txt").write_text("\n".join(bugs) + "\n")
        made.append((sub.name, bugs))
    return made


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="a new folder for the class")
    parser.add_argument("--count", type=int, default=20)
    parser.add_argument("--labs", nargs="*", default=[])
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    out = Path(args.out)
    if out.exists():
        sys.exit(f"make_class: {out} exists; choose a new folder")
    if args.count < 1:
        sys.exit("make_class: --count must be at least 1")
    for name, bugs in make(out, args.count, lab_stages(args.labs), args.seed):
        print(f"{name}: {'; '.join(bugs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
