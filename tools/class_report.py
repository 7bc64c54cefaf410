"""The class at a glance, after `./physlab grade subs/* --out R` (tools/grader): R/tests.csv, one
row per graded test with how the class did on it, and R/class.html, a page that needs nothing but
itself (its charts are inline SVG drawn by gnuplot): a score histogram per lab, the tests failed
most often with the handout section each grades (a link into the handout), and the checks that
failed most often. The Grading page, "Grading a class", describes both.
"""

import csv
import html
import io
import os
import re
import statistics
import subprocess
import tempfile
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
COLUMNS = ["test", "lab", "section", "hidden", "points", "submissions", "passed", "pass_rate",
           "assertion", "not_written", "time_out", "crash", "not_compiled", "not_run"]
STATUS_COLUMN = {"failed": "assertion", "not implemented": "not_written", "timed out": "time_out",
                 "crashed": "crash", "not compiled": "not_compiled", "not run": "not_run"}
BINS = 10     # histogram bars: 0-10 %, ..., 90-100 % of a lab's points
SHOWN = 15    # rows of the most-failed tables


def handout(stage: str) -> tuple:
    """(page id, {section: (title, anchor)}, the handout's path) of a lab's handout."""
    found = sorted((ROOT / "docs").glob(f"lab{stage[:2]}_*.md"))
    if not found:
        return None, {}, None
    text = found[0].read_text(encoding="utf-8", errors="replace")
    page = re.search(r"^# .*\{#(\w+)\}", text, re.MULTILINE)
    sections = {int(n): (title, anchor) for n, title, anchor in
                re.findall(r"^## (\d+)\. (.+?) \{#(\w+)\}$", text, re.MULTILINE)}
    return page.group(1) if page else None, sections, found[0]


def section_link(stage: str, section: int) -> str:
    """An HTML link to the handout's section: into the built documentation site when there is one
    (./physlab docs), else to the handout's Markdown source."""
    page, sections, source = handout(stage)
    title, anchor = sections.get(section, (f"section {section}", ""))
    site = Path(os.environ.get("PHYSLAB_BUILD", ROOT / "build")) / "docs" / "html" / f"{page}.html"
    if page and site.exists():
        target = site.as_uri() + (f"#{anchor}" if anchor else "")
    elif source is not None:
        target = source.as_uri()
    else:
        return html.escape(f"{section}. {title}")
    return f'<a href="{html.escape(target)}">{section}. {html.escape(title)}</a>'


def per_test(graded: dict) -> dict:
    """(lab, test) -> its row of tests.csv, and the failed checks (check -> submissions)."""
    rows = {}
    for data, results, _ in graded.values():
        for r in results:
            for t in r.tests:
                if not t.graded:
                    continue
                row = rows.setdefault((r.stage, t.name), {
                    "test": t.name, "lab": r.stage, "section": t.sections[-1] if t.sections else "",
                    "hidden": "yes" if t.hidden else "no", "points": t.points, "submissions": 0,
                    "passed": 0, "checks": Counter(), **{c: 0 for c in STATUS_COLUMN.values()}})
                row["submissions"] += 1
                if t.passed:
                    row["passed"] += 1
                else:
                    row[STATUS_COLUMN.get(t.status, "crash")] += 1
                    row["checks"].update(set(t.checks))
    for row in rows.values():
        row["pass_rate"] = round(row["passed"] / row["submissions"], 3)
    return rows


def lab_scores(graded: dict) -> dict:
    """lab -> ([percent of the lab's points per submission], the lab's points)."""
    scores = {}
    for data, results, _ in graded.values():
        for r in results:
            graded_tests = [t for t in r.tests if t.graded]
            possible = sum(t.points for t in graded_tests)
            if possible > 0:
                got = sum(t.points for t in graded_tests if t.passed)
                scores.setdefault(r.stage, ([], possible))[0].append(100.0 * got / possible)
    return dict(sorted(scores.items()))


