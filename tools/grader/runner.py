"""Running tests: listing an executable's test cases, running them in the sandbox one per process
or in batches, and each test's verdict from the notary's authenticated line (judge()) or its
batch's records, within a per-test time limit and the grade's Deadline.
"""

import concurrent.futures
import hmac
import os
import re
import secrets
import select
import shutil
import signal
import subprocess
import tempfile
import time
import xml.etree.ElementTree as ET
from pathlib import Path

from .common import OUTPUT_FILE_LIMIT, OUTPUT_LIMIT, TEST_MEMORY, Program, TestCase, read_capped
from .failures import describe_failure
from .sandbox import Sandbox, kill_group


def escape_spec(name: str) -> str:
    """A test name as a Catch2 test spec that matches exactly that test."""
    return re.sub(r'([\\,\[\]*"~])', r"\\\1", name)


def list_tests(exe: Path, stage: str) -> list:
    """The test cases of an instructor-built executable, from its --physlab-list."""
    listing = subprocess.run([str(exe), "--physlab-list"], capture_output=True, timeout=60,
                             check=True).stdout.decode("ascii", errors="replace")
    cases = []
    for line in listing.splitlines():
        name_hex, _, tags = line.partition("\t")
        cases.append(TestCase(stage=stage, name=bytes.fromhex(name_hex).decode("utf-8", "replace"),
                              tags=[t for t in tags.split(",") if t]))
    return cases


class Deadline:
    """The time left for grading; None means no overall limit."""

    def __init__(self, seconds):
        self.end = None if seconds is None else time.monotonic() + seconds

    def left(self) -> float:
        return float("inf") if self.end is None else self.end - time.monotonic()


def run_one(sandbox: Sandbox, program: Program, case: TestCase, seed: int, timeout: float,
            deadline: Deadline, scratch: Path, homes: Path, env=None) -> TestCase:
    """Runs one test case in homes/home-<slot>, its output and verdict files in the private
    `scratch`, with `env` added to its environment; its status comes from the harness's
    authenticated verdict."""
    budget = min(timeout, deadline.left())
    if budget <= 1.0:
        case.status, case.output = "not run", "not run: the grading deadline was reached"
        return case
    slot = sandbox.acquire()
    try:
        run_sandboxed_test(sandbox, slot, program, case, seed, budget, scratch, homes, env)
    except Exception as error:  # an error of the grader's own costs this test, not the grade
        case.status, case.output = "crashed", f"the grader could not run this test: {error}"
    finally:
        sandbox.release(slot)
    return case


