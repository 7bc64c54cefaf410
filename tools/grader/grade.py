"""Grading one submission (grade_one()): every lab compiled, checked and linked (build_stage()),
visible tests before hidden ones in fresh homes, partial credit, and report.txt and results.json
always written, last and atomically.
"""

import concurrent.futures
import os
import shutil
import tempfile
import time
from pathlib import Path

from .build import Builder
from .common import OUTPUT_LIMIT, ROOT, GradingFailure, Program, StageResult, SubmissionError, graded_stages
from .isolation import Isolation
from .kit import Kit
from .objects import check_object, sandbox_notes
from .partial import link_own_files, second_chances, take_second_chances
from .report import failure_outputs, gradescope_json, not_graded_outputs, report, write_outputs
from .runner import Deadline, list_tests, run_cases
from .sandbox import Sandbox
from .submission import Submitted, find_labs, submitted_sources


def build_stage(builder: Builder, kit: Kit, labs: Submitted, result: StageResult, hidden: list,
                run_dir: Path):
    """Compiles, checks and links one stage. Returns its executables, {"tests": {unit: path},
    "hidden": {unit: path}} where unit None is every student file of the lab and a file's name its
    own executable (link_own_files), the visible ones copied to run_dir; or None when the lab did
    not compile or link."""
    stage = result.stage
    sources = submitted_sources(labs, stage, result.notes)
    stubs = {n: (ROOT / "labs" / stage / n).read_bytes() for n in sources}
    # A thread per file: each waits for a slot of the sandbox, which goes to the largest file
    # waiting in any lab (Sandbox.acquire())
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(sources) + len(stubs) or 1) as pool:
        done = dict(zip(sources, pool.map(lambda n: builder.compile(stage, n, sources[n]), sources)))
        stub_objs = dict(zip(stubs, pool.map(lambda n: builder.compile(stage, n, stubs[n], "stub-"), stubs)))
    errors = [c.error + ("\n" + c.log if c.log else "") for c in done.values() if c.error]
    if any(s.error for s in stub_objs.values()):
        raise GradingFailure(f"the instructor's stubs of {stage} did not compile here: "
                             f"{next(c.error for c in stub_objs.values() if c.error)}")
    if errors:
        result.compile_error = "\n".join(errors)
        return None
    stub_defined = kit.defined_by([str(s.obj) for s in stub_objs.values()])
    own_defined = kit.defined_by([str(c.obj) for c in done.values()])
    problems = []
    for name, c in done.items():
        problems += [f"{name}: {p}" for p in check_object(kit, stage, c.obj, stub_defined, own_defined)]
        if "checker" in kit.stages[stage]:
            result.notes += [f"{name}: {p}" for p in sandbox_notes(kit, stage, c.obj, own_defined)]
    if problems:
        result.compile_error = "refused:\n" + "\n".join(problems[:30])
        return None
    warnings = "\n".join(c.log for c in done.values() if c.log.strip())
    if warnings:
        result.notes.append("compiler warnings:\n" + warnings[-OUTPUT_LIMIT:])
    objects = {name[:-len(".cpp")]: c.obj for name, c in done.items()}
    if "checker" in kit.stages[stage]:
        return build_remote_stage(builder, kit, result, objects, hidden, run_dir)
    exe = builder.private / stage / f"test_{stage}"
    error = builder.link(stage, "tests", list(objects.values()), exe)
    if error:
        result.compile_error = error
        return None
    exes = {"tests": {None: exe}, "hidden": {}}
    if hidden:
        hidden_exe = builder.private / stage / f"test_{stage}_hidden"
        if builder.link(stage, "hidden", list(objects.values()), hidden_exe):
            for case in hidden:
                case.status, case.output = "not compiled", "the hidden tests did not link"
        else:
            exes["hidden"][None] = hidden_exe
    link_own_files(builder, kit, result, objects, exes)
    for unit, path in exes["tests"].items():
        exes["tests"][unit] = Program(runnable(path, run_dir))
    for unit, path in exes["hidden"].items():
        exes["hidden"][unit] = Program(path)
    return exes


def runnable(path: Path, run_dir: Path) -> Path:
    """A copy of `path` in the run folder, where the sandbox's identities may execute it."""
    copy = run_dir / path.name
    shutil.copyfile(path, copy)
    os.chmod(copy, 0o755)
    return copy


