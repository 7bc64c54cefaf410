#!/usr/bin/env python3
"""Check the built documentation site: every image present, every formula rendered, every table a table.

  check_docs.py HTML_DIR

On every page of HTML_DIR (the Doxygen output, build/docs/html):
  - images: each <img src> and <object data> that names a local file must exist on disk;
  - tables: a paragraph holding a markdown table row or rule (a line of pipes, |---|) is a table
    that did not render (a stray pipe in a cell ends it, see docs/conventions.md);
  - raw TeX: a TeX command (\hat, \mathbf, ...) in a paragraph's text outside a formula is a formula
    that lost its \f$ markers, and a control character (a form feed, an escape) is a backslash
    sequence that a script turned into one (\f, \e);
  - formulas: each page with formulas is loaded in headless Chromium (file://, no network) and,
    after MathJax ran, must show no MathJax error (merror, MathJax_Error, "Undefined control
    sequence", "Math Processing Error") and some rendered math.
Without Chromium the formula check is skipped with a message; the other two still run.
Exit status 1 when anything is wrong, each finding on its own line as page: problem.
"""
import argparse
import concurrent.futures
import html.parser
import re
import subprocess
import sys
import tempfile
from pathlib import Path
from urllib.parse import unquote, urlsplit

sys.path.insert(0, str(Path(__file__).resolve().parent))
import headless  # noqa: E402

# Doxygen writes MathJax 2 input as \( \) inline and \[ \] displayed
FORMULA = re.compile(r"\\\(|\\\[")
# a rule row; Doxygen turns its "---" into an em dash when the table did not render
TABLE_RULE = re.compile(r"\|\s*:?(-{3,}|[\u2013\u2014]-*):?\s*(\||$)")
MATHJAX_BOX = re.compile(r'class="[^"]*\b(merror|MathJax_Error)\b')
MATHJAX_MESSAGE = re.compile(r"Undefined control sequence[^<]*|Math Processing Error|Misplaced [^<]*"
                             r"|Missing (open|close) brace|Extra (open|close) brace")
# Doxygen's formula spans in a paragraph's text, and what is left outside them
FORMULA_SPAN = re.compile(r"\\\(.*?\\\)|\\\[.*?\\\]", re.DOTALL)
TEX_COMMAND = re.compile(r"\\[A-Za-z]{2,}")
CONTROL = re.compile(r"[\x00-\x08\x0b-\x0c\x0e-\x1f\x7f]")
MATHJAX_RENDERED = re.compile(r'class="(MathJax|MathJax_Display|MathJax_CHTML|MathJax_SVG)[" ]')


class Page(html.parser.HTMLParser):
    """The local files a page shows, and the text of its paragraphs."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.sources = []
        self.paragraphs = []
        self._paragraph = None
        self._verbatim = 0  # inside <pre> or a code fragment

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "img" and a.get("src"):
            self.sources.append(a["src"])
        elif tag == "object" and a.get("data"):
            self.sources.append(a["data"])
        elif tag in ("pre", "code") or (tag == "div" and "fragment" in (a.get("class") or "")):
            self._verbatim += 1
        elif tag == "p" and not self._verbatim:
            self._paragraph = []

    def handle_endtag(self, tag):
        if tag in ("pre", "code") and self._verbatim:
            self._verbatim -= 1
        elif tag == "p" and self._paragraph is not None:
            self.paragraphs.append("".join(self._paragraph))
            self._paragraph = None

    def handle_data(self, data):
        if self._paragraph is not None and not self._verbatim:
            self._paragraph.append(data)


def local_file(page, ref):
    """The file a page's reference names, or None for a remote or inline one."""
    parts = urlsplit(ref)
    if parts.scheme in ("http", "https", "data", "mailto") or parts.netloc:
        return None
    if parts.scheme == "file":
        return Path(unquote(parts.path))
    return (page.parent / unquote(parts.path)).resolve()


