"""The outputs of a grade or a test run: report.txt (per lab, what to fix first, then one line per
unwritten function, then the passes), Gradescope's results.json, and the outputs of a grading that
failed.
"""

import json
import re
from pathlib import Path

from .common import OUTPUT_LIMIT, TestCase, clean, section_files, write_atomically
from .failures import indented
from .hints import handout_hint, hint_of

SYMBOL = {"passed": "PASS", "failed": "FAIL", "not implemented": "TODO", "timed out": "TIME",
          "crashed": "CRSH", "not compiled": "COMP", "not run": "----", "not graded": "NGRD"}


WAITS_RE = re.compile(r"not implemented: (\S+) \(see Lab (\d+) handout, sections? (\d+)")


# Statuses of a test that ran and broke: the failures a student can act on, shown in full
BROKE = ("failed", "crashed", "timed out")


def test_line(t: TestCase) -> str:
    """A test's one line: status, points earned/possible (framework tests: -), name, marks."""
    pts = f"{t.points if t.passed else 0:g}/{t.points:g}" if t.graded else "  - "
    extra = " [hidden]" if t.hidden else (" [framework]" if not t.graded else "")
    return f" {SYMBOL[t.status]} {pts:>6}  {t.name}{extra}"


def failure_block(t: TestCase) -> list:
    """A broken test: its line, what its checks saw (the values), its hint, the handout's section."""
    lines = [test_line(t)] + ["            " + l for l in t.output.splitlines()[:12]]
    hint = hint_of(t)
    if hint:
        lines += indented("            ", hint)
    if not t.hidden:
        lines.append("            " + handout_hint(t))
    return lines


def unwritten(t: TestCase) -> tuple:
    """What an unwritten test waits for, as (function, where): its stub's message names the function
    and its handout section, and the lab's stubs name the file of that section."""
    m = WAITS_RE.search(t.output)
    if not m:
        return "a function not written yet", ""
    function, lab, section = m.group(1), m.group(2), int(m.group(3))
    if lab != t.stage[:2].lstrip("0"):
        return function, f"Lab {lab} handout, section {section}"
    unit = section_files(t.stage).get(section)
    return function, f"{unit}.cpp" if unit else f"handout section {section}"


def todo_lines(tests: list) -> list:
    """One line per unwritten function, the function most tests wait for first."""
    groups = {}
    for t in tests:
        groups.setdefault(unwritten(t), []).append(t)
    order = sorted(groups, key=lambda key: -len(groups[key]))  # stable: ties keep the tests' order
    lines = []
    for function, place in order:
        cases = groups[(function, place)]
        points = sum(t.points for t in cases if t.graded)
        count = f"{len(cases)} test{'s' if len(cases) > 1 else ''}"
        worth = f" ({points:g} point{'' if points == 1 else 's'})" if points else ""
        lines.append(f" TODO: {count}{worth} wait{'' if len(cases) > 1 else 's'} for {function}"
                     + (f" ({place})" if place else ""))
    return lines


def grouped_lines(tests: list) -> list:
    """Tests that did not run their checks (not compiled, not run, not graded): one line per status
    and reason."""
    groups = {}
    for t in tests:
        groups.setdefault((t.status, (t.output.strip().splitlines() or [""])[0]), []).append(t)
    lines = []
    for (status, why), cases in groups.items():
        if len(cases) == 1:
            lines.append(test_line(cases[0]) + (f": {why}" if why else ""))
        else:
            lines.append(f" {SYMBOL[status]}: {len(cases)} tests {status}" + (f": {why}" if why else ""))
    return lines


