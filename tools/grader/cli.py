"""The grader's commands and their options: `run` (./physlab test), `grade` (one submission, a
class or a shard of one), `merge` (a class's shards), `gradescope` (the zip) and `stages` (the
labs a grade builds).
"""

import argparse
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

import course as course_file  # tools/course.py, beside the package

from . import __doc__ as GRADER_DOC
from .classes import SHARD, grade_class, merge_shards, projection, shard_of, write_class, write_shard
from .common import ROOT, Program, StageResult, discover_stages, graded_stages, select_stages
from .grade import grade_one
from .gradescope import cmd_gradescope
from .hints import hint_problems, tag_problems
from .kit import Kit
from .objects import refusals_ahead
from .report import failure_outputs, gradescope_json, not_graded, report, summary_line, test_line, write_outputs
from .runner import Deadline, list_tests, run_cases
from .sandbox import Sandbox, make_private
from .submission import submission_problems
from .tree import course_points, executables, own_file_executable, remote_pairs, stub_check

EXIT_NOT_GRADED = 3  # `grade`'s status when a submission was not graded (its outputs say why)


def cmd_run(args) -> int:
    """Run already built tests; print the report; optionally write results.json."""
    start = time.monotonic()
    build = Path(args.build).resolve()
    stages = select_stages(discover_stages(ROOT), args.labs)
    sandbox = Sandbox(args.jobs, switch_user=False)  # the tree's own code: run it as we are
    if args.timeout is None:
        args.timeout = course_file.DEFAULT_LIMITS["test"]
    scratch = Path(tempfile.mkdtemp(prefix="physlab-test-"))
    results, jobs = [], []
    kit = None
    if args.variant == "labs" and args.expect != "fail" and (build / "grading" / "toolchain.json").exists():
        kit = Kit(build)
    for stage in stages:
        result = StageResult(stage)
        result.notes += refusals_ahead(kit, stage)
        for exe in executables(build, stage, args.variant):
            if not exe.exists():
                result.compile_error += f"{exe.name} was not built\n"
                continue
            cases = course_points(stage, list_tests(exe, stage))
            result.tests += cases
            jobs += [(Program(own_file_executable(exe, c), batch=True), c) for c in cases]
        results.append(result)
    if args.variant == "solutions":
        jobs += remote_pairs(build, stages, sandbox, scratch, results)
    if args.variant == "solutions" and (build / "test_common").exists():
        common = StageResult("common", list_tests(build / "test_common", "common"))
        jobs += [(Program(build / "test_common", batch=True), c) for c in common.tests]
        results.append(common)
    for slot in sandbox.slots:
        (scratch / f"home-{slot}").mkdir()
    # Each test's line as soon as its batch ends (the student's loop sees its first results
    # while the rest run); the report after them leaves the passes out
    live = args.expect != "fail"
    labels = {id(t): f"lab {r.stage}{r.how}" for r in results for t in r.tests}

    def finished(cases: list) -> None:
        for t in cases:
            print(f"{test_line(t)}  ({labels[id(t)]})")
        sys.stdout.flush()

    try:
        run_cases(sandbox, jobs, args.seed, args.timeout, Deadline(None), scratch, scratch, args.jobs,
                  finished if live else None)
    finally:
        sandbox.finish()
        shutil.rmtree(scratch, ignore_errors=True)
    title = f"PhysLab tests against {args.variant}/"
    text = report(results, args.seed, title)
    mistagged = [f"TAG: {p}" for p in tag_problems(results)] + [f"HINT: {p}" for p in hint_problems(stages)] \
        if args.variant == "solutions" else []
    if args.out:
        write_outputs(Path(args.out), text, gradescope_json(results, time.monotonic() - start))
    if args.expect == "fail":
        passed, failed = stub_check(results)
    else:
        print("\n" + report(results, args.seed, title, passes=False))
        passed, failed = summary_line(results)
        print(f"\n{passed} passed, {failed} failed")
    for problem in mistagged:
        print(f"  {problem}")
    failed += len(mistagged)
    if args.summary:  # the graded tests once: a checker's second run of a lab's tests is not counted again
        graded = [t for r in results if not r.how for t in r.tests if t.graded]
        graded_passed = sum(t.passed for t in graded)
        Path(args.summary).write_text(f"{passed} {failed} {len(graded)} {graded_passed}\n")
    return 0 if failed == 0 else 1


def limits_of(args, course) -> None:
    """The time limits: the command line's, else the course file's, else the defaults."""
    limits = course.limits if course is not None else course_file.DEFAULT_LIMITS
    for option, key in (("deadline", "deadline"), ("timeout", "test"), ("compile_timeout", "compile")):
        if getattr(args, option) is None:
            setattr(args, option, limits[key])