def broken_tables(paragraphs):
    found = []
    for text in paragraphs:
        for line in text.splitlines():
            line = line.strip()
            if TABLE_RULE.search(line) or (line.startswith("|") and line.endswith("|") and len(line) > 1):
                found.append(line if len(line) <= 90 else line[:87] + "...")
    return found


def raw_tex(paragraphs):
    """Paragraph text outside formulas that holds a TeX command or a control character."""
    found = []
    for text in paragraphs:
        outside = FORMULA_SPAN.sub(" ", text)
        for pattern, what in ((TEX_COMMAND, "raw TeX (a formula without its \\f$ markers?)"),
                              (CONTROL, "a control character (a backslash sequence turned into one?)")):
            m = pattern.search(outside)
            if m:
                start = max(0, m.start() - 40)
                snippet = outside[start:m.end() + 40].replace("\n", " ")
                found.append(f"{what}: ...{snippet!r}...")
    return found


def rendered_dom(browser, page, profile, budget_ms):
    """The page's DOM after its scripts ran, from headless Chromium with the network off."""
    dom = headless.run(browser, page, Path(profile), ["--allow-file-access-from-files", "--dump-dom"],
                       budget_ms=budget_ms, timeout=120)
    if not dom.strip():
        raise RuntimeError("chromium returned an empty page")
    return dom


def mathjax_problems(dom):
    problems = [m.group(0).strip() for m in MATHJAX_MESSAGE.finditer(dom)]
    if not problems and MATHJAX_BOX.search(dom):
        problems.append("a MathJax error box")
    if not problems and not MATHJAX_RENDERED.search(dom):
        problems.append("MathJax rendered nothing (is it copied beside the pages?)")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("html", type=Path, help="the site's folder (build/docs/html)")
    parser.add_argument("--budget", type=int, default=20000,
                        help="virtual milliseconds each page gets to run MathJax (default 20000)")
    parser.add_argument("--formulas", default="*.html",
                        help="which pages' formulas to render (comma-separated globs; default every page). Chromium takes "
                             "about 8 s a page here, so CI renders the handouts' and leaves the API pages "
                             "(the same MathJax set-up) to the images and tables check")
    args = parser.parse_args()
    pages = sorted(p for p in args.html.glob("*.html"))
    if not pages:
        sys.exit(f"check_docs: no pages in {args.html}: build the docs first (./physlab docs)")

    findings = []
    images = 0
    formula_pages = []
    for page in pages:
        text = page.read_text(encoding="utf-8", errors="replace")
        parsed = Page()
        parsed.feed(text)
        for ref in parsed.sources:
            target = local_file(page, ref)
            if target is None:
                continue
            images += 1
            if not target.is_file():
                findings.append(f"{page.name}: missing image {ref}")
        for row in broken_tables(parsed.paragraphs):
            findings.append(f"{page.name}: table not rendered: {row}")
        findings.extend(f"{page.name}: {problem}" for problem in raw_tex(parsed.paragraphs))
        if FORMULA.search(text) and any(page.match(glob) for glob in args.formulas.split(",")):
            formula_pages.append(page)

    browser = headless.find_browser()
    if browser is None:
        mathjax = "skipped: chromium not installed (apt-get install chromium)"
    else:
        errors = 0

        def render(page):
            # Two at once (8 s a page, 2 s of it CPU), each with a profile of its own (a profile
            # takes one browser at a time)
            with tempfile.TemporaryDirectory(prefix="physlab-chromium-") as profile:
                try:
                    return mathjax_problems(rendered_dom(browser, page, profile, args.budget))
                except (RuntimeError, subprocess.TimeoutExpired) as e:
                    return [f"could not render: {e}"]

        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            for page, problems in zip(formula_pages, pool.map(render, formula_pages)):
                errors += len(problems)
                findings.extend(f"{page.name}: formula: {p}" for p in problems)
        mathjax = f"{len(formula_pages)} pages with formulas rendered, {errors} MathJax problems"

    for f in findings:
        print(f)
    print(f"docs check: {len(pages)} pages, {images} images, formulas: {mathjax}; "
          f"{len(findings)} problems" + ("" if findings else " (ok)"))
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