def build_remote_stage(builder: Builder, kit: Kit, result: StageResult, objects: dict, hidden: list,
                       run_dir: Path) -> dict:
    """build_stage() for a remote stage: the instructor's checkers run the tests, and the
    submitted objects are linked into a worker only, in the run folder. Partial credit is
    second_chances(): exes["alone"] names the files whose tests may run again."""
    stage, spec = result.stage, kit.stages[result.stage]
    worker = run_dir / f"worker_{stage}"
    error = builder.link(stage, "worker", list(objects.values()), worker)
    if error:
        result.compile_error = error
        return None
    os.chmod(worker, 0o755)
    checkers = {"tests": runnable(Path(spec["checker"]), run_dir)}
    if hidden and spec.get("checker_hidden"):
        checkers["hidden"] = Path(spec["checker_hidden"])  # copied to the run folder after the visible tests
    exes = {kind: {None: Program(checker, worker, batch=True)} for kind, checker in checkers.items()}
    exes.setdefault("hidden", {})
    reference = spec.get("reference", {})
    exes["alone"] = {unit: objects[unit] for unit in objects if unit in reference}
    return exes


def in_course(course, stage: str, cases: list) -> list:
    """The cases of the course (all without one), with the course's points and visibility."""
    if course is None:
        return cases
    kept = []
    for case in cases:
        test = course.test(stage, case.name)
        if test is not None:
            case.course_points, case.course_hidden = test.points, test.hidden and not case.hidden
            kept.append(case)
    return kept