def cmd_grade(args) -> int:
    """Grade one submission into --out, or several (a class, in parallel) into --out/<name>/ plus
    scores.csv, tests.csv and class.html. The course file and the submissions are checked before
    anything is graded."""
    out = Path(args.out).resolve()
    problems = submission_problems(args.submissions)
    if args.shard:
        # The same share whichever machine grades it: a class is always graded into out/<name>/
        args.submissions = shard_of(args.submissions, args.shard)
        if not args.submissions and not problems:
            i, n = args.shard
            out.mkdir(parents=True, exist_ok=True)
            write_shard(out, args.shard, None, [], 0.0)
            print(f"grader: shard {i}/{n} has no submission (fewer submissions than shards)")
            return 0
    course = None
    if args.course:
        try:
            course = course_file.load(args.course)
        except course_file.CourseError as error:
            problems.insert(0, f"course file {error}")
    if course is not None and args.labs:
        wanted = select_stages(discover_stages(ROOT), args.labs)
        problems += [f"--labs {s}: lab {s} is not in the course {args.course}" for s in wanted if s not in course.labs]
    if problems:
        for problem in problems:
            print(f"grader: {problem}", file=sys.stderr)
        if len(args.submissions) == 1 and not args.shard:  # Gradescope: the student's result says why
            failure_outputs(out, f"PhysLab grade of {Path(args.submissions[0]).name}",
                            "; ".join(problems), 0.0)
        print("grader: nothing graded", file=sys.stderr)
        return 2
    limits_of(args, course)
    out.mkdir(parents=True, exist_ok=True)
    single = len(args.submissions) == 1 and not args.shard
    # A class is graded several submissions at once, each with sandbox users of its own; as the
    # current user (not root) nothing keeps two submissions' processes apart: one at a time.
    root = os.geteuid() == 0
    parallel = 1 if single or not root else max(1, min(len(args.submissions), os.cpu_count() or 1, args.jobs))
    jobs_each = max(1, args.jobs // parallel)
    sandboxes = [Sandbox(jobs_each, switch_user=True, first=k * jobs_each,
                         group=None if single else 255 - k) for k in range(parallel)]
    if sandboxes[0].root:
        for path in (ROOT, Path(args.build).resolve(), out):
            make_private(path)
    try:
        kit = Kit(Path(args.build).resolve())
        kit.require_notary()
    except Exception as error:  # no usable instructor build: every submission still gets its files
        for sub_path in args.submissions:
            target = out if single else out / Path(sub_path).absolute().name
            failure_outputs(target, f"PhysLab grade of {Path(sub_path).name}", str(error), 0.0)
        print(f"grader: {error}", file=sys.stderr)
        return 1
    if course is not None:
        print(course.summary())
    if single:
        data, _ = grade_one(args, kit, sandboxes[0], Path(args.submissions[0]).absolute(), out, course)
        if not_graded(data):
            print(f"grader: not graded: {not_graded(data)}", file=sys.stderr)
            return EXIT_NOT_GRADED
        return 0
    used = os.times()
    grade_class(args, kit, sandboxes, out, course)
    done = os.times()
    cpu = sum(b - a for a, b in zip(used[:4], done[:4]))  # this process and every child it waited for
    names = [Path(p).absolute().name for p in args.submissions]
    course_name = course.name if course is not None else None
    graded = write_class(out, names, course_name, cpu)
    write_shard(out, args.shard or (1, 1), course_name, names, cpu)
    return class_summary(out, graded, f"{parallel} at a time", cpu)


def class_summary(out: Path, graded: dict, how: str, cpu: float) -> int:
    """Prints each submission's score and time, the class's times, where its tables are, and the
    submissions not graded; returns grade's exit status."""
    for name, (data, _, seconds) in graded.items():
        score = f"not graded ({not_graded(data)})" if not_graded(data) else f"{data['score']:g},{data['max_score']:g}"
        print(f"{name},{score}  ({seconds:.0f} s)")
    times = [seconds for _, _, seconds in graded.values()]
    print(f"{len(times)} submissions, {how}: {sum(times) / len(times):.0f} s each on "
          f"average (slowest {max(times):.0f} s)")
    print(projection(cpu, len(times)))
    print(f"wrote {out / 'scores.csv'}, {out / 'tests.csv'} and {out / 'class.html'}")
    failed = [name for name, (data, _, _) in graded.items() if not_graded(data)]
    if failed:
        print(f"grader: {len(failed)} not graded (tried twice): {', '.join(failed)}", file=sys.stderr)
        return EXIT_NOT_GRADED
    return 0


def cmd_merge(args) -> int:
    """Joins the outputs of a class graded in shards (grade --shard I/N on several machines) into
    --out: each submission's folder, and scores.csv, tests.csv and class.html as one grade of the
    whole class writes them."""
    out = Path(args.out).resolve()
    graded, problems = merge_shards([Path(f).resolve() for f in args.shards], out)
    if problems:
        for problem in problems:
            print(f"grader: merge: {problem}", file=sys.stderr)
        print("grader: merge: nothing written", file=sys.stderr)
        return 2
    if not graded:
        print("grader: merge: the shards hold no submission", file=sys.stderr)
        return 2
    cpu = json.loads((out / SHARD).read_text())["cpu_seconds"]
    return class_summary(out, graded, f"merged from {len(args.shards)} shards", cpu)


def cmd_stages(args) -> int:
    """The labs `grade` with the same --labs and --course needs built: a bad lab or course file
    falls back to every lab, so that the grade itself refuses it with its own message."""
    every = discover_stages(ROOT)
    try:
        chosen = graded_stages(args.labs, course_file.load(args.course) if args.course else None)
    except (SystemExit, course_file.CourseError):
        chosen = every
    print("\n".join(chosen or every))
    return 0


class Parser(argparse.ArgumentParser):
    """Option errors in one line that names the option and the value, without the grader's
    internal usage (people meet it through ./physlab, whose --help is theirs)."""

    def error(self, message):
        self.exit(2, f"physlab: {self.prog.split()[-1]}: {message}\n")


def whole_number(text: str) -> int:
    if not text.isdigit():
        raise argparse.ArgumentTypeError(f"needs a whole number (e.g. 42), got '{text}'")
    return int(text)


def shard_spec(text: str) -> tuple:
    i, _, n = text.partition("/")
    if not (i.isdigit() and n.isdigit() and 1 <= int(i) <= int(n)):
        raise argparse.ArgumentTypeError(f"needs I/N with 1 <= I <= N (e.g. 2/4), got '{text}'")
    return int(i), int(n)


def seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = 0.0
    if not value > 0:
        raise argparse.ArgumentTypeError(f"needs a positive number of seconds, got '{text}'")
    return value


def main() -> int:
    parser = Parser(description=GRADER_DOC, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    common = Parser(add_help=False)
    common.add_argument("--labs", nargs="*", default=[], help="lab numbers or names (default: all)")
    common.add_argument("--seed", type=whole_number, default=int.from_bytes(os.urandom(3), "big"),
                        help="Catch2 --rng-seed for every test (default: random, printed)")
    common.add_argument("--timeout", type=seconds, default=None,
                        help="seconds per test case (default 30, or the course file's; the slowest "
                             "reference test takes about 1 s)")
    common.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    run = sub.add_parser("run", parents=[common], help="run built tests and report")
    run.add_argument("--build", required=True, help="the CMake build folder")
    run.add_argument("--variant", choices=["solutions", "labs"], default="labs")
    run.add_argument("--out", help="also write report.txt and results.json here")
    run.add_argument("--expect", choices=["pass", "fail"], default="pass",
                     help="fail: the stub check (every graded test must fail, not implemented)")
    run.add_argument("--summary", help="write 'passed failed' counts to this file")
    run.set_defaults(func=cmd_run)
    grade = sub.add_parser("grade", parents=[common], help="grade submissions")
    grade.add_argument("submissions", nargs="+", metavar="SUBMISSION",
                       help="a student's labs/ folder or a copy of the repo (several: one folder each)")
    grade.add_argument("--out", required=True,
                       help="folder for report.txt and results.json (several: DIR/<name>/ and scores.csv)")
    grade.add_argument("--build", required=True, help="the instructor's built tree")
    grade.add_argument("--deadline", type=float, default=None,
                       help="seconds for the whole grade of one submission (default 540, or the "
                            "course file's; Gradescope allows 600)")
    grade.add_argument("--compile-timeout", type=float, default=None,
                       help="seconds to compile one lab file (default 120, or the course file's)")
    grade.add_argument("--course", help="the course file (the Grading page): its labs, sections, "
                                        "points, hidden tests and time limits")
    grade.add_argument("--shard", type=shard_spec, default=None, metavar="I/N",
                       help="grade the I-th of N shares of the submissions (by name), into DIR/<name>/, "
                            "for `merge` to join")
    grade.set_defaults(func=cmd_grade)
    merge = sub.add_parser("merge", help="join the outputs of a class graded in shards")
    merge.add_argument("shards", nargs="+", metavar="SHARD", help="each shard's --out folder")
    merge.add_argument("--out", required=True, help="the class's folder (may be one of the shards' parent)")
    merge.set_defaults(func=cmd_merge)
    package = sub.add_parser("gradescope", help="write the Gradescope autograder zip")
    package.add_argument("--out", required=True, help="the zip file to write")
    package.add_argument("--course", help="the course file the zip grades with (physlab/course.toml)")
    package.set_defaults(func=cmd_gradescope)
    stages = sub.add_parser("stages", help="the labs a grade with these arguments builds, one per line "
                                           "(every lab when they name none or cannot be read)")
    stages.add_argument("--labs", nargs="*", default=[])
    stages.add_argument("--course")
    stages.set_defaults(func=cmd_stages)
    args, unknown = parser.parse_known_args()
    if unknown and args.command != "stages":
        parser.error("unrecognized arguments: " + " ".join(unknown))
    return args.func(args)
