"""The instructor's build as the grader uses it (Kit): the toolchain and the stages' objects,
compile and link commands, the precompiled framework headers, and the symbol tables (nm, c++filt)
of objects, libraries and the framework's API.
"""

import hashlib
import json
import os
import re
import shutil
import stat
import subprocess
import tempfile
import threading
import time
from pathlib import Path

from .common import ROOT, write_atomically
from .policy import ALLOWED_C, ALLOWED_STD, FORBIDDEN_STD, PHYSLAB_NAME

SHARED_LIBRARIES = ("libstdc++.so.6", "libm.so.6", "libc.so.6", "libgcc_s.so.1")


class Kit:
    """The instructor's build as the grader uses it (written by cmake/PhysLab.cmake): the compiler
    and flags, and per stage the test, hidden-test and framework objects and earlier stages'
    reference libraries. None of it is ever shown to student code."""

    def require_notary(self) -> None:
        """Grading trusts only the notary's verdict: refuse a build whose runner has none."""
        if self.toolchain.get("notary") is not True:
            raise RuntimeError("this build's test runner has no notary (the portable runner, built on "
                               "a non-ELF system or with -DPHYSLAB_PORTABLE_RUNNER=ON): its verdicts come "
                               "from the process that runs student code; grade with a Linux build")

    def __init__(self, build: Path):
        folder = build / "grading"
        if not (folder / "toolchain.json").exists():
            raise RuntimeError(f"{folder} is missing: build the tests first (./physlab build)")
        self.build = build
        self.toolchain = json.loads((folder / "toolchain.json").read_text())
        self.stages = {p.stem: json.loads(p.read_text()) for p in folder.glob("[0-9][0-9]_*.json")}
        self.cache = folder / "cache"
        self.cache.mkdir(mode=0o700, exist_ok=True)
        headers = sorted((ROOT / "common" / "include").rglob("*"))
        digest = hashlib.sha256(json.dumps(self.toolchain, sort_keys=True).encode())
        for h in headers:
            if h.is_file():
                digest.update(str(h.relative_to(ROOT)).encode() + h.read_bytes())
        self.digest = digest.hexdigest()
        self._exports = None
        self._libm = None
        self._api = {}
        self._symbols = {}
        self._precompiled = {}
        self._precompiled_lock = threading.Lock()

    def compiler(self, include: Path) -> list:
        """The compiler with the reference's flags and the framework's and Eigen's headers."""
        cmd = [self.toolchain["compiler"]] + self.toolchain["flags"].split() + ["-I", str(include)]
        for d in self.toolchain["system_include"]:
            cmd += ["-isystem", d]
        return cmd

    def compile_command(self, include: Path, source: Path, obj: Path, header: Path = None) -> list:
        """`header`: the stage's precompiled framework headers (precompiled()), included first."""
        return self.compiler(include) + self.toolchain["warnings"].split() + (
            ["-include", str(header)] if header else []) + [
            "-MD", "-MF", str(obj.with_suffix(".d")), "-c", str(source), "-o", str(obj)]

    def precompiled(self, stage: str):
        """The framework headers the stage's stubs include, precompiled with the flags a submitted
        file compiles with (GCC's .gch): a file then skips parsing Eigen and the framework, a
        third of its compile. They hold only the framework's public headers, and live where the
        sandbox's identities can read them (PRECOMPILED, not the instructor's tree, which is
        often closed to other users). Built at the first grade that needs them; None where the
        compiler would not use them, and the files then compile as they are."""
        with self._precompiled_lock:
            if stage not in self._precompiled:
                self._precompiled[stage] = self._precompile(stage)
            header = self._precompiled[stage]
        if header:
            os.utime(header.parent)  # in use: prune_precompiled() spares it
        return header

    def _precompile(self, stage: str):
        includes = sorted({i for f in (ROOT / "labs" / stage).glob("*.cpp")
                           for i in re.findall(r'^#include\s+"(physlab/[^"]+)"', f.read_text(), re.MULTILINE)})
        if not includes:
            return None
        text = ("// The framework headers of the stage's stubs, precompiled for grading (tools/grader/kit.py)\n"
                + "".join(f'#include "{i}"\n' for i in includes))
        folder = precompiled_folder()
        if folder is None:
            return None
        final = folder / f"{stage}-{hashlib.sha256((self.digest + text).encode()).hexdigest()[:16]}"
        header = final / "framework.hpp"
        if (final / "framework.hpp.gch").exists():
            return header
        prune_precompiled(folder)
        work = Path(tempfile.mkdtemp(dir=folder, prefix=".building-"))
        try:
            (work / "framework.hpp").write_text(text)
            base = self.compiler(ROOT / "common" / "include") + self.toolchain["warnings"].split()
            built = subprocess.run(base + ["-x", "c++-header", str(work / "framework.hpp"), "-o",
                                           str(work / "framework.hpp.gch")], capture_output=True, timeout=300)
            if built.returncode != 0:
                return None
            # Only a header the compiler then reads from its .gch ("!" in -H's list) saves anything
            probe = subprocess.run(base + ["-include", str(work / "framework.hpp"), "-H", "-fsyntax-only",
                                           "-x", "c++", "/dev/null"], capture_output=True, text=True, timeout=120)
            if f"! {work / 'framework.hpp.gch'}" not in probe.stderr:
                return None
            for path in (work, work / "framework.hpp", work / "framework.hpp.gch"):
                os.chmod(path, 0o755 if path.is_dir() else 0o644)
            try:
                os.rename(work, final)  # whole or not at all: another grade may be building it too
            except OSError:
                pass  # that grade's is in place
            return header if (final / "framework.hpp.gch").exists() else None
        except (OSError, subprocess.TimeoutExpired):
            return None
        finally:
            shutil.rmtree(work, ignore_errors=True)

    def preprocess_command(self, include: Path, source: Path, out: Path) -> list:
        return self.compiler(include) + ["-E", str(source), "-o", str(out)]

    def link_command(self, stage: str, tests: str, student: list, exe: Path, reference=()) -> list:
        spec = self.stages[stage]
        # The instructor's objects come first and its libraries whole: wherever the student's
        # objects and the instructor's define the same inline function, the instructor's is used.
        cmd = [self.toolchain["compiler"]] + self.toolchain["flags"].split() + ["-o", str(exe)]
        cmd += self.toolchain["main"] + spec[tests] + spec["framework"] + list(reference)
        cmd += ["-Wl,--whole-archive"] + spec["depends"] + [self.toolchain["common"]]
        return cmd + ["-Wl,--no-whole-archive"] + [str(o) for o in student] + self.toolchain["libraries"]

    def worker_command(self, stage: str, student: list, exe: Path, reference=()) -> list:
        """Links a worker (a remote stage): the server's table, the submitted objects, the
        reference's objects of the stage's other files, the framework; statically."""
        spec = self.stages[stage]
        cmd = [self.toolchain["compiler"]] + self.toolchain["flags"].split() + ["-static", "-o", str(exe)]
        cmd += spec["server"] + [str(o) for o in student] + list(reference) + spec["framework"]
        cmd += ["-Wl,--start-group"] + spec["depends"] + [self.toolchain["common"], "-Wl,--end-group"]
        return cmd + self.toolchain["worker_libraries"]

    def symbols(self, path: str) -> tuple:
        """(defined: name -> nm type, undefined names) of an object or archive's global symbols."""
        if path not in self._symbols:
            listing = self.listing(["-P", "-g"], path)
            defined, undefined = {}, set()
            for line in listing.splitlines():
                parts = line.split()
                if len(parts) < 2 or line.endswith(":"):
                    continue
                if parts[1] in "Uwv":
                    undefined.add(parts[0])
                else:
                    defined[parts[0]] = parts[1]
            self._symbols[path] = (defined, undefined)
        return self._symbols[path]

    def listing(self, options: list, path: str) -> str:
        """What `nm options path` prints, kept in the cache by the file's content: the
        instructor's archives and every object compiled before are listed once, not at every
        grade (each listing takes nm about half a second; a grade needs some 130)."""
        named = options + ([path] if "-A" in options else [])  # -A prints the path on every line
        with open(path, "rb") as f:
            key = hashlib.sha256(" ".join(named).encode() + b"\0" + f.read()).hexdigest()
        cached = self.cache / f"nm-{key}.txt"
        try:
            return cached.read_text()
        except OSError:
            text = subprocess.run(["nm", *options, path], capture_output=True, timeout=60,
                                  text=True, errors="replace").stdout
            write_atomically(cached, text)
            return text

    def defined_by(self, paths: list) -> set:
        found = set()
        for p in paths:
            if not p.startswith("-") and os.path.exists(p):
                found |= set(self.symbols(p)[0])
        return found

    def libm(self) -> set:
        """The functions of the maths library (libm), every one of which a lab file may call."""
        if self._libm is None:
            path = subprocess.run([self.toolchain["compiler"], "-print-file-name=libm.so.6"],
                                  capture_output=True, text=True).stdout.strip()
            listing = subprocess.run(["nm", "-D", "--defined-only", path], capture_output=True,
                                     text=True, errors="replace").stdout
            self._libm = {l.split()[-1].split("@")[0] for l in listing.splitlines() if l.split()}
        return self._libm

    def framework_api(self, stage: str) -> set:
        """What a lab file of `stage` may call in the framework and earlier labs: every global
        symbol of the stage's library side, less those of object files that reach the system
        (plotting and demo output), directly or through another such file; no lab file needs them."""
        if stage not in self._api:
            spec = self.stages[stage]
            members = {}  # (library, member) -> (defined, imported)
            for path in spec["framework"] + spec["depends"] + [self.toolchain["common"]]:
                if path.startswith("-") or not os.path.exists(path):
                    continue
                for line in self.listing(["-P", "-A", "-g"], path).splitlines():
                    member, _, rest = line.rpartition(": ")
                    parts = rest.split()
                    if len(parts) >= 2:
                        defined, imported = members.setdefault(member, (set(), set()))
                        (imported if parts[1] in "Uwv" else defined).add(parts[0])
            inside = set().union(*(d for d, _ in members.values()))
            outside = demangle(set().union(*(i for _, i in members.values())) - inside
                               - ALLOWED_C - self.libm())
            system = {n for n, d in outside.items() if not PHYSLAB_NAME.match(d)
                      and (not ALLOWED_STD.match(d) or FORBIDDEN_STD.match(d))}
            reaching, refused, allowed = set(), set(system), set(inside)
            while True:
                more = {m for m, (_, i) in members.items() if m not in reaching and i & refused}
                if not more:
                    break
                reaching |= more
                allowed = set().union(*(d for m, (d, _) in members.items() if m not in reaching))
                refused = system | (inside - allowed)
            self._api[stage] = allowed
        return self._api[stage]

    def exports(self) -> set:
        """Symbols the shared libraries of the link define: a student's weak definition of one
        would replace it for the whole executable (the harness included), so none is allowed."""
        if self._exports is None:
            self._exports = set()
            libs = [l for l in self.toolchain["libraries"] if ".so" in l]
            for name in SHARED_LIBRARIES:
                libs.append(subprocess.run([self.toolchain["compiler"], f"-print-file-name={name}"],
                                           capture_output=True, text=True).stdout.strip())
            for lib in libs:
                listing = subprocess.run(["nm", "-D", "--defined-only", lib], capture_output=True,
                                         text=True, errors="replace").stdout
                self._exports |= {l.split()[-1].split("@")[0] for l in listing.splitlines() if l.split()}
        return self._exports