def report(results: list, seed: int, title: str, passes: bool = True) -> str:
    """The report, per lab: what the student can act on first (tests that broke, with their values,
    hint and handout section; visible before hidden), then one line per unwritten function, the
    passes (not with `passes` false: a run that printed each test's line as it finished), and a
    summary naming the failure to fix first. Deterministic: the tests' own order."""
    out = [title, f"random seed: {seed} (rerun one test: build/test_NN_name_labs \"<test name>\" "
                  f"--rng-seed {seed})", ""]
    total = earned = 0.0
    counts = {"pass": 0, "fail": 0, "todo": 0}
    first = ""
    for r in results:
        graded = [t for t in r.tests if t.graded]
        got = sum(t.points for t in graded if t.passed)
        possible = sum(t.points for t in graded)
        total += possible
        earned += got
        out.append(f"== lab {r.stage}{r.how}: {got:g} / {possible:g} points ==")
        out += ["   note: " + n for n in r.notes]
        if r.compile_error:
            out.append("   did not compile; every test of this lab scores 0. The build says:")
            out += ["   | " + l for l in r.compile_error.strip().splitlines()[-40:]]
        broke = sorted((t for t in r.tests if t.status in BROKE), key=lambda t: t.hidden)
        todo = [t for t in r.tests if t.status == "not implemented"]
        passed = [t for t in r.tests if t.passed]
        other = [t for t in r.tests if not t.passed and t not in broke and t not in todo]
        for t in broke:
            out += failure_block(t)
        out += grouped_lines(other) + todo_lines(todo)
        out += [test_line(t) for t in passed] if passes else []
        failing = len(broke) + len(other)
        first_fix = broke[0].name if broke else ("the build's first error above" if r.compile_error else "")
        fix = f"; fix first: {first_fix}" if first_fix else ""
        out.append(f" summary: {got:g} / {possible:g} points; {len(passed)} pass, {failing} fail, "
                   f"{len(todo)} todo{fix}")
        counts["pass"] += len(passed)
        counts["fail"] += failing
        counts["todo"] += len(todo)
        first = first or (f"lab {r.stage}: {first_fix}" if first_fix else "")
        out.append("")
    fix = f"; fix first: {first}" if first else ""
    out.append(f"TOTAL: {earned:g} / {total:g} points; {counts['pass']} pass, {counts['fail']} fail, "
               f"{counts['todo']} todo{fix}")
    return clean("\n".join(out))


def gradescope_json(results: list, elapsed: float) -> dict:
    tests = []
    for lab_index, r in enumerate(results, start=1):
        for i, t in enumerate((t for t in r.tests if t.graded), start=1):
            tests.append({
                "name": clean(f"lab {r.stage}: {t.name}"),
                "number": f"{lab_index}.{i}",
                "score": t.points if t.passed else 0.0,
                "max_score": t.points,
                "status": "passed" if t.passed else "failed",
                "output": clean(t.status if t.passed else "\n".join(
                    [t.status] + ([hint_of(t)] if hint_of(t) else []) + [t.output]))[:OUTPUT_LIMIT],
                "visibility": "after_published" if t.hidden else "visible",
                "tags": t.tags,
                "extra_data": {"seconds": round(t.seconds, 3)},  # where a grade's time goes
            })
    notes = [clean(f"lab {r.stage}: {n}") for r in results for n in r.notes]
    return {
        # Points are multiples of 1e-4 (a course's rescaling): sums rounded there, not 200.00000000003
        "score": round(sum(t["score"] for t in tests), 4),
        "max_score": round(sum(t["max_score"] for t in tests), 4),
        "execution_time": round(elapsed, 2),
        "output": "\n".join(["Per-test results below; the full report is report.txt."] + notes),
        "tests": tests,
    }


def write_outputs(out: Path, text: str, data: dict) -> None:
    out.mkdir(parents=True, exist_ok=True)
    write_atomically(out / "report.txt", text + "\n")
    write_atomically(out / "results.json", json.dumps(data, indent=2))


def failure_outputs(out: Path, title: str, why: str, elapsed: float) -> dict:
    text = clean(f"{title}\n\nGRADING FAILED: {why}\nscore: 0")
    data = {"score": 0.0, "max_score": 0.0, "execution_time": round(elapsed, 2),
            "output": clean(f"Grading failed: {why}"), "tests": []}
    write_outputs(out, text, data)
    return data


def not_graded_outputs(out: Path, title: str, why: str, elapsed: float) -> dict:
    """report.txt and results.json of a submission the grading failed on (GradingFailure): no
    score; results.json says "not graded" and why (extra_data.not_graded)."""
    text = clean(f"{title}\n\nNOT GRADED: {why}\nThe grading failed, not your code: it will be graded again.")
    data = {"score": 0.0, "max_score": 0.0, "execution_time": round(elapsed, 2),
            "output": clean(f"Not graded: {why}. The grading failed, not your code: it will be graded again."),
            "tests": [], "extra_data": {"not_graded": clean(why)}}
    write_outputs(out, text, data)
    return data


def not_graded(data: dict) -> str:
    """Why a submission was not graded ("" when it was)."""
    return data.get("extra_data", {}).get("not_graded", "")


def summary_line(results: list) -> tuple:
    cases = [t for r in results for t in r.tests]
    passed = sum(t.passed for t in cases)
    return passed, len(cases) - passed
