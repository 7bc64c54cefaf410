"""What a failed test's report points to: the handout section and the student's file that hold
what it grades, and its hint in the physics' words (tests/.../hints.toml), never a hidden test's
expected value; with the checks that every graded test's tags and every hint can be placed.
"""

import functools
import re
import tomllib

import course as course_file  # tools/course.py, beside the package

from .common import ROOT, TestCase, clean, section_files


@functools.lru_cache(maxsize=None)
def handout_sections(stage: str) -> tuple:
    """The lab's handout (path relative to the tree) and its numbered sections {number: title}."""
    found = sorted((ROOT / "docs").glob(f"lab{stage[:2]}_*.md"))
    if not found:
        return None, {}
    text = found[0].read_text(encoding="utf-8", errors="replace")
    sections = re.findall(r"^## (\d+)\. (.+?)(?: \{#\w+\})?$", text, re.MULTILINE)
    return found[0].relative_to(ROOT), {int(number): title for number, title in sections}


def handout_hint(case: TestCase) -> str:
    """Where the handout explains what a failed test checks, and which of the student's files hold
    the functions it grades: from the test's [sec=N] tags."""
    path, titles = handout_sections(case.stage)
    if path is None or not case.sections:
        return ""
    named = [f"{n} ({titles[n]})" if n in titles else str(n) for n in case.sections]
    where = f"section {named[0]}" if len(named) == 1 else \
        "sections " + (", ".join(named) if len(named) <= 2 else ", ".join(map(str, case.sections)))
    files = ", ".join(f"labs/{case.stage}/{u}.cpp" for u in sorted(case.units))
    return f"handout: {path}, {where}; your code: {files}"


HINT_FIELD_RE = re.compile(r"\{(\w*)\}")
HINT_NUMBER_RE = re.compile(r"(?<![A-Za-z_])\d")  # a number, not a digit of a name (RK4)


@functools.lru_cache(maxsize=None)
def hint_table(stage: str, hidden: bool) -> dict:
    """test name -> (text, measured) from tests/NN_name/hints.toml (visible tests) or
    tests/hidden/NN_name/hints.toml (hidden tests): a hint is a string, or a table with `text` and
    `measured`, a sentence with {fields} filled from the failure (lhs and rhs, the two sides of the
    first failed comparison; a name the test CAPTUREs), shown only when every field was found."""
    path = ROOT / "tests" / ("hidden" if hidden else "") / stage / "hints.toml"
    if not path.exists():
        return {}
    table = {}
    for name, entry in tomllib.loads(path.read_text(encoding="utf-8")).items():
        if isinstance(entry, str):
            table[name] = (entry, "")
        elif isinstance(entry, dict):
            table[name] = (str(entry.get("text", "")), str(entry.get("measured", "")))
    return table


def hint_problems(stages: list) -> list:
    """Hints that name no test of their lab's file, and hidden tests' hints that could give a value
    away: a number of their own, or the expected side {rhs} of a comparison."""
    problems = []
    for stage in stages:
        for hidden in (False, True):
            where = f"tests/{'hidden/' if hidden else ''}{stage}/hints.toml"
            path = ROOT / where
            if not path.exists():
                continue
            try:
                raw = tomllib.loads(path.read_text(encoding="utf-8"))
            except tomllib.TOMLDecodeError as error:
                problems.append(f"{where}: not valid TOML: {error}")
                continue
            names = {t.name for t in course_file.tree_tests(ROOT, stage) if ("hidden" in t.tags) == hidden}
            for name, entry in raw.items():
                if name not in names:
                    problems.append(f"{where}: no {'hidden' if hidden else 'visible'} graded test named {name!r}")
                if not isinstance(entry, (str, dict)) or (isinstance(entry, dict) and (
                        set(entry) - {"text", "measured"} or not isinstance(entry.get("text", ""), str)
                        or not isinstance(entry.get("measured", ""), str))):
                    problems.append(f"{where}: {name!r}: a hint is text or a table of text and measured")
                    continue
                text, measured = hint_table(stage, hidden).get(name, ("", ""))
                if not text:
                    problems.append(f"{where}: {name!r}: the hint has no text")
                if hidden and HINT_NUMBER_RE.search(HINT_FIELD_RE.sub("", text + measured)):
                    problems.append(f"{where}: {name!r}: a hidden test's hint may hold no number of its "
                                    f"own (it could be the expected value); measured values come from fields")
                if hidden and "{rhs}" in measured:
                    problems.append(f"{where}: {name!r}: {{rhs}} is a hidden test's expected side")
                if "" in HINT_FIELD_RE.findall(text + measured):
                    problems.append(f"{where}: {name!r}: an empty {{}} field")
    return problems


def hint_of(case: TestCase) -> str:
    """The hint of a failed test (the test ran and broke: not unwritten, not uncompiled), or ''."""
    if case.passed or case.status in ("not implemented", "not compiled", "not run"):
        return ""
    text, measured = hint_table(case.stage, "hidden" in case.tags).get(case.name, ("", ""))
    if not text:
        return ""
    fields = HINT_FIELD_RE.findall(measured)
    if measured and all(f in case.captured for f in fields):
        text += " " + HINT_FIELD_RE.sub(lambda m: case.captured[m.group(1)], measured)
    return clean(f"hint: {text}")


def tag_problems(results: list) -> list:
    """Graded tests whose [sec=N] tags do not name a section of their lab's files: without one,
    partial credit and the handout hint cannot place them."""
    problems = []
    for r in results:
        for t in r.tests:
            if not t.graded:
                continue
            unknown = [s for s in t.sections if s not in section_files(r.stage)]
            if not t.sections or unknown:
                why = f"section {', '.join(map(str, unknown))} is in no lab file" if unknown else \
                      "no [sec=N] tag naming the handout section it grades"
                problems.append(f"lab {r.stage}: {t.name}: {why}")
    return problems
