"""Grading a class: several submissions, each in a sandbox of its own, a few at a time with a
progress line after each, one not graded tried once more; and the text of a scores.csv field.
"""

import re
import sys
import threading
import time
from pathlib import Path

from .grade import grade_one
from .kit import Kit
from .report import not_graded
from .sandbox import Sandbox


def csv_text(text: str) -> str:
    """Text for a field of scores.csv: no comma, quote or line break."""
    return re.sub(r'[,"\n\r]+', " ", text)[:200]


def grade_class(args, kit: Kit, sandboxes: list, out: Path, course) -> dict:
    """Grades the submissions, len(sandboxes) at a time, with a progress line after each; returns
    {name: (results.json's data, lab results, seconds)} in the order given."""
    paths = [Path(p).absolute() for p in args.submissions]
    waiting = list(reversed(paths))
    graded, lock = {}, threading.Lock()
    start = time.monotonic()

    def worker(sandbox: Sandbox) -> None:
        while True:
            with lock:
                if not waiting:
                    return
                path = waiting.pop()
            began = time.monotonic()
            data, results = grade_one(args, kit, sandbox, path, out / path.name, course, quiet=True)
            if not_graded(data):  # the grading failed, not the code: once more
                data, results = grade_one(args, kit, sandbox, path, out / path.name, course, quiet=True)
            seconds = time.monotonic() - began
            with lock:
                graded[path.name] = (data, results, seconds)
                done, total = len(graded), len(paths)
                left = (time.monotonic() - start) / done * (total - done)
                score = "not graded" if not_graded(data) else f"{data['score']:g}/{data['max_score']:g}"
                print(f"graded {done}/{total}: {path.name} {score} "
                      f"in {seconds:.0f} s; about {left / 60:.1f} min left", file=sys.stderr, flush=True)

    threads = [threading.Thread(target=worker, args=(sandbox,)) for sandbox in sandboxes]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return {p.name: graded[p.name] for p in paths}
