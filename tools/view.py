#!/usr/bin/env python3
"""Turn replay files into a self-contained viewer page (./physlab view NN runs it).

  view.py REPLAY --out PAGE.html [--reference REPLAY] [--label TEXT] [--reference-label TEXT]
          [--note TEXT] [--tolerance METRES]
  view.py --error TEXT --out PAGE.html

One replay: the page plays it. With --reference: REPLAY is the student's run and the page shows
both side by side under one camera (--label and --reference-label name them), with the first frame
where a body's position differs by more than --tolerance (default 1 mm) or its orientation by more
than 1 mrad (or a particle's position by more than the tolerance) marked on the time slider and
named. Frames are matched by time: a reference recorded by ./physlab publish holds fewer frames
(thinned), and is compared at the frames it holds. --note: a line shown on the page (the
student's lab is not written yet, so only the reference is shown). --error: a page that says what
went wrong instead of a blank one.

The page inlines three.js and OrbitControls from Debian's libjs-three (r111) and the replays as
base64 (Chromium refuses fetch() of file:// URLs), so it works from file:// with the network off.
The replay layout is on the conventions page ("Replay files"); this reader and the page's
(viewer/viewer.js) check it as the C++ reader does. Exit status 2 on a missing, foreign or
truncated replay (the page then shows the error).
"""
import argparse
import base64
import html
import json
import math
import re
import struct
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
THREE_DIR = Path("/usr/share/javascript/three")
THREE = THREE_DIR / "build" / "three.min.js"
ORBIT = THREE_DIR / "examples" / "js" / "controls" / "OrbitControls.js"
MAGIC = b"PHYSLAB-REPLAY"
VERSION = 3
KINDS = ("sphere", "box", "capsule", "plane", "convex")
# In a run's settings: the framework answer did the work (World::describe(), Lab 6's matrix-free
# sweeps), so the run is not the student's code, whatever build it came from
FRAMEWORK_ANSWER = "(framework answer)"
TIME_TOLERANCE = 1e-6  # s: the same step's time in two runs (float32 of the same double)
ORIENTATION_TOLERANCE = 1e-3  # rad: 1 mrad, the angle a 1 m body turns to move its end by 1 mm


class ReplayError(Exception):
    """A replay file that cannot be read, with the message naming the byte."""


def read_replay(path):
    """parse_replay() of the file at `path`."""
    try:
        data = Path(path).read_bytes()
    except OSError as e:
        raise ReplayError(f"replay {path}: cannot be read ({e.strerror})") from None
    return parse_replay(data, path)


def parse_replay(data, path):
    """The replay in `data` (named `path` in messages) as a dict: title, settings, bodies (kind, fixed),
    particle count, frames (time, poses, particles) and its bytes."""
    at = 0

    def need(n, field):
        if len(data) - at < n:
            raise ReplayError(f"replay {path}: truncated at byte {len(data)}: {field} ({n} bytes from byte {at}) is missing")

    def take(fmt, field):
        nonlocal at
        size = struct.calcsize(fmt)
        need(size, field)
        values = struct.unpack_from(fmt, data, at)
        at += size
        return values

    if data[:len(MAGIC)] != MAGIC:
        raise ReplayError(f'replay {path}: not a PhysLab replay: bytes 0-13 are not "PHYSLAB-REPLAY"')
    at = len(MAGIC)
    (version,) = take("<H", "the version")
    if not 1 <= version <= VERSION:
        raise ReplayError(f"replay {path}: version {version} at byte 14 is not one this reader knows (1-{VERSION})")
    bodies_n, particles_n, springs_n, frames_n = take("<4I", "the header's counts")
    texts = []
    for field in ("the title", "the settings"):
        (n,) = take("<I", field + "'s length")
        texts.append(bytes(take(f"<{n}s", field)[0]).decode("utf-8", "replace"))
    bodies = []
    for i in range(bodies_n):
        kind, fixed, _, _, _, _, v, k = take("<2I4f2I", f"body {i}")
        take(f"<{3 * v}f{3 * k}I", f"body {i}'s vertices and triangles")
        bodies.append({"kind": KINDS[kind] if kind < len(KINDS) else f"kind {kind}", "fixed": bool(fixed)})
    take(f"<{2 * springs_n}I", f"the {springs_n} springs")
    frames = []
    for f in range(frames_n):
        time, _, _, _, contacts = take("<3f2I", f"frame {f}'s time, energies and counts")
        flags = take("<I", f"frame {f}'s flags")[0] if version > 1 else 1
        if not flags & 1 and contacts:
            raise ReplayError(f"replay {path}: frame {f} holds {contacts} contacts but says they were not recorded")
        poses = take(f"<{7 * bodies_n}f", f"frame {f}'s poses")
        if version > 2 and flags & 2:  # a byte per body: 1 while it sleeps
            take(f"<{bodies_n}B", f"frame {f}'s sleeping bodies")
        particles = take(f"<{3 * particles_n}f", f"frame {f}'s particles")
        need(40 * contacts, f"frame {f}'s {contacts} contacts")
        at += 40 * contacts
        frames.append({"time": time, "poses": poses, "particles": particles})
    if at != len(data):
        raise ReplayError(f"replay {path}: {len(data) - at} bytes after the last frame, at byte {at}")
    if not frames:
        raise ReplayError(f"replay {path}: no frames")
    return {"title": texts[0], "settings": texts[1], "bodies": bodies, "particles": particles_n, "frames": frames, "bytes": data}


