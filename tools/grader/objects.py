"""Checks of a compiled lab file before it is linked: no inline assembly in the student's own
lines, no instruction that enters the kernel, no section, definition or call the policy refuses;
and the same refusals shown ahead in a student's own build.
"""

import re
import subprocess
from pathlib import Path

from .common import COMPILE_OUTPUT, read_capped
from .kit import Kit, demangle
from .policy import (ALLOWED_C, ALLOWED_SECTIONS, ALLOWED_STD, ASM_KEYWORD_RE, FORBIDDEN_STD,
                     KERNEL_ENTRY_RE, PHYSLAB_NAME, STD_INSTANCE, why_refused)

LINE_MARKER_RE = re.compile(r'^# (\d+) "((?:[^"\\]|\\.)*)"')
LITERAL_RE = re.compile(r'R"([^ ()\\\t\n]{0,16})\((?:.|\n)*?\)\1"|"(?:[^"\\\n]|\\.)*"|\'(?:[^\'\\\n]|\\.)*\'')


def inline_assembly(preprocessed: Path, source: Path) -> str:
    """Where the student's own lines use inline assembly after preprocessing (so a macro cannot
    hide it), e.g. "asm at line 12"; "" when they do not. Lines of headers are not the student's:
    the tokens a student's macro produces are attributed to the line that uses it."""
    try:
        text = read_capped(preprocessed, COMPILE_OUTPUT)
    except OSError:
        return "its preprocessed source could not be checked"
    own, line, found, lines = False, 0, [], []
    for raw in text.splitlines():
        m = LINE_MARKER_RE.match(raw)
        if m:
            line, own = int(m.group(1)), m.group(2) == str(source)
            continue
        if own:
            lines.append((line, raw))
        line += 1
    code = LITERAL_RE.sub('""', "\n".join(raw for _, raw in lines))
    for number, kept in zip((n for n, _ in lines), code.split("\n")):
        m = ASM_KEYWORD_RE.search(kept)
        if m:
            found.append(f"{m.group(1)} at line {number}")
    return ", ".join(found[:3])


def kernel_entries(obj: Path) -> list:
    """Instructions of the object that enter the kernel (syscall, sysenter, int $n)."""
    listing = subprocess.run(["objdump", "-d", "--no-show-raw-insn", str(obj)], capture_output=True,
                             text=True, errors="replace", timeout=60).stdout
    return sorted({" ".join(m.group(1).split()) for m in KERNEL_ENTRY_RE.finditer(listing)})


def sections_of(obj: Path) -> list:
    listing = subprocess.run(["readelf", "-S", "-W", str(obj)], capture_output=True, text=True,
                             errors="replace", timeout=60).stdout
    names = []
    for line in listing.splitlines():
        m = re.match(r"^\s*\[\s*(\d+)\]\s+(\S+)", line)
        if m and m.group(1) != "0":
            names.append(m.group(2))
    return names


def check_object(kit: Kit, stage: str, obj: Path, stub_defined: set, own_defined: set) -> list:
    """Why a student's object may not be linked (empty when it may): what it defines must be what
    the stub defines, or internal, or a weak copy of an inline function that replaces nothing.
    In a remote stage the object is linked into a worker alone, which can reach nothing but its
    pipes whatever it holds: only the first rule is kept, so that a helper's name cannot collide
    with the reference's (sandbox_notes() says what the sandbox will refuse)."""
    defined, undefined = kit.symbols(str(obj))
    if "checker" in kit.stages[stage]:
        strong = [s for s, t in defined.items() if t not in "WVuvw" and s not in stub_defined]
        names = demangle(strong)
        return [f"defines {names[s]}, which the stub does not: make helpers static or put them "
                f"in an anonymous namespace" for s in strong]
    problems = [f"section {s} is not allowed in a lab file" for s in sections_of(obj)
                if not ALLOWED_SECTIONS.match(s)]
    spec = kit.stages[stage]
    test_side = kit.defined_by(kit.toolchain["main"] + spec["tests"] + spec["hidden"])
    library_side = kit.defined_by(spec["framework"] + spec["depends"] + [kit.toolchain["common"]])
    exports = kit.exports()
    strong = [s for s, t in defined.items() if t not in "WVu" and s not in stub_defined]
    weak = [s for s, t in defined.items() if t in "WVu" and s in exports and s not in stub_defined]
    # A weak copy of a standard-library template the headers instantiate ("text" + std::string(...)
    # emits std::operator+) is ordinary C++: the notary calls no C++ library function
    weak = [s for s, d in demangle(weak).items() if not STD_INSTANCE.match(d)]
    reached = [s for s in undefined if s in test_side and s not in library_side
               and s not in own_defined and s not in exports]
    names = demangle(strong + weak + reached)
    problems += [f"defines {names[s]}, which the stub does not: make helpers static or put them "
                 f"in an anonymous namespace" for s in strong]
    problems += [f"defines {names[s]}, a library function" for s in weak]
    problems += [f"uses {names[s]}, which belongs to the test harness" for s in reached]
    return problems + import_problems(kit, stage, obj, own_defined | set(reached))


def import_problems(kit: Kit, stage: str, obj: Path, own_defined: set) -> list:
    """What the object uses that a lab file may not (the allow-list on the Grading page), and the
    instructions in it that enter the kernel; each with its reason."""
    _, undefined = kit.symbols(str(obj))
    spec = kit.stages[stage]
    library_side = kit.defined_by(spec["framework"] + spec["depends"] + [kit.toolchain["common"]])
    framework, libm = kit.framework_api(stage), kit.libm()
    imports = demangle(s for s in undefined if s not in own_defined and s not in framework
                       and s not in libm and s not in ALLOWED_C)
    refused = sorted(d for n, d in imports.items() if (PHYSLAB_NAME.match(d) and n in library_side) or
                     (not PHYSLAB_NAME.match(d) and (not ALLOWED_STD.match(d) or FORBIDDEN_STD.match(d))))
    problems = [f"uses {n}: {why_refused(n)}" for n in refused]
    return problems + [f"contains the instruction '{i}', which enters the kernel" for i in kernel_entries(obj)]


def sandbox_notes(kit: Kit, stage: str, obj: Path, own_defined: set) -> list:
    """In a remote stage: what the object calls that its sandbox refuses (files, processes, the
    network, the kernel directly), as notes; such a call fails when the code runs."""
    return [f"{p}; in the grader's sandbox that call fails" for p in import_problems(kit, stage, obj, own_defined)]


def refusals_ahead(kit: Kit, stage: str) -> list:
    """For a student's own build: the grader's import refusals of the lab files as compiled here,
    so a student learns of them before submitting rather than from a grade of 0."""
    if kit is None or stage not in kit.stages:
        return []
    build = kit.build
    objects = sorted((build / "CMakeFiles" / f"physlab_{stage}_labs.dir").rglob("*.o"))
    own = kit.defined_by([str(o) for o in objects])
    notes = []
    for obj in objects:
        if "checker" in kit.stages[stage]:
            notes += [f"{obj.name.removesuffix('.o')}: {p}" for p in sandbox_notes(kit, stage, obj, own)]
        else:
            notes += [f"the grader will refuse {obj.name.removesuffix('.o')}: {p}"
                      for p in import_problems(kit, stage, obj, own)]
    return notes
