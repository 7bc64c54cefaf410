#!/usr/bin/env python3
"""The demo charts the handouts show, for the two kinds of tree.

Every demo chart in docs/*.md is written \\chart{file,caption} (an alias of docs/Doxyfile.in).
The instructor's tree shows the chart its demos drew with the reference. A student copy shows two:
the reference's, shipped by `./physlab publish` as docs/figures/reference/reference_<file>, and the
student's own from the charts folder, or a placeholder saying that their code cannot draw it yet.

  docs_figures.py reference --docs DIR --charts DIR --out DIR
      copy every chart as reference_<file> into --out (publish); fails when one was not drawn
  docs_figures.py placeholders --docs DIR --charts DIR --out DIR
      empty --out, then write a placeholder there for every chart missing from --charts (the
      student's docs build; a file in both folders would be ambiguous to Doxygen)
"""
import argparse
import re
import shutil
import subprocess
import sys
from pathlib import Path

CHART = re.compile(r"\\chart\{([^,}]+),")
NOT_DRAWN = "not drawn yet: your code cannot draw it yet"


def charts(docs):
    """The chart files the handouts in `docs` show, in order, each once."""
    names = []
    for md in sorted(Path(docs).glob("*.md")):
        for name in CHART.findall(md.read_text(encoding="utf-8")):
            if name not in names:
                names.append(name)
    return names


def lab_of(name):
    """'lab04_soup.gif' -> '04'."""
    match = re.match(r"lab(\d\d)_", name)
    return match.group(1) if match else ""


def hint(name):
    lab = lab_of(name)
    demo = f"./physlab demo {lab}" if lab else "./physlab demo"
    return f"{name}: {demo} draws it once your code can"


def write_svg(path, name):
    path.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" width="640" height="120" viewBox="0 0 640 120">\n'
        '  <rect x="1" y="1" width="638" height="118" fill="#f6f6f6" stroke="#999" stroke-dasharray="6 4"/>\n'
        f'  <text x="320" y="52" font-family="sans-serif" font-size="20" text-anchor="middle">{NOT_DRAWN}</text>\n'
        f'  <text x="320" y="84" font-family="sans-serif" font-size="14" text-anchor="middle" fill="#555">{hint(name)}</text>\n'
        "</svg>\n",
        encoding="utf-8")


def write_gif(path, name):
    script = "\n".join([
        "set terminal gif size 640,120",
        f"set output '{path}'",
        "unset border; unset tics; unset key",
        "set margins 0,0,0,0",
        f"set label 1 '{NOT_DRAWN}' at graph 0.5,0.6 center",
        f"set label 2 '{hint(name)}' at graph 0.5,0.3 center",
        "plot [0:1][0:1] NaN",
    ])
    result = subprocess.run(["gnuplot"], input=script, text=True, capture_output=True)
    if result.returncode != 0 or not path.is_file():
        sys.exit(f"docs_figures: gnuplot could not write the placeholder {path}:\n{result.stderr}")


def reference(args):
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    names = charts(args.docs)
    missing = [n for n in names if not (Path(args.charts) / n).is_file()]
    if missing:
        sys.exit("docs_figures: the demos did not draw " + ", ".join(missing) +
                 f" in {args.charts}: the student copy would lack their reference figure")
    for name in names:
        shutil.copyfile(Path(args.charts) / name, out / f"reference_{name}")
    print(f"{len(names)} reference figures in {out}")


def placeholders(args):
    out = Path(args.out)
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    missing = [n for n in charts(args.docs) if not (Path(args.charts) / n).is_file()]
    for name in missing:
        if name.endswith(".svg"):
            write_svg(out / name, name)
        elif name.endswith(".gif"):
            write_gif(out / name, name)
        else:
            sys.exit(f"docs_figures: no placeholder for the file type of {name} (svg and gif only)")
    if missing:
        print(f"{len(missing)} charts not drawn by your code yet; the handouts say so beside the reference's")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    for name, fn in (("reference", reference), ("placeholders", placeholders)):
        p = sub.add_parser(name)
        p.add_argument("--docs", required=True, help="the handouts folder (docs/)")
        p.add_argument("--charts", required=True, help="the folder the demos wrote their charts to")
        p.add_argument("--out", required=True)
        p.set_defaults(fn=fn)
    args = parser.parse_args()
    args.fn(args)


if __name__ == "__main__":
    main()
