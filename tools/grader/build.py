"""Compiling and linking a submission (Builder): each lab file compiled in the sandbox as this run's
identity, cached by its content, with the diagnostics outside the submission left out; graded
executables and workers linked in the private folder.
"""

import hashlib
import os
import re
import shutil
import signal
import subprocess
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

from .common import COMPILE_MEMORY, COMPILE_OUTPUT, GradingFailure, read_capped, write_atomically
from .kit import PRECOMPILED, Kit
from .objects import inline_assembly
from .runner import Deadline
from .sandbox import Sandbox

# Exit statuses of a compile killed by SIGKILL or SIGTERM (directly, or as bubblewrap reports its
# child's end, 128 + the signal): nothing the grader does to a compile in time sends them.
KILLED = (-signal.SIGKILL, -signal.SIGTERM, 128 + signal.SIGKILL, 128 + signal.SIGTERM)
# What g++ says when one of its passes (cc1plus, as) was killed by SIGKILL or SIGTERM; it then exits 1.
KILLED_PASS_RE = re.compile(r"(Killed|Terminated) signal terminated program")


def filter_diagnostics(text: str, allowed: list, shown: dict) -> str:
    """Compiler output with the diagnostics located outside `allowed` folders left out, and the
    sandbox's paths shown as the student's (shown: real prefix -> displayed prefix)."""
    header = re.compile(r"^(?:In file included from |\s+from )?(/[^:]+):")
    kept, keep = [], True
    for line in text.splitlines():
        m = header.match(line)
        if m:
            real = os.path.realpath(m.group(1))
            keep = any(real == a or real.startswith(a.rstrip("/") + "/") for a in allowed)
            if not keep:
                kept.append("(a diagnostic in a file outside the submission and the framework is not shown)")
        if keep:
            for real, display in shown.items():
                line = line.replace(real, display)
            kept.append(line)
    return "\n".join(kept)


def dependencies(dfile: Path) -> list:
    try:
        text = dfile.read_text(errors="replace").replace("\\\n", " ")
    except OSError:
        return []
    return text.split(":", 1)[1].split() if ":" in text else []


@dataclass
class Compiled:
    obj: Path = None
    log: str = ""
    error: str = ""