def run_sandboxed_test(sandbox: Sandbox, slot: int, program: Program, case: TestCase, seed: int,
                       budget: float, scratch: Path, homes: Path, env=None) -> None:
    key = secrets.token_hex(32)
    work = Path(tempfile.mkdtemp(dir=scratch, prefix="test-"))
    home = homes / f"home-{slot}"
    try:
        read_end, write_end = os.pipe()
        os.write(write_end, key.encode())
        os.close(write_end)
        out_fd = os.open(work / "output", os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
        verdict_fd = os.open(work / "verdict", os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
        cmd = [str(program.exe), escape_spec(case.name), "-r", "xml", "--rng-seed", str(seed)]
        variables = {**(env or {}), "PHYSLAB_VERDICT": f"{read_end}:{verdict_fd}:{case.name.encode('utf-8').hex()}"}
        if program.worker is not None:
            variables.update(sandbox.isolation.environment(program.worker))
        try:
            code, case.seconds = sandbox.run(
                cmd, slot=slot, cwd=home, timeout=budget, memory=TEST_MEMORY, stdout=out_fd,
                pass_fds=(read_end, verdict_fd), extra_env=variables)
        finally:
            for fd in (read_end, out_fd, verdict_fd):
                os.close(fd)
        judge(case, code, budget, key, read_capped(work / "verdict", 1 << 16),
              read_capped(work / "output"))
    finally:
        shutil.rmtree(work, ignore_errors=True)


# How the harness's child ends (tests/support/runner.cpp, Outcome): only 0 is a pass.
NOT_GRADED = 5  # a remote test whose worker could not be started: the grading failed, not the code
OUTCOMES = {1: None, 3: "the test ran but asserted nothing",
            4: "the harness ran other test cases than this one"}


def judge(case: TestCase, code, budget: float, key: str, verdicts: str, output: str) -> None:
    """Sets the case's status from the notary's line carrying this run's key: passed only when the
    process that ran the test exited with status 0 (exactly this test ran, asserted something and
    failed nothing). The test's output only explains a failure."""
    verdict = None
    for line in verdicts.splitlines():
        parts = line.split(" ")
        if len(parts) == 4 and parts[0] == "physlab-verdict" and hmac.compare_digest(parts[1], key) \
                and parts[2] in ("exit", "signal") and parts[3].isdigit():
            verdict = (parts[2], int(parts[3]))
    status, detail, case.checks, case.captured = describe_failure(output)
    if code is None:
        case.status = "timed out"
        case.output = f"killed after {budget:.3g} s" + (f"\n{detail}" if detail else "")
        return
    if verdict == ("exit", 0):
        case.status, case.output = "passed", ""
        return
    if verdict == ("exit", NOT_GRADED):
        case.status, case.output = "not graded", output.strip().splitlines()[-1][:OUTPUT_LIMIT] if output.strip() else ""
        return
    if verdict is not None and verdict[0] == "signal":
        number = verdict[1]
        name = signal.Signals(number).name if number in signal.Signals._value2member_map_ else str(number)
        why = " (output limit exceeded)" if number == signal.SIGXFSZ else ""
        case.status = "crashed"
        case.output = f"crashed ({name}){why}" + (f"\n{detail}" if detail else "")
        return
    if verdict is not None and verdict[1] in OUTCOMES:
        if OUTCOMES[verdict[1]]:
            status, detail = "failed", OUTCOMES[verdict[1]] + (f"\n{detail}" if detail else "")
    elif verdict is not None:
        status, detail = "crashed", f"the test process ended (exit code {verdict[1]}) without a verdict"
    else:
        status, detail = "crashed", "the test process ended without a verdict" + (f"\n{detail}" if detail else "")
    case.status = status
    case.output = detail or output[-OUTPUT_LIMIT:]


# Tests per process in a batch: enough that starting one costs little beside its tests, few
# enough that the batches of a lab spread over every slot.
BATCH_SIZE = 12
# What a batch's records say (tests/support/runner.cpp, batch mode).
RECORD_RE = re.compile(r"^(start|end) ([0-9a-f]+)(?: (\d+) (\d+))?$")
TEST_CASE_RE = re.compile(r"<TestCase\b.*?</TestCase>", re.DOTALL)


def run_cases(sandbox: Sandbox, jobs: list, seed: int, timeout: float, deadline: Deadline,
              scratch: Path, homes: Path, workers: int, decided=None) -> None:
    """Runs (program, case) pairs, `workers` at a time: a batch program's cases in batches of
    BATCH_SIZE (run_batch()), any other's one process each (run_one()). `decided`, when given, is
    called in this thread with each batch's (or single test's) cases as soon as they are decided,
    in the order they finish."""
    batches, single = {}, []
    for program, case in jobs:
        if program.batch:
            batches.setdefault(program, []).append(case)
        else:
            single.append((program, case))
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        futures = {pool.submit(run_batch, sandbox, program, cases[i:i + BATCH_SIZE], seed, timeout,
                               deadline, scratch, homes): cases[i:i + BATCH_SIZE]
                   for program, cases in batches.items() for i in range(0, len(cases), BATCH_SIZE)}
        futures.update({pool.submit(run_one, sandbox, program, case, seed, timeout, deadline, scratch, homes): [case]
                        for program, case in single})
        for future in concurrent.futures.as_completed(futures):
            future.result()
            if decided is not None:
                decided(futures[future])


def run_batch(sandbox: Sandbox, program: Program, cases: list, seed: int, timeout: float,
              deadline: Deadline, scratch: Path, homes: Path) -> None:
    """Runs `cases` of one batch program, as many per process as it can: a process that ends in
    the middle of a test (a crash, a worker that failed it, a time-out) decides that test, and
    a new process runs the ones after it. Each test keeps its own time limit."""
    pending = list(cases)
    while pending:
        if min(timeout, deadline.left()) <= 1.0:
            for case in pending:
                case.status, case.output = "not run", "not run: the grading deadline was reached"
            return
        slot = sandbox.acquire()
        try:
            decided = run_batch_once(sandbox, slot, program, pending, seed, timeout, deadline, scratch, homes)
        except Exception as error:  # an error of the grader's own costs these tests, not the grade
            for case in pending:
                case.status, case.output = "crashed", f"the grader could not run this test: {error}"
            return
        finally:
            sandbox.release(slot)
        pending = [case for case in pending if id(case) not in decided]


def run_batch_once(sandbox: Sandbox, slot: int, program: Program, cases: list, seed: int,
                   timeout: float, deadline: Deadline, scratch: Path, homes: Path) -> set:
    """One process of a batch; returns the ids of the cases it decided (at least one)."""
    by_hex = {case.name.encode("utf-8").hex(): case for case in cases}
    work = Path(tempfile.mkdtemp(dir=scratch, prefix="batch-"))
    decided, current, timed_out = set(), None, False
    started = time.monotonic()  # of the current test, or of the wait for the next one
    try:
        records_read, records_write = os.pipe()
        out_fd = os.open(work / "output", os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
        cmd = [str(program.exe), ",".join(escape_spec(c.name) for c in cases), "-r", "xml", "--rng-seed", str(seed)]
        env = {"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8", "HOME": str(homes / f"home-{slot}"),
               "TMPDIR": str(homes / f"home-{slot}"), "PHYSLAB_RECORDS": str(records_write)}
        if program.worker is not None:
            env.update(sandbox.isolation.environment(program.worker))
        limits = sandbox.limits(TEST_MEMORY, timeout * len(cases), min(OUTPUT_FILE_LIMIT * len(cases), 64 << 20))
        try:
            pinned = sandbox.processor(slot) if program.worker is not None else []
            proc = sandbox.spawn(pinned + limits + cmd, sandbox.ids(slot), cwd=homes / f"home-{slot}", env=env,
                                 stdout=out_fd, stderr=out_fd, pass_fds=(records_write,))
        finally:
            for fd in (records_write, out_fd):
                os.close(fd)
        try:
            pending = b""
            while True:
                now = time.monotonic()
                wait = min(deadline.left(), started + timeout - now)
                if wait <= 0:
                    timed_out = True
                    break
                ready, _, _ = select.select([records_read], [], [], min(wait, 1.0))
                if not ready:
                    continue
                chunk = os.read(records_read, 1 << 16)
                if not chunk:
                    break
                *lines, pending = (pending + chunk).split(b"\n")
                for line in lines:
                    m = RECORD_RE.match(line.decode("ascii", errors="replace"))
                    case = by_hex.get(m.group(2)) if m else None
                    if case is None or id(case) in decided:
                        continue
                    if m.group(1) == "start":
                        current, started = case, time.monotonic()
                    elif case is current:
                        passed, failed = int(m.group(3)), int(m.group(4))
                        case.seconds = time.monotonic() - started
                        case.status = "passed" if failed == 0 and passed > 0 else "failed"
                        case.output = "" if failed or passed else "the test ran but asserted nothing"
                        decided.add(id(case))
                        current, started = None, time.monotonic()
        finally:
            os.close(records_read)
            kill_group(proc.pid)
            code = proc.wait()
            with sandbox.lock:
                sandbox.live.discard(proc.pid)
            sandbox.end(slot)
        output = read_capped(work / "output", 16 << 20)
        explain_batch(cases, decided, output)
        if current is not None:
            current.seconds = time.monotonic() - started
            ended_test(current, None if timed_out else code, timeout, output)
            decided.add(id(current))
        elif not decided:  # the process never started a test: nothing after it would either
            for case in cases:
                ended_test(case, None if timed_out else code, timeout, output)
                decided.add(id(case))
        return decided
    finally:
        shutil.rmtree(work, ignore_errors=True)


def explain_batch(cases: list, decided: set, output: str) -> None:
    """The explanation of each failed test of a batch, from its part of the XML report."""
    failed = {case.name: case for case in cases if id(case) in decided and case.status == "failed"}
    for match in TEST_CASE_RE.finditer(output):
        try:
            name = ET.fromstring(match.group(0)).get("name")
        except ET.ParseError:
            continue
        case = failed.get(name)
        if case is not None:
            status, detail, case.checks, case.captured = describe_failure(f"<Catch>{match.group(0)}</Catch>")
            case.status = status
            case.output = "\n".join(filter(None, [case.output, detail])) or "a check failed"


def ended_test(case: TestCase, code, budget: float, output: str) -> None:
    """A test of a batch that took its process with it: `code` is how the process ended (None:
    killed at the test's time limit); a checker says why a worker failed it on its last line."""
    said = [line[len("physlab: "):] for line in output.splitlines() if line.startswith("physlab: ")]
    why = said[-1][:OUTPUT_LIMIT] if said else ""
    if code is None:
        case.status, case.output = "timed out", f"killed after {budget:.3g} s"
    elif code == NOT_GRADED:
        case.status, case.output = "not graded", why
    elif code < 0:
        number = -code
        name = signal.Signals(number).name if number in signal.Signals._value2member_map_ else str(number)
        extra = " (output limit exceeded)" if number == signal.SIGXFSZ else ""
        case.status, case.output = "crashed", f"crashed ({name}){extra}"
    elif why:
        case.status, case.output = "failed", why
    else:
        case.status, case.output = "crashed", f"the test process ended (exit code {code}) without a verdict"