def grade_one(args, kit: Kit, sandbox: Sandbox, submission: Path, out: Path, course=None,
              quiet: bool = False) -> tuple:
    """Grades one submission into `out`; returns (results.json's data, the lab results). Never
    raises: whatever the submission does, report.txt and results.json are written, last and
    atomically. `quiet`: no report on the terminal (a class prints a progress line instead)."""
    start = time.monotonic()
    deadline = Deadline(args.deadline)
    title = f"PhysLab grade of {submission.name}"
    private = Path(tempfile.mkdtemp(prefix="physlab-grade-"))
    shared = Path(tempfile.mkdtemp(prefix="physlab-sandbox-"))
    workers = len(sandbox.slots)
    results = []
    try:
        stages = graded_stages(args.labs, course)
        labs = find_labs(submission) if submission.is_dir() else None
        if labs is None:
            raise SubmissionError("no labs/ folder with NN_name stages in the submission")
        if sandbox.gid is not None:
            # Only this submission's sandbox users (its group) may enter: others graded at the same
            # time cannot reach its hidden tests
            os.chown(shared, 0, sandbox.gid)
            os.chmod(shared, 0o710)
        else:
            os.chmod(shared, 0o711)
        shutil.copytree(ROOT / "common" / "include", shared / "include")
        run_dir = shared / "run"
        run_dir.mkdir(mode=0o711)
        for path in [shared / "include"] + list((shared / "include").rglob("*")):
            os.chmod(path, 0o755 if path.is_dir() else 0o644)
        builder = Builder(kit, sandbox, private, shared, deadline, args.compile_timeout)
        remote = [stage for stage in stages if "checker" in kit.stages.get(stage, {})]
        if any("checker" in spec for spec in kit.stages.values()):
            sandbox.isolation = Isolation(kit, run_dir, sandbox)
        visible_jobs, hidden_jobs, plans = [], [], []
        for stage in stages:
            visible = in_course(course, stage, list_tests(kit.build / f"test_{stage}", stage))
            hidden_ref = kit.build / f"test_{stage}_hidden"
            hidden = in_course(course, stage, list_tests(hidden_ref, stage) if hidden_ref.exists() else [])
            if stage in remote:  # a framework test grades nothing, and its scenes are slow across the wire
                visible, hidden = [c for c in visible if c.graded], [c for c in hidden if c.graded]
            result = StageResult(stage, visible + hidden)
            if stage in remote:
                result.notes.append(sandbox.isolation.describe())
            plans.append((result, visible, hidden))
        # Every lab at once: their compiles share the sandbox's slots, so no slot waits for one
        # lab's last file while another lab's files are still to compile
        with concurrent.futures.ThreadPoolExecutor(max_workers=len(plans) or 1) as pool:
            built = list(pool.map(lambda plan: build_stage(builder, kit, labs, plan[0], plan[2], run_dir), plans))
        for (result, visible, hidden), exes in zip(plans, built):
            if exes is None:
                for case in result.tests:
                    case.status, case.output = "not compiled", result.compile_error[-OUTPUT_LIMIT:]
            else:
                visible_jobs += [(exes["tests"].get(c.unit, exes["tests"][None]), c) for c in visible]
                if None in exes["hidden"]:
                    hidden_jobs += [(exes["hidden"].get(c.unit, exes["hidden"][None]), c) for c in hidden]
            results.append(result)
        phases = {"build": time.monotonic() - start}  # seconds, in results.json's extra_data

        copies = {}  # a hidden checker -> its copy in the run folder

        def hidden_copies(jobs) -> list:
            moved = []
            for program, case in jobs:
                if program.exe.parent != run_dir and program.exe not in copies:
                    copies[program.exe] = runnable(program.exe, run_dir)
                moved.append((Program(copies.get(program.exe, program.exe), program.worker, program.batch), case))
            return moved

        make_homes(sandbox, shared)
        if all(program.batch for program, _ in visible_jobs + hidden_jobs):
            # Only checkers, which never load submitted code, and their workers, which can reach
            # no file, process or other worker: a hidden test's inputs cannot reach a visible
            # test's output, so both kinds run at once, hidden first (its few long tests then
            # overlap the many short visible ones)
            run_cases(sandbox, hidden_copies(hidden_jobs) + visible_jobs, args.seed, args.timeout, deadline,
                      private, shared, workers)
            phases["tests"] = time.monotonic() - start - sum(phases.values())
            chances = second_chances(builder, kit, plans, built, run_dir)
            if chances:
                run_cases(sandbox, hidden_copies([(p, fresh) for p, fresh, _ in chances]), args.seed,
                          args.timeout, deadline, private, shared, workers)
                take_second_chances(chances)
                phases["partial credit"] = time.monotonic() - start - sum(phases.values())
            sandbox.finish()
        else:
            # Every visible test first; hidden tests only after every process of those runs is
            # gone and their files removed, so no student process can carry a hidden test's text
            # into a visible output.
            run_cases(sandbox, visible_jobs, args.seed, args.timeout, deadline, private, shared, workers)
            phases["visible tests"] = time.monotonic() - start - sum(phases.values())
            sandbox.finish()
            make_homes(sandbox, shared)
            run_cases(sandbox, hidden_copies(hidden_jobs), args.seed, args.timeout, deadline, private, shared, workers)
            sandbox.finish()
            phases["hidden tests"] = time.monotonic() - start - sum(phases.values())
        ungraded = [c for r in results for c in r.tests if c.status == "not graded"]
        if ungraded:
            raise GradingFailure(f"{len(ungraded)} tests could not start the sandbox of the submitted "
                                 f"code ({ungraded[0].output or ungraded[0].name})")
        text = report(results, args.seed, title)
        data = gradescope_json(results, time.monotonic() - start)
        data["extra_data"] = {"seconds": {k: round(v, 2) for k, v in phases.items()}}
        write_outputs(out, text, data)
    except SubmissionError as error:  # the submission's own fault: a score of 0 that says why
        sandbox.finish()
        text = f"{title}\n\nGRADING FAILED: {error}"
        data = failure_outputs(out, title, str(error), time.monotonic() - start)
        results = []
    except Exception as error:  # the grading's own failure is never a score; a report is still written
        try:
            sandbox.finish()
        except Exception as cleanup:
            error = f"{error}; then, ending the sandbox: {cleanup}"
        why = str(error) if isinstance(error, GradingFailure) else f"the grader failed: {type(error).__name__}: {error}"
        text = f"{title}\n\nNOT GRADED: {why}"
        data = not_graded_outputs(out, title, why, time.monotonic() - start)
        results = []
    finally:
        shutil.rmtree(private, ignore_errors=True)
        shutil.rmtree(shared, ignore_errors=True)
    if not quiet:
        print(text)
        print(f"\nwrote {out / 'report.txt'} and {out / 'results.json'}")
    return data, results


def make_homes(sandbox: Sandbox, shared: Path) -> None:
    """Fresh, empty working folders for the sandbox users (finish() removes their files)."""
    for slot in sandbox.slots:
        home = shared / f"home-{slot}"
        shutil.rmtree(home, ignore_errors=True)
        home.mkdir(mode=0o700)
        if sandbox.ids(slot):
            os.chown(home, *sandbox.ids(slot))