class Builder:
    """Compiles lab files in the sandbox and links graded executables in the private folder."""

    def __init__(self, kit: Kit, sandbox: Sandbox, private: Path, shared: Path, deadline: Deadline,
                 compile_timeout: float):
        self.kit, self.sandbox, self.private, self.shared = kit, sandbox, private, shared
        self.deadline, self.compile_timeout = deadline, compile_timeout
        self.include = shared / "include"
        self.system = [os.path.realpath(d) for d in kit.toolchain["system_include"]]
        self.system += ["/usr/include", "/usr/lib/gcc", "/usr/local/include"]

    def compile(self, stage: str, name: str, source: bytes, prefix: str = "") -> Compiled:
        key = hashlib.sha256(self.kit.digest.encode() + stage.encode() + name.encode() + source).hexdigest()
        cached, cached_log = self.kit.cache / f"{key}.o", self.kit.cache / f"{key}.log"
        target = self.private / stage / (prefix + name.replace(".cpp", ".o"))
        target.parent.mkdir(parents=True, exist_ok=True)
        if cached.exists() and cached_log.exists():
            shutil.copyfile(cached, target)
            return Compiled(target, cached_log.read_text())
        budget = min(self.compile_timeout, self.deadline.left())
        if budget <= 1.0:
            return Compiled(error=f"{name}: not compiled: the grading deadline was reached")
        slot = self.sandbox.acquire(priority=len(source))
        work = Path(tempfile.mkdtemp(dir=self.shared, prefix="compile-"))
        try:
            (work / name).write_bytes(source)
            ids = self.sandbox.ids(slot)
            if ids:
                os.chown(work, *ids)
            os.chmod(work, 0o700)
            log_path = self.private / stage / f"{prefix}{name}.log"
            log_fd = os.open(log_path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
            obj = work / name.replace(".cpp", ".o")
            preprocessed = work / name.replace(".cpp", ".ii")
            # Inline assembly is refused where the file's code runs beside the tests; a worker's
            # sandbox holds whatever instructions it runs, so a remote lab's file skips the scan
            remote = "checker" in self.kit.stages.get(stage, {})
            isolation = self.sandbox.isolation
            header = self.kit.precompiled(stage)
            jail = (lambda cmd: isolation.compiling(cmd, work, self.include, header and header.parent)) \
                if isolation else (lambda cmd: cmd)
            try:
                if not remote:
                    self.sandbox.run(jail(self.kit.preprocess_command(self.include, work / name, preprocessed)),
                                     slot=slot, cwd=work, timeout=budget, memory=COMPILE_MEMORY,
                                     stdout=subprocess.DEVNULL, fsize=COMPILE_OUTPUT)
                    budget = min(self.compile_timeout, self.deadline.left())
                code, _ = self.sandbox.run(jail(self.kit.compile_command(self.include, work / name, obj, header)),
                                           slot=slot, cwd=work, timeout=budget,
                                           memory=COMPILE_MEMORY, stdout=log_fd, fsize=COMPILE_OUTPUT)
            finally:
                os.close(log_fd)
            outside = [d for d in dependencies(obj.with_suffix(".d"))
                       if not self.allowed(os.path.realpath(work / d))]
            if outside:
                return Compiled(error=f"{name} includes files outside the submission and the "
                                      f"framework headers: {', '.join(sorted(set(outside))[:5])}")
            log = filter_diagnostics(read_capped(log_path, 1 << 20),
                                     [str(work), str(self.include)] + self.system,
                                     {f"{work}/": f"labs/{stage}/", f"{self.include}/": "common/include/"})
            if code is None:
                return Compiled(error=f"{name}: compilation stopped after {budget:.0f} s")
            if code in KILLED or KILLED_PASS_RE.search(log):  # not our time limit (code None) nor a limit of the file's making
                raise GradingFailure(f"the compiler of {name} was killed from outside (status {code})")
            if code != 0 or not obj.exists():
                return Compiled(log=log, error=f"{name} did not compile")
            assembly = "" if remote else inline_assembly(preprocessed, work / name)
            if assembly:
                return Compiled(error=f"{name}: refused: inline assembly ({assembly}); lab code "
                                      f"is C++ only")
            shutil.copyfile(obj, target)
            # Atomically: another submission graded at once may read the same entry
            partial = cached.with_name(f".{key}.{threading.get_ident()}.tmp")
            shutil.copyfile(target, partial)
            os.replace(partial, cached)
            write_atomically(cached_log, log)
            return Compiled(target, log)
        finally:
            shutil.rmtree(work, ignore_errors=True)
            self.sandbox.release(slot)

    def allowed(self, real: str) -> bool:
        roots = [str(self.shared), os.path.realpath(PRECOMPILED)] + self.system
        return any(real == r or real.startswith(r.rstrip("/") + "/") for r in roots)

    def link(self, stage: str, tests: str, objects: list, exe: Path, reference: list = ()) -> str:
        """Links the student's `objects` (and the instructor's `reference` objects of the stage's
        other files) with the `tests` ("tests", "hidden") or, for "worker", into the worker of a
        remote stage; returns '' or an explanation naming the missing or doubly defined functions."""
        budget = min(120.0, self.deadline.left())
        command = (self.kit.worker_command(stage, objects, exe, reference) if tests == "worker"
                   else self.kit.link_command(stage, tests, objects, exe, reference))
        try:
            proc = subprocess.run(command, capture_output=True,
                                  text=True, errors="replace", timeout=max(budget, 1.0))
        except subprocess.TimeoutExpired:
            return "linking stopped at the grading deadline"
        if proc.returncode == 0:
            return ""
        text = proc.stdout + proc.stderr
        missing = sorted(set(re.findall(r"undefined reference to [`']([^']+)'", text)))
        twice = sorted(set(re.findall(r"multiple definition of [`']([^']+)'", text)))
        lines = [f"missing function: {m} (no definition in your files; is it written, with the "
                 f"header's exact signature?)" for m in missing]
        lines += [f"defined twice: {t}" for t in twice]
        return "\n".join(lines) or "the lab did not link"