def histogram_svg(stage: str, percents: list) -> str:
    """A bar chart of how many submissions scored in each tenth of the lab's points, by gnuplot."""
    counts = [0] * BINS
    for p in percents:
        counts[min(int(p // (100 / BINS)), BINS - 1)] += 1
    with tempfile.TemporaryDirectory(prefix="physlab-class-") as tmp:
        data, chart = Path(tmp) / "bins.dat", Path(tmp) / "chart.svg"
        data.write_text("".join(f"{(i + 0.5) * 100 / BINS:g} {c}\n" for i, c in enumerate(counts)))
        script = "\n".join([
            "set terminal svg size 460,260 fixed font 'sans,11' background '#ffffff'",
            f"set output '{chart}'",
            f"set title 'Lab {stage[:2]}: submissions per score band'",
            "set xlabel 'score (% of the lab points)'", "set ylabel 'submissions'",
            "set xrange [0:100]", "set xtics 0,10,100", "set yrange [0:*]", "set ytics 1" if max(counts) <= 10 else "set ytics",
            "set boxwidth 9", "set style fill solid 0.8 border rgb '#1f4e79'", "set grid ytics",
            "unset key",
            f"plot '{data}' using 1:2 with boxes lc rgb '#4a90c2'", ""])
        subprocess.run(["gnuplot"], input=script, text=True, check=True, capture_output=True)
        svg = chart.read_text(encoding="utf-8")
    return svg[svg.find("<svg"):]


def write_tests_csv(out: Path, rows: dict) -> None:
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(COLUMNS)
    for row in sorted(rows.values(), key=lambda r: (r["lab"], r["pass_rate"], r["test"])):
        writer.writerow([f"{row[c]:g}" if isinstance(row[c], float) else row[c] for c in COLUMNS])
    (out / "tests.csv").write_text(buffer.getvalue(), encoding="utf-8")


def page(rows: dict, scores: dict, graded: dict, course_name, cpu: str) -> str:
    esc = html.escape
    times = [seconds for _, _, seconds in graded.values()]
    failed = {name: data["extra_data"]["not_graded"] for name, (data, _, _) in graded.items()
              if data.get("extra_data", {}).get("not_graded")}
    title = f"PhysLab class report: {len(graded) - len(failed)} submissions graded" + \
        (f", {len(failed)} not graded" if failed else "") + (f", course {course_name}" if course_name else "")
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{esc(title)}</title>",
             "<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
             "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:3px 8px;"
             "text-align:left;vertical-align:top}th{background:#eef3f8}td.n{text-align:right}"
             ".charts{display:flex;flex-wrap:wrap;gap:1em}code{font-size:90%}</style></head><body>",
             f"<h1>{esc(title)}</h1>",
             f"<p>Graded in {sum(times) / 60:.1f} min of grading time, {sum(times) / len(times):.0f} s "
             f"a submission on average (slowest {max(times):.0f} s). {esc(cpu)}.</p>",
             *(["<h2>Not graded</h2><p>The grading failed on these (twice), not their code: grade them "
                "again.</p><ul>" + "".join(f"<li>{esc(n)}: {esc(why)}</li>" for n, why in failed.items()) + "</ul>"]
               if failed else []),
             "<h2>Scores per lab</h2><table><tr><th>lab</th><th>points</th><th>mean</th><th>median</th>"
             "<th>lowest</th><th>highest</th></tr>"]
    for stage, (percents, possible) in scores.items():
        parts.append(f"<tr><td>{esc(stage)}</td><td class='n'>{round(possible, 2):g}</td>"
                     + "".join(f"<td class='n'>{v:.0f} %</td>" for v in
                               (statistics.mean(percents), statistics.median(percents), min(percents),
                                max(percents))) + "</tr>")
    parts.append("</table><div class='charts'>")
    parts += [f"<figure>{histogram_svg(stage, percents)}</figure>" for stage, (percents, _) in scores.items()]
    parts.append("</div><h2>The tests failed most often</h2><table><tr><th>lab</th><th>test</th>"
                 "<th>handout section</th><th>points</th><th>passed</th><th>assertion</th>"
                 "<th>not written</th><th>time-out</th><th>crash</th><th>not compiled</th></tr>")
    failing = sorted((r for r in rows.values() if r["passed"] < r["submissions"]),
                     key=lambda r: (r["pass_rate"], r["lab"], r["test"]))[:SHOWN]
    for r in failing:
        hidden = " <em>(hidden)</em>" if r["hidden"] == "yes" else ""
        link = section_link(r["lab"], r["section"]) if r["section"] != "" else ""
        parts.append(f"<tr><td>{esc(r['lab'])}</td><td>{esc(r['test'])}{hidden}</td><td>{link}</td>"
                     f"<td class='n'>{r['points']:g}</td><td class='n'>{r['passed']}/{r['submissions']}</td>"
                     + "".join(f"<td class='n'>{r[c]}</td>" for c in
                               ("assertion", "not_written", "time_out", "crash", "not_compiled")) + "</tr>")
    if not failing:
        parts.append("<tr><td colspan='10'>every submission passed every test</td></tr>")
    parts.append("</table><h2>The checks that failed most often</h2><p>A check counts once per "
                 "submission in which it failed.</p><table><tr><th>submissions</th><th>check</th>"
                 "<th>test</th><th>lab</th></tr>")
    checks = sorted(((n, check, r) for r in rows.values() for check, n in r["checks"].items()),
                    key=lambda x: (-x[0], x[2]["lab"], x[1]))[:SHOWN]
    for n, check, r in checks:
        parts.append(f"<tr><td class='n'>{n}</td><td><code>{esc(check)}</code></td>"
                     f"<td>{esc(r['test'])}</td><td>{esc(r['lab'])}</td></tr>")
    if not checks:
        parts.append("<tr><td colspan='4'>no check failed</td></tr>")
    parts.append("</table><p>Per test: <code>tests.csv</code>; per submission: <code>scores.csv</code> "
                 "and each submission's <code>report.txt</code>.</p></body></html>\n")
    return "\n".join(parts)


def write(out: Path, graded: dict, course_name=None, cpu: str = "") -> None:
    """Writes out/tests.csv and out/class.html for the graded class {name: (data, results, s)},
    graded with the course `course_name` (None: none); `cpu`: a line on its CPU time."""
    rows = per_test(graded)
    write_tests_csv(out, rows)
    (out / "class.html").write_text(page(rows, lab_scores(graded), graded, course_name, cpu), encoding="utf-8")
