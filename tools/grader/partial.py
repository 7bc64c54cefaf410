"""Partial credit: a test of one lab file runs again with that file and the reference's objects of
the lab's other files (link_own_files(), and second_chances() in a remote lab), so a finished file
earns its points whatever else is unwritten.
"""

import concurrent.futures
import os
import re
from pathlib import Path

from .build import Builder
from .common import Program, StageResult, TestCase
from .kit import Kit


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
