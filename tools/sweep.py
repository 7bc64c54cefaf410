#!/usr/bin/env python3
"""Seed sweep: every graded test of the chosen labs, visible and hidden, on the reference over
many seeds, each run as the grader runs it (tools/grader: own process, time limit, verdict
from the harness). Lists every failure with its seed and first failing line; exits 1 on any.

A seed reaches a test only through the test support's rng() (tests/support/support.cpp): no test
calls Catch::rngSeed(), std::rand() or a Catch generator. The first seed runs every test with
PHYSLAB_SEED_PROBE set, and rng() writes the name of each test that draws from it; the other
seeds run only those. A test that never draws does the same thing whatever the seed (until its
first draw nothing depends on the seed), so one run is all of its runs. Called by
`./physlab sweep`; see `sweep.py --help`.
"""

import argparse
import concurrent.futures
import copy
import os
import shutil
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
# The grader's listing and running of tests (tools/grader)
from grader.common import ROOT, Program, discover_stages, select_stages  # noqa: E402
from grader.report import SYMBOL  # noqa: E402
from grader.runner import Deadline, list_tests, run_one  # noqa: E402
from grader.sandbox import Sandbox  # noqa: E402
from grader.tree import executables  # noqa: E402

QUICK_SEEDS = 4  # --quick (CI): the first run of everything and 3 more seeds of the seeded tests


def first_line(case) -> str:
    """Where a failed run failed: its first failed check, else the first line of its output."""
    if case.checks:
        return case.checks[0]
    return next((line for line in case.output.splitlines() if line.strip()), case.status)


def run_all(sandbox, runs: list, timeout: float, scratch: Path, env: dict, failures: list) -> None:
    """Runs (exe, case, seed) triples, as many at a time as the sandbox has slots; appends each
    failed run to `failures` and prints it at once, and the count done every 5% (a long sweep
    shows how far it got)."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(sandbox.slots)) as pool:
        futures = {pool.submit(run_one, sandbox, Program(exe), copy.copy(case), seed, timeout,
                               Deadline(None), scratch, scratch, env): seed
                   for exe, case, seed in runs}
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            case, seed = future.result(), futures[future]
            if len(runs) >= 100 and done % (len(runs) // 20) == 0:
                print(f"sweep: {done} of {len(runs)} runs done (up to seed {seed})", flush=True)
            if not case.passed:
                failures.append((case, seed))
                print(f"FAIL lab {case.stage}, seed {seed}, {SYMBOL[case.status]}: {case.name}\n"
                      f"     {first_line(case)}", flush=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("labs", nargs="*", help="labs to sweep: 01, 1 or 01_particles (default: all)")
    parser.add_argument("--build", type=Path, required=True, help="the built tree (reference test executables)")
    parser.add_argument("--seeds", type=int, default=200, help="seeds per seeded test (default 200)")
    parser.add_argument("--first", type=int, default=1, help="the first seed (default 1): seeds first, first + 1, ...")
    parser.add_argument("--quick", action="store_true", help=f"{QUICK_SEEDS} seeds (CI)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2, help="tests run at once")
    parser.add_argument("--timeout", type=float, default=30.0, help="seconds per test run (default 30)")
    args = parser.parse_args()
    if args.quick:
        args.seeds = QUICK_SEEDS
    if args.seeds < 1:
        parser.error("--seeds must be at least 1")
    seeds = list(range(args.first, args.first + args.seeds))
    build = args.build.resolve()
    cases = []
    for stage in select_stages(discover_stages(ROOT), args.labs):
        for exe in executables(build, stage, "solutions"):
            if not exe.exists():
                print(f"sweep: {exe} was not built", file=sys.stderr)
                return 2
            cases += [(exe, c) for c in list_tests(exe, stage) if c.graded]
    sandbox = Sandbox(args.jobs, switch_user=False)  # the tree's own code: run it as we are
    scratch = Path(tempfile.mkdtemp(prefix="physlab-sweep-"))
    for slot in sandbox.slots:
        (scratch / f"home-{slot}").mkdir()
    probe = scratch / "seeded"
    probe.touch()
    failures = []
    try:
        print(f"sweep: {len(cases)} graded tests, seed {seeds[0]}, noting which draw from the seed", flush=True)
        run_all(sandbox, [(exe, c, seeds[0]) for exe, c in cases], args.timeout, scratch,
                {"PHYSLAB_SEED_PROBE": str(probe)}, failures)
        seeded_names = set(probe.read_text(encoding="utf-8", errors="replace").splitlines())
        seeded = [(exe, c) for exe, c in cases if c.name in seeded_names]
        if len(seeds) > 1:
            print(f"sweep: {len(seeded)} of them draw from the seed: seeds {seeds[1]}..{seeds[-1]}", flush=True)
            run_all(sandbox, [(exe, c, s) for s in seeds[1:] for exe, c in seeded], args.timeout, scratch, {},
                    failures)
    finally:
        sandbox.finish()
        shutil.rmtree(scratch, ignore_errors=True)
    runs = len(cases) + len(seeded) * (len(seeds) - 1)
    print(f"\nsweep: {runs} runs: {len(seeded)} seeded tests x {len(seeds)} seeds "
          f"({seeds[0]}..{seeds[-1]}), {len(cases) - len(seeded)} unseeded tests once")
    by_test = {}
    for case, seed in failures:
        by_test.setdefault((case.stage, case.name), []).append(seed)
    for (stage, name), failed in sorted(by_test.items()):
        total = len(seeds) if name in seeded_names else 1
        print(f"  lab {stage}: {name}: failed on {len(failed)} of {total} seeds: "
              f"{' '.join(map(str, sorted(failed)))}")
    print(f"sweep: {len(failures)} failed runs in {len(by_test)} tests" if failures else "sweep: no failure")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
