"""Grading a class: several submissions, each in a sandbox of its own, a few at a time with a
progress line after each, one not graded tried once more; a class split into shards graded on
several machines (`--shard I/N`) and joined again (`merge`); the class's tables and page.

Each submission's folder holds, beside its report, the record the class tables are made from
(RECORD), and each grade of a class the share it graded (SHARD): scores.csv, tests.csv and
class.html are always written from those files, so a merge of shards writes what one grade of the
whole class writes.
"""

import json
import os
import re
import shutil
import sys
import threading
import time
from pathlib import Path

from .common import StageResult, TestCase, write_atomically
from .grade import grade_one
from .kit import Kit
from .report import not_graded
from .sandbox import Sandbox

RECORD = "record.json"  # in each submission's folder: its tests' outcomes and grading time
SHARD = "shard.json"    # in a class grade's folder: which share of which class it graded
PROJECTED_CLASS = 500   # the class size whose grading time is projected from the CPU time measured


def csv_text(text: str) -> str:
    """Text for a field of scores.csv: no comma, quote or line break."""
    return re.sub(r'[,"\n\r]+', " ", text)[:200]


def grade_class(args, kit: Kit, sandboxes: list, out: Path, course) -> None:
    """Grades the submissions into out/<name>/, len(sandboxes) at a time, with a progress line
    after each; each folder gets its RECORD, from which write_class() makes the class's tables."""
    paths = [Path(p).absolute() for p in args.submissions]
    waiting = list(reversed(paths))
    graded, lock = [], threading.Lock()
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
            write_record(out / path.name, results, seconds)
            with lock:
                graded.append(path.name)
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


def shard_of(paths: list, shard) -> list:
    """The submissions of shard (i, n): the i-th of every n in the order of their folder names,
    so that every machine given the same class takes the same share whatever order it lists them."""
    if shard is None:
        return list(paths)
    i, n = shard
    return sorted(paths, key=lambda p: Path(p).name)[i - 1::n]


def write_record(folder: Path, results: list, seconds: float) -> None:
    """What the class tables need of one graded submission (its lab results), beside its report."""
    labs = [{"stage": r.stage, "tests": [{"name": t.name, "tags": t.tags, "status": t.status, "checks": t.checks,
                                          "course_points": t.course_points, "course_hidden": t.course_hidden}
                                         for t in r.tests]} for r in results]
    write_atomically(folder / RECORD, json.dumps({"seconds": round(seconds, 1), "labs": labs}, indent=1))


def load_record(folder: Path) -> tuple:
    """(results.json's data, lab results, seconds) of a graded submission's folder."""
    data = json.loads((folder / "results.json").read_text(encoding="utf-8"))
    record = json.loads((folder / RECORD).read_text(encoding="utf-8"))
    results = [StageResult(lab["stage"], [TestCase(lab["stage"], t["name"], t["tags"], status=t["status"],
                                                   checks=t["checks"], course_points=t["course_points"],
                                                   course_hidden=t["course_hidden"]) for t in lab["tests"]])
               for lab in record["labs"]]
    return data, results, record["seconds"]


def write_shard(out: Path, shard: tuple, course_name, names: list, cpu_seconds: float) -> None:
    write_atomically(out / SHARD, json.dumps({"shard": list(shard), "course": course_name,
                                              "submissions": sorted(names), "cpu_seconds": round(cpu_seconds, 1)},
                                             indent=1))


def projection(cpu_seconds: float, count: int) -> str:
    """The class's CPU time a submission, and what a class of PROJECTED_CLASS would take."""
    each = cpu_seconds / max(count, 1)
    hours = each * PROJECTED_CLASS / 3600
    cores = os.cpu_count() or 1
    return (f"CPU time: {each:.0f} s a submission; a class of {PROJECTED_CLASS}: {hours:.1f} core-hours, about "
            f"{hours / cores:.1f} h on one machine of {cores} cores like this one, {hours / cores / 8:.1f} h on 8 of them")


def write_class(out: Path, names: list, course_name, cpu_seconds: float) -> dict:
    """scores.csv, tests.csv and class.html of the submissions `names`, graded into out/<name>/,
    in the order of their names; returns {name: (data, results, seconds)}."""
    import class_report  # tools/class_report.py: only an instructor grading a class needs it
    graded = {name: load_record(out / name) for name in sorted(names)}
    rows = ["submission,score,max_score"]
    rows += [f"{name},not graded ({csv_text(not_graded(data))}),"
             if not_graded(data) else f"{name},{data['score']:g},{data['max_score']:g}"
             for name, (data, _, _) in graded.items()]
    write_atomically(out / "scores.csv", "\n".join(rows) + "\n")
    class_report.write(out, graded, course_name, projection(cpu_seconds, len(graded)))
    return graded


def merge_shards(folders: list, out: Path) -> tuple:
    """Joins the outputs of a class graded in shards: checks that they are every shard of one
    split of one class, copies each submission's folder into `out` and writes the class's tables
    there. Returns (graded, [problems]); nothing is written when there are problems."""
    problems, shards = [], []
    for folder in folders:
        try:
            shards.append((folder, json.loads((folder / SHARD).read_text(encoding="utf-8"))))
        except (OSError, ValueError) as error:
            problems.append(f"{folder}: not the output of a class grade ({SHARD}: {error})")
    if problems:
        return {}, problems
    splits = {meta["shard"][1] for _, meta in shards}
    courses = {meta["course"] for _, meta in shards if meta["submissions"]} or {None}  # an empty shard knows no course
    if len(splits) > 1:
        problems.append(f"the shards come from different splits (of {', '.join(map(str, sorted(splits)))})")
    if len(courses) > 1:
        problems.append(f"the shards were graded with different courses ({', '.join(map(str, courses))})")
    count = max(splits)
    seen = {}
    for folder, meta in shards:
        i = meta["shard"][0]
        if i in seen:
            problems.append(f"shard {i} of {count} twice: {seen[i]} and {folder}")
        seen[i] = folder
    problems += [f"shard {i} of {count} is missing" for i in range(1, count + 1) if i not in seen and len(splits) == 1]
    owner = {}
    for folder, meta in shards:
        for name in meta["submissions"]:
            if name in owner:
                problems.append(f"submission {name} is in two shards: {owner[name]} and {folder}")
            owner[name] = folder
            if not (folder / name / RECORD).is_file():
                problems.append(f"{folder / name}: no {RECORD} (graded by an older grader, or not finished)")
    if problems:
        return {}, problems
    out.mkdir(parents=True, exist_ok=True)
    for name, folder in owner.items():
        if (folder / name).resolve() != (out / name).resolve():
            shutil.copytree(folder / name, out / name, dirs_exist_ok=True)
    cpu = sum(meta["cpu_seconds"] for _, meta in shards)
    course_name = courses.pop()
    graded = write_class(out, list(owner), course_name, cpu)
    write_shard(out, (1, 1), course_name, list(owner), cpu)
    return graded, []
