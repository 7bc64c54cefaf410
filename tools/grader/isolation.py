"""How submitted code is fenced in beyond its identity (Isolation): a checker's worker in
bubblewrap's namespaces with the seccomp filter (or the filter alone where namespaces are refused),
and a submitted file's compile in namespaces that show it the system and the framework only.
"""

import os
import shutil
import subprocess
from pathlib import Path

from .common import clean
from .kit import Kit
from .sandbox import Sandbox


class Isolation:
    """How a checker starts its worker (docs/grading.md, "Where submitted code runs"): in
    bubblewrap's namespaces (no other process, no network, a file system holding the worker
    alone) with the seccomp filter, which lets it compute and talk on its pipes only; or, where
    namespaces are refused (an unprivileged container), with the filter alone, installed by the
    checker before the worker starts, under the run's own identity."""

    def __init__(self, kit: "Kit", folder: Path, sandbox: Sandbox):
        """Probes, as the identity tests run under, with a copy of a reference worker in `folder`
        (one the sandbox's identities may read), which kind the machine allows."""
        ids = sandbox.ids(sandbox.slots[0])
        extra = [sandbox.gid] if ids and sandbox.gid is not None else []
        self.filter = folder / "worker.bpf"
        shutil.copyfile(kit.toolchain["worker_filter"], self.filter)
        os.chmod(self.filter, 0o644)
        self.bwrap = shutil.which("bwrap")
        self.why = "bubblewrap (bwrap) is not installed"
        # Any lab's reference worker that is built: a grade or test of some labs builds theirs only
        reference = next((spec["reference_worker"] for spec in kit.stages.values()
                          if "checker" in spec and os.path.exists(spec["reference_worker"])), None)
        if self.bwrap and reference is None:
            self.why = "no reference worker is built to try bubblewrap with"
        if self.bwrap and reference:
            probe = folder / "probe-worker"
            shutil.copyfile(reference, probe)
            os.chmod(probe, 0o755)
            try:
                proc = subprocess.run(["/bin/sh", "-c", 'exec "$@" 5<"$PHYSLAB_FILTER"', "sh"] + self.command(probe),
                                      env={"PATH": "/usr/bin:/bin", "PHYSLAB_FILTER": str(self.filter)},
                                      user=ids[0] if ids else None, group=ids[1] if ids else None,
                                      extra_groups=extra if ids else None, capture_output=True, text=True,
                                      errors="replace", timeout=30)
                self.why = "" if proc.returncode == 0 else \
                    f"namespaces refused: {clean(proc.stderr).strip()[:200] or f'bwrap exited {proc.returncode}'}"
            except (OSError, subprocess.TimeoutExpired) as error:
                self.why = f"bwrap did not start: {error}"
            finally:
                probe.unlink(missing_ok=True)

    def command(self, worker: Path) -> list:
        return [self.bwrap, "--unshare-all", "--die-with-parent", "--new-session", "--cap-drop", "ALL",
                "--clearenv", "--ro-bind", str(worker), "/worker", "--seccomp", "5", "--chdir", "/", "/worker"]

    def compiling(self, cmd: list, work: Path, include: Path, precompiled: Path = None) -> list:
        """`cmd` (a compile of a submitted file in `work`) in bubblewrap's namespaces where they
        are allowed: the compiler sees the system's files (/usr), the framework's headers and the
        file, and nothing of the instructor's tree, other submissions or the network."""
        if self.why:
            return cmd
        view = ["--ro-bind", "/usr", "/usr"]
        for link in ("/bin", "/lib", "/lib64", "/sbin"):
            if os.path.islink(link):
                view += ["--symlink", os.readlink(link), link]
            elif os.path.isdir(link):
                view += ["--ro-bind", link, link]
        if os.path.isdir("/etc/alternatives"):
            view += ["--ro-bind", "/etc/alternatives", "/etc/alternatives"]
        return [self.bwrap, "--unshare-all", "--die-with-parent", "--new-session", "--cap-drop", "ALL",
                *view, "--dev", "/dev", "--tmpfs", "/tmp", "--ro-bind", str(include), str(include),
                *(["--ro-bind", str(precompiled), str(precompiled)] if precompiled else []),
                "--bind", str(work), str(work), "--chdir", str(work), "--"] + cmd

    def describe(self) -> str:
        if not self.why:
            return "your code ran in a process of its own: bubblewrap namespaces and a seccomp filter"
        return f"your code ran in a process of its own: a seccomp filter and this run's own identity ({self.why})"

    def environment(self, worker: Path) -> dict:
        """What a checker needs to start `worker` (tests/support/remote/remote.cpp)."""
        if not self.why:
            return {"PHYSLAB_WORKER": "\x1f".join(self.command(worker)), "PHYSLAB_WORKER_FILTER": str(self.filter)}
        return {"PHYSLAB_WORKER": str(worker), "PHYSLAB_WORKER_FILTER": str(self.filter),
                "PHYSLAB_WORKER_FILTER_MODE": "install"}