def matched_frames(student, reference):
    """(student frame index, reference frame index) of the frames both runs recorded at the same
    time: every frame when both are whole, the reference's when it was thinned (./physlab publish)."""
    pairs, f = [], 0
    for g, r in enumerate(reference["frames"]):
        while f < len(student["frames"]) and student["frames"][f]["time"] < r["time"] - TIME_TOLERANCE:
            f += 1
        if f == len(student["frames"]):
            break
        if abs(student["frames"][f]["time"] - r["time"]) <= TIME_TOLERANCE:
            pairs.append((f, g))
    return pairs


def first_difference(student, reference, tolerance):
    """(frame index or None, text): where the student's run first leaves the reference's, at the
    frames both recorded (matched by time)."""
    if len(student["bodies"]) != len(reference["bodies"]) or student["particles"] != reference["particles"]:
        return 0, "The two runs do not have the same bodies or particles: they are not the same scene."
    pairs = matched_frames(student, reference)
    for f, g in pairs:
        s, r = student["frames"][f], reference["frames"][g]
        for i, body in enumerate(student["bodies"]):
            a, b = s["poses"][7 * i:7 * i + 7], r["poses"][7 * i:7 * i + 7]
            gap = math.dist(a[:3], b[:3])
            if not gap <= tolerance:  # a NaN differs too
                return f, (f"First difference at frame {f + 1} (t = {s['time']:.3f} s): body {i} ({body['kind']}) "
                           f"position differs by {1000 * gap:.3g} mm (tolerance {1000 * tolerance:g} mm).")
            dot = min(1.0, abs(sum(p * q for p, q in zip(a[3:], b[3:]))))
            angle = 2 * math.acos(dot) if dot == dot else math.inf
            if not angle <= ORIENTATION_TOLERANCE:
                return f, (f"First difference at frame {f + 1} (t = {s['time']:.3f} s): body {i} ({body['kind']}) "
                           f"orientation differs by {1000 * angle:.3g} mrad (tolerance "
                           f"{1000 * ORIENTATION_TOLERANCE:g} mrad).")
        for k in range(student["particles"]):
            gap = math.dist(s["particles"][3 * k:3 * k + 3], r["particles"][3 * k:3 * k + 3])
            if not gap <= tolerance:
                return f, (f"First difference at frame {f + 1} (t = {s['time']:.3f} s): particle {k} position "
                           f"differs by {1000 * gap:.3g} mm (tolerance {1000 * tolerance:g} mm).")
    if not pairs:
        return 0, "The two runs recorded no frame at the same time: they are not the same scene."
    same = (f"Your run and the reference agree within {1000 * tolerance:g} mm and "
            f"{1000 * ORIENTATION_TOLERANCE:g} mrad at all {len(pairs)} frames both recorded.")
    if len(student["frames"]) != len(reference["frames"]):
        same += f" (Yours has {len(student['frames'])} frames, the reference {len(reference['frames'])}.)"
    return None, same


def page(title, data, labels):
    """The page's HTML: the template with three.js, OrbitControls, the data and the viewer inlined."""
    for lib in (THREE, ORBIT):
        if not lib.is_file():
            raise ReplayError(f"{lib} is missing: install Debian's libjs-three (./physlab setup)")
    # JSON inside <script>: "</" must not close the element
    parts = {
        "TITLE": html.escape(title),
        "LABELS": "".join(f"<span>{html.escape(label)}</span>" for label in labels),
        "DATA": json.dumps(data).replace("</", "<\\/"),
        "THREE": THREE.read_text(encoding="utf-8"),
        "ORBIT": ORBIT.read_text(encoding="utf-8"),
        "VIEWER": (ROOT / "viewer" / "viewer.js").read_text(encoding="utf-8"),
    }
    template = (ROOT / "viewer" / "viewer.html").read_text(encoding="utf-8")
    # One pass, so that nothing inlined is searched for placeholders
    return re.sub(r"@([A-Z]+)@", lambda m: parts[m.group(1)], template)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("replay", nargs="?", help="the replay to show (the student's with --reference)")
    parser.add_argument("--out", required=True, help="the page to write")
    parser.add_argument("--reference", help="the reference's replay of the same scene: both side by side")
    parser.add_argument("--note", help="a note shown on the page")
    parser.add_argument("--label", default="your code", help="what the first replay is, with --reference")
    parser.add_argument("--reference-label", default="reference", help="what the --reference replay is")
    parser.add_argument("--tolerance", type=float, default=1e-3, help="position tolerance of the comparison [m]")
    parser.add_argument("--error", help="write a page that shows this error")
    args = parser.parse_args()
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    data = {"note": args.note, "diff": None, "replays": []}
    title, labels = "PhysLab viewer", []
    status = 0
    try:
        if args.error:
            raise ReplayError(args.error)
        if not args.replay:
            raise ReplayError("no replay named")
        runs = [(args.replay, args.label if args.reference else "")]
        if args.reference:
            runs.append((args.reference, args.reference_label))
        replays = [read_replay(path) for path, _ in runs]
        if args.reference and FRAMEWORK_ANSWER in replays[0]["settings"]:
            # The run took the framework answer's path, which calls no student function
            runs[0] = (args.replay, "the framework's code (this scene runs none of yours)")
        title = replays[0]["title"]
        labels = [label for _, label in runs if label]
        if args.reference:
            frame, text = first_difference(replays[0], replays[1], args.tolerance)
            data["diff"] = {"frame": frame, "text": text}
        data["replays"] = [{"name": Path(path).name, "label": label, "base64": base64.b64encode(r["bytes"]).decode()}
                           for (path, label), r in zip(runs, replays)]
    except ReplayError as e:
        data = {"error": str(e)}
        print(f"view: {e}", file=sys.stderr)
        status = 2
    try:
        out.write_text(page(title, data, labels), encoding="utf-8")
    except ReplayError as e:
        print(f"view: {e}", file=sys.stderr)
        return 2
    print(out)
    return status


if __name__ == "__main__":
    sys.exit(main())
