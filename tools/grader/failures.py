"""What a failed test's Catch2 XML report says: each distinct failed check once, what happened and
the messages in scope, within a few lines (describe_failure()), with the checks for the class page
and the CAPTUREd values for the hints.
"""

import re
import xml.etree.ElementTree as ET
from pathlib import Path

from .common import clean

# What Catch2 records as the expression of a failure outside any check: an exception or a signal
# after the last check (or section start) that ran, whose line it reports.
UNKNOWN_EXPRESSION = "{Unknown expression after the reported line}"
# Lines of explanation per failed test: report() shows 12, and judge() may put one of its own
# (crashed, timed out) before them.
FAILURE_LINES = 11


def where(node) -> str:
    return f"{Path(node.get('filename', '?')).name}:{node.get('line', '?')}"


def text_of(node) -> str:
    return (node.text or "").strip() if node is not None else ""


def indented(prefix: str, text: str) -> list:
    """The lines of text, the first after prefix and the others under it."""
    first, *rest = text.splitlines() or [""]
    return [prefix + first] + [" " * len(prefix) + line for line in rest]


def failure_of(node, notes: list):
    """A failure as (key, (what, where), detail lines, notes) from one node of Catch2's XML report
    (Expression, Exception, FatalErrorCondition or Failure) and the messages (INFO, CAPTURE) that
    Catch2 wrote before it; None for a check that passed. The key is the same for every failure of
    one check: its place and expression. Its headline is what + where, with a count between them
    when the check failed more than once."""
    if node.tag != "Expression":  # FAIL(), or an exception or signal before any check
        verb = {"Exception": "threw before any check", "FatalErrorCondition": "crashed before any check"}
        first, *rest = text_of(node).splitlines() or [""]
        place = f" (test at {where(node)}): {first}" if node.tag in verb else f" at {where(node)}: {first}"
        return (where(node), first), (verb.get(node.tag, "failed"), place), rest, notes
    if node.get("success") != "false":
        return None
    original = text_of(node.find("Original"))
    expanded = text_of(node.find("Expanded"))
    exception, fatal = node.find("Exception"), node.find("FatalErrorCondition")
    if UNKNOWN_EXPRESSION in original:  # after the check at that line, not in it
        verb, message = ("threw", text_of(exception)) if exception is not None else ("crashed", text_of(fatal))
        first, *rest = message.splitlines() or [""]
        return (where(node), first), (f"{verb} outside any check", f", after {where(node)}: {first}"), rest, notes
    kind = node.get("type") or "CHECK"
    details = []
    if expanded and expanded != original:
        details.append(f"actual: {expanded}")
    if exception is not None:
        details.append(f"threw: {text_of(exception)}")
    elif fatal is not None:
        details.append(f"crashed: {text_of(fatal)}")
    elif "THROWS" in kind and not details:
        details.append("nothing was thrown")
    return (where(node), original), (f"{kind}( {original} ) failed", f" at {where(node)}"), details, notes


def failures_in(node, found: list) -> None:
    """Appends the failures under `node` to `found`, in the order Catch2 met them."""
    notes = []
    for child in node:
        if child.tag == "Info":
            notes.append(text_of(child))
        elif child.tag in ("Expression", "Exception", "FatalErrorCondition", "Failure"):
            failure = failure_of(child, notes)
            if failure:
                found.append(failure)
            notes = []
        else:
            failures_in(child, found)


def fit(blocks: list, limit: int) -> list:
    """At most `limit` lines from blocks of [headline, what happened, more lines...]: the first two
    lines of as many blocks as fit, then their other lines, first block first; a last line counts
    the blocks left out."""
    shown = len(blocks)
    while shown > 0 and sum(len(b[:2]) for b in blocks[:shown]) + (shown < len(blocks)) > limit:
        shown -= 1
    room = limit - sum(len(b[:2]) for b in blocks[:shown]) - (shown < len(blocks))
    lines = []
    for block in blocks[:shown]:
        extra = block[2:2 + room]
        room -= len(extra)
        lines += block[:2] + extra
    if shown < len(blocks):
        lines.append(f"and {len(blocks) - shown} more failed check{'s' if len(blocks) - shown > 1 else ''}")
    return lines


CAPTURED_RE = re.compile(r"^(\w+) := (.*)$")
COMPARISON_RE = re.compile(r" (==|!=|<=|>=|<|>) ")


def short_number(text: str) -> str:
    """A number to four significant digits (what a hint needs), any other text as it is."""
    try:
        return f"{float(text):.4g}"
    except ValueError:
        return text


def describe_failure(output: str) -> tuple:
    """(status, explanation, failed checks, captured values) from the Catch2 XML report inside a
    test's output: each distinct failed check once (a check in a loop says how many times it
    failed, and shows its first failure), what happened, then the messages in scope, within
    FAILURE_LINES lines; the checks as "file:line: expression" for the class page, and the values
    CAPTURE()d at the first failure (name -> text) for the hints. The output is the student's as
    much as the harness's: it only explains, it never decides a pass."""
    start, end = output.find("<Catch"), output.rfind("</Catch>")
    if start < 0 or end < 0:
        return "failed", "", [], {}
    try:
        tree = ET.fromstring(output[start:end + len("</Catch>")])
    except ET.ParseError:
        return "failed", "", [], {}
    found = []
    failures_in(tree, found)
    counts, firsts = {}, {}
    for key, head, details, notes in found:
        counts[key] = counts.get(key, 0) + 1
        firsts.setdefault(key, (head, details, notes))
    blocks = []
    for key, ((what, place), details, notes) in firsts.items():
        head = what + (f" {counts[key]} times{place}; the first:" if counts[key] > 1 else place)
        blocks.append([head] + [line for d in details for line in indented("  ", d)]
                      + [line for n in notes for line in indented("  note: ", n)])
    text = [line for block in blocks for line in block]
    status = "not implemented" if any("not implemented" in line for line in text) else "failed"
    checks = [clean(f"{place}: {expression}") for place, expression in firsts]
    captured = {}
    for note in (found[0][3] if found else []):
        m = CAPTURED_RE.match(note)
        if m:
            captured[m.group(1)] = short_number(clean(m.group(2)))[:80]
    actual = next((d[len("actual: "):] for d in (found[0][2] if found else []) if d.startswith("actual: ")), "")
    sides = COMPARISON_RE.split(re.sub(r"\s+", " ", actual), maxsplit=1)  # Catch2 may wrap long sides
    if len(sides) == 3:  # the first failed comparison's two sides, as the test wrote them
        captured["lhs"], captured["rhs"] = (short_number(clean(side.strip()))[:80] for side in sides[::2])
    return status, "\n".join(fit(blocks, FAILURE_LINES)), checks, captured