def demangle(names) -> dict:
    names = sorted(names)
    if not names:
        return {}
    out = subprocess.run(["c++filt"], input="\n".join(names), capture_output=True, text=True).stdout
    return dict(zip(names, out.splitlines()))


# Where the precompiled framework headers live (Kit.precompiled()): one folder per user of the
# grader, readable by every user, writable by that user alone.
PRECOMPILED = Path("/var/tmp" if os.path.isdir("/var/tmp") else tempfile.gettempdir()) / f"physlab-pch-{os.geteuid()}"
UNUSED_PRECOMPILED = 2 * 86400  # seconds unused after which another build's headers are removed


def precompiled_folder():
    """PRECOMPILED, made if needed; None unless it is ours and no one else may write to it (a
    header planted there would compile into every submission)."""
    try:
        PRECOMPILED.mkdir(mode=0o755, exist_ok=True)
        info = os.lstat(PRECOMPILED)
    except OSError:
        return None
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.geteuid() or info.st_mode & 0o022:
        return None
    return PRECOMPILED


def prune_precompiled(folder: Path) -> None:
    """Removes the headers of builds no grade has used for UNUSED_PRECOMPILED (each is ~120 MB)."""
    for entry in folder.iterdir():
        try:
            if time.time() - entry.stat().st_mtime > UNUSED_PRECOMPILED:
                shutil.rmtree(entry, ignore_errors=True)
        except OSError:
            pass
