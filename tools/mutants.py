#!/usr/bin/env python3
"""Mutation check of the graded tests: do they catch realistic student bugs?

Each tests/hidden/mutants/NN_name/<bug>.patch is a unified diff against a reference file in
solutions/NN_name, starting with a comment line "# <the bug>". For every patch this script
applies it to a scratch copy of the reference, builds the lab's test executables against that
copy (one build folder, configured once, so each mutant recompiles one file), and runs the lab's
graded tests, hidden ones included, with a few seeds. A mutant is *caught* when some graded test
that grades its file fails (as the grader links it: see grades()), *survived*
when all pass, and *invalid* when it does not apply or does not compile. Each visible graded test
that catches a mutant must also tell the student why: its failure shows at least one value (a
Catch2 expansion with a number, or an INFO/CAPTURE message) and the test has a hint in
tests/NN_name/hints.toml; the tests that do not are listed as *unexplained*. Called by
`./physlab mutants [NN...] [--only NAME...]`; see `mutants.py --help`.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
# The grader's reading of Catch2's report, its hint tables and its lab files' sections
from grader.common import section_files  # noqa: E402
from grader.failures import failures_in  # noqa: E402
from grader.hints import hint_table  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
MUTANTS = ROOT / "tests" / "hidden" / "mutants"
SOLUTIONS = ROOT / "solutions"
TARGET_RE = re.compile(r"^\+\+\+ b/solutions/(\d\d_[a-z0-9_]+/\S+)", re.MULTILINE)
OUTPUT_LIMIT = 1500  # characters of compiler or apply errors shown for an invalid mutant
NUMBER_RE = re.compile(r"(?<![\w.])\d")  # a number written in a check, not a digit of a name (v_3)


@dataclass
class Mutant:
    """One patch and what the graded tests made of it."""

    stage: str
    path: Path
    bug: str
    status: str = "not run"  # caught | survived | invalid
    detail: str = ""
    catchers: list = field(default_factory=list)
    unexplained: list = field(default_factory=list)  # visible catchers without a value or a hint

    @property
    def name(self) -> str:
        return f"{self.stage}/{self.path.stem}"

    @property
    def files(self) -> list:
        """Files the patch changes, relative to the labs folder (01_particles/forces.cpp)."""
        return TARGET_RE.findall(self.path.read_text())


def select_stages(wanted: list) -> list:
    """Stages with mutants matching the numbers or names given ('01', '1', '01_particles')."""
    if not MUTANTS.is_dir():
        sys.exit(f"mutants: no {MUTANTS} (the mutants live in the instructor's tree only)")
    stages = sorted(p.name for p in MUTANTS.iterdir() if p.is_dir())
    if not wanted:
        return stages
    chosen = []
    for w in wanted:
        matches = [s for s in stages if s == w or s[:2] == w.zfill(2)]
        if not matches:
            sys.exit(f"mutants: no mutants for '{w}' (labs with mutants: {' '.join(stages)})")
        chosen += [s for s in matches if s not in chosen]
    return chosen


def load_mutants(stages: list, only: list = ()) -> list:
    """The mutants of the stages; with `only`, those whose file name (without .patch) is listed."""
    mutants = []
    for stage in stages:
        for path in sorted((MUTANTS / stage).glob("*.patch")):
            if only and path.stem not in only:
                continue
            first = (path.read_text().splitlines() or [""])[0]
            bug = first[1:].strip() if first.startswith("#") else "(no description)"
            mutants.append(Mutant(stage, path, bug))
    return mutants


def sync_scratch(labs: Path) -> None:
    """Make the scratch labs folder an exact copy of solutions/, copying only what differs so
    that an unchanged file keeps its timestamp and is not recompiled."""
    for src in SOLUTIONS.rglob("*.cpp"):
        dst = labs / src.relative_to(SOLUTIONS)
        if not dst.exists() or dst.read_bytes() != src.read_bytes():
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(src, dst)  # a fresh timestamp: make rebuilds it


def restore(labs: Path, files: list) -> None:
    for rel in files:
        shutil.copyfile(SOLUTIONS / rel, labs / rel)


def apply_patch(labs: Path, patch: Path, check_only: bool = False) -> subprocess.CompletedProcess:
    # -p2 strips "a/solutions/". The ceiling keeps git from treating the scratch folder as part
    # of an enclosing repository, so paths are taken relative to it.
    env = dict(os.environ, GIT_CEILING_DIRECTORIES=str(labs.parent))
    return subprocess.run(["git", "apply", "-p2", *(["--check"] if check_only else []), str(patch)], cwd=labs,
                          env=env, capture_output=True, text=True)


def stale(mutants: list) -> list:
    """The mutants whose patch no longer applies to solutions/ (a reference changed under them),
    as "lab/name: git's message" lines; checked without building anything."""
    found = []
    for m in mutants:
        applied = apply_patch(SOLUTIONS, m.path, check_only=True)
        if applied.returncode != 0:
            found.append(f"{m.stage}/{m.path.name}: does not apply: {applied.stderr.strip()[:OUTPUT_LIMIT]}")
    return found


def configure(build: Path, labs: Path) -> None:
    if (build / "CMakeCache.txt").exists():
        return
    subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                    f"-DPHYSLAB_LABS_DIR={labs}"], check=True, stdout=subprocess.DEVNULL)


def test_targets(build: Path, stage: str) -> list:
    """The executables of the lab's graded tests built from the labs folder: test_NN_labs, and
    test_NN_hidden_labs where the build keeps the hidden tests apart."""
    listing = subprocess.run(["cmake", "--build", str(build), "--target", "help"],
                             capture_output=True, text=True, check=True).stdout
    names = set(re.findall(r"^\.\.\. (\S+)", listing, re.MULTILINE))
    return [t for t in (f"test_{stage}_labs", f"test_{stage}_hidden_labs") if t in names]


def build_targets(build: Path, targets: list, jobs: int) -> subprocess.CompletedProcess:
    return subprocess.run(["cmake", "--build", str(build), "--target", *targets, "-j", str(jobs)],
                          capture_output=True, text=True)


def failing_tests(build: Path, targets: list, stage: str, seed: int, timeout: float) -> list:
    """(name, tags, shows a value) of the lab's graded tests that fail with this seed; a crash or
    a hang counts as a failure of the whole run (named by what happened, tags None)."""
    failed = []
    for target in targets:
        failed += failing_in(build / target, stage, seed, timeout)
    return failed


def failing_in(exe: Path, stage: str, seed: int, timeout: float) -> list:
    cmd = [str(exe), f"[lab{stage[:2]}]", "-r", "xml", "--rng-seed", str(seed)]
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                              errors="replace")
    except subprocess.TimeoutExpired:
        return [(f"({exe.name} timed out after {timeout:g} s)", None, True)]
    try:
        tree = ET.fromstring(proc.stdout)
    except ET.ParseError:
        return [(f"({exe.name} crashed: exit status {proc.returncode})", None, True)]
    failed = [(case.get("name"), case.get("tags", ""), shows_value(case)) for case in tree.iter("TestCase")
              if case.find("OverallResult") is not None
              and case.find("OverallResult").get("success") != "true"]
    if not failed and proc.returncode != 0:
        failed = [(f"({exe.name} exit status {proc.returncode})", None, True)]
    return failed


def shows_value(case) -> bool:
    """Whether a failed test case (a node of Catch2's XML report) shows the student a value: a
    failed check whose expansion holds a number, an INFO/CAPTURE message in scope of a failure,
    or a failed check on inputs written out as numbers (refuse(f(0.5, -1))): the check's text
    is the value."""
    found = []
    failures_in(case, found)
    return any(notes or (what.endswith(") failed") and NUMBER_RE.search(expression))
               or any(d.startswith("actual: ") and re.search(r"\d", d) for d in details)
               for (_, expression), (what, _), details, notes in found)


def unexplained(stage: str, failed: list) -> list:
    """The visible tests among `failed` whose failure shows no value or that have no hint, as
    "test name: what is missing"."""
    hints = hint_table(stage, False)
    found = []
    for name, tags, value in failed:
        if tags is None or "[hidden]" in tags:
            continue
        missing = [what for what, ok in (("no value", value), ("no hint", name in hints)) if not ok]
        if missing:
            found.append(f"{name}: {', '.join(missing)}")
    return found


def grades(stage: str, tags, units: set) -> bool:
    """Whether a failing test costs the mutated files `units` points as the grader links it: a
    test of one file runs with the reference of the lab's other files (partial credit), a test of
    several with all of the student's; a crashed run (tags None) counts."""
    if tags is None:
        return True
    table = section_files(stage)
    graded = {table[int(n)] for n in re.findall(r"\[sec=(\d+)\]", tags) if int(n) in table}
    return len(graded) != 1 or bool(graded & units)


def check_reference(build: Path, targets: list, stage: str, seeds: list, jobs: int,
                    timeout: float) -> None:
    """The unmutated reference must pass every graded test, or no verdict means anything."""
    built = build_targets(build, targets, jobs)
    if built.returncode != 0:
        output = built.stdout + built.stderr
        sys.exit(f"mutants: the reference of {stage} does not build:\n{output[-OUTPUT_LIMIT:]}")
    for seed in seeds:
        failed = failing_tests(build, targets, stage, seed, timeout)
        if failed:
            sys.exit(f"mutants: the reference of {stage} fails with seed {seed}: "
                     f"{', '.join(name for name, _, _ in failed)}")


def judge(mutant: Mutant, build: Path, targets: list, labs: Path, seeds: list, jobs: int,
          timeout: float) -> None:
    applied = apply_patch(labs, mutant.path)
    if applied.returncode != 0:
        mutant.status, mutant.detail = "invalid", "does not apply: " + applied.stderr.strip()
        return
    try:
        built = build_targets(build, targets, jobs)
        if built.returncode != 0:
            output = built.stdout + built.stderr
            errors = "\n".join(l for l in output.splitlines() if "error" in l.lower())
            mutant.status = "invalid"
            mutant.detail = "does not build: " + (errors or output)[-OUTPUT_LIMIT:]
            return
        units = {Path(f).stem for f in mutant.files}
        for seed in seeds:
            failed = [(name, tags, value) for name, tags, value
                      in failing_tests(build, targets, mutant.stage, seed, timeout)
                      if grades(mutant.stage, tags, units)]
            if failed:
                mutant.status, mutant.catchers = "caught", [name for name, _, _ in failed]
                mutant.detail = f"seed {seed}"
                mutant.unexplained = unexplained(mutant.stage, failed)
                return
        mutant.status = "survived"
    finally:
        restore(labs, mutant.files)


def summary(mutants: list) -> str:
    lines = []
    for m in mutants:
        if m.status == "caught":
            more = f" (+{len(m.catchers) - 1} more)" if len(m.catchers) > 1 else ""
            lines.append(f"  caught    {m.name}: {m.detail}: {m.catchers[0]}{more}")
        elif m.status == "survived":
            lines.append(f"  SURVIVED  {m.name}: {m.bug}")
        else:
            lines.append(f"  INVALID   {m.name}: {m.detail}")
    offenders = {}  # test -> what it lacks, and the mutants it caught so
    for m in mutants:
        for line in m.unexplained:
            offenders.setdefault(f"{m.stage}: {line}", []).append(m.path.stem)
    if offenders:
        lines += ["", "UNEXPLAINED: visible tests that caught a mutant without showing a value or without a hint:"]
        lines += [f"  {test} (caught {', '.join(names)})" for test, names in sorted(offenders.items())]
    lines.append("")
    total_caught = total_valid = 0
    for stage in sorted({m.stage for m in mutants}):
        of_stage = [m for m in mutants if m.stage == stage]
        valid = [m for m in of_stage if m.status != "invalid"]
        caught = sum(m.status == "caught" for m in valid)
        total_caught, total_valid = total_caught + caught, total_valid + len(valid)
        invalid = len(of_stage) - len(valid)
        lines.append(f"{stage}: {caught}/{len(valid)} caught ({rate(caught, len(valid))})"
                     + (f", {invalid} invalid" if invalid else ""))
    lines.append(f"total: {total_caught}/{total_valid} caught ({rate(total_caught, total_valid)})"
                 + (f"; {len(offenders)} visible tests unexplained" if offenders else ""))
    return "\n".join(lines)


def rate(caught: int, valid: int) -> str:
    return f"{100.0 * caught / valid:.0f}%" if valid else "n/a"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("labs", nargs="*", help="labs to check: 01, 1 or 01_particles (default: all)")
    parser.add_argument("--build", type=Path, default=ROOT / "build-mutants",
                        help="build folder of its own, configured once (default: build-mutants)")
    parser.add_argument("--seeds", type=int, default=3,
                        help="run the tests with seeds 1..N; a mutant is caught by the first failing seed")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--timeout", type=float, default=300.0,
                        help="seconds one run of a lab's tests may take (a hang counts as caught)")
    parser.add_argument("--only", nargs="+", default=[], metavar="NAME",
                        help="only these mutants: patch names without .patch (impulse-sign ...)")
    parser.add_argument("--applies", action="store_true",
                        help="only check that every patch applies to solutions/ (seconds, no build)")
    args = parser.parse_args()

    stages = select_stages(args.labs)
    mutants = load_mutants(stages, args.only)
    unknown = sorted(set(args.only) - {m.path.stem for m in mutants})
    if unknown:
        sys.exit(f"mutants: no mutant named {', '.join(unknown)} in {' '.join(stages)}")
    if args.applies:
        problems = stale(mutants)
        print("\n".join(problems + [f"mutants: {len(mutants) - len(problems)} of {len(mutants)} patches apply"]))
        return 1 if problems else 0
    build = args.build.resolve()
    labs = build / "scratch" / "labs"
    seeds = list(range(1, args.seeds + 1))

    stages = [s for s in stages if any(m.stage == s for m in mutants)]
    sync_scratch(labs)
    configure(build, labs)
    for stage in stages:
        print(f"==> {stage}: checking the reference, then {sum(m.stage == stage for m in mutants)} mutants",
              file=sys.stderr, flush=True)
        targets = test_targets(build, stage)
        if not targets:
            sys.exit(f"mutants: the build in {build} has no test_{stage}_labs target")
        check_reference(build, targets, stage, seeds, args.jobs, args.timeout)
        for m in (m for m in mutants if m.stage == stage):
            judge(m, build, targets, labs, seeds, args.jobs, args.timeout)
            print(f"    {m.status:8s}  {m.name}", file=sys.stderr, flush=True)
    print(summary(mutants))
    return 1 if any(m.status == "invalid" or m.unexplained for m in mutants) else 0


if __name__ == "__main__":
    sys.exit(main())
