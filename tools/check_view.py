#!/usr/bin/env python3
"""Test viewer pages (./physlab view) in a real browser, offline.

  check_view.py PAGE.html [PAGE.html ...]

Each page is loaded from file:// in headless Chromium with the network blocked (every host name
resolves nowhere, every request goes to a proxy that is not there), and must
  - ask for nothing beyond the machine: Chromium's net log (--log-net-log) holds no request that
    the page started (the browser's own background requests, initiator "not an origin", are
    Chromium's, not the page's), and outside the inlined three.js the page names no http(s) URL;
  - draw the scene: in a screenshot the 3-D canvas (the window's middle third) is not one colour:
    at least 1% of it differs from its most common colour (a canvas three.js did not draw is the
    page's background, or black, all over; a ground plane may fill most of a drawn one);
  - step to the last frame: opened at #frame=last, its DOM shows frame N of N, N being the
    frame count of the replay inlined in the page (of the first, the student's, when two are shown:
    the other is matched by time), and no error box;
  - label its energy plot: the legend says what the axis holds, energies in J or the total's
    relative drift.
With --measure it also prints how long a page takes to show each frame in turn (#measure: the
poses, the contacts drawn, the panel and the energy plot, waiting for the GPU after each), median
and slowest: a figure, not a check (Chromium here renders in software, SwiftShader, on a shared
CPU; a laptop's GPU draws faster). Without Chromium the check is skipped with a message (exit 0).
Exit status 1 when a page fails, each finding on its own line as page: problem.
"""
import argparse
import base64
import html
import json
import re
import struct
import subprocess
import sys
import tempfile
import zlib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import headless  # noqa: E402
from view import ORBIT, THREE, ReplayError, parse_replay  # noqa: E402

WINDOW = (900, 700)
CANVAS_BACKGROUND = (0xf4, 0xf4, 0xf0)  # the scene's background colour (viewer/viewer.js)
# Requests Chromium makes for itself, whatever page it shows
BROWSER_INITIATOR = "not an origin"


def chromium(browser, page, profile, extra, fragment="", virtual_time=True):
    """Runs headless Chromium on page#fragment, offline, in the viewer's window size; returns its
    stdout. With virtual_time, timers run ahead for 4 s of page time; without, the page's clock
    is the wall's."""
    return headless.run(browser, page, profile, [f"--window-size={WINDOW[0]},{WINDOW[1]}", *extra], fragment,
                        4000 if virtual_time else None)


def page_requests(netlog):
    """URLs of the requests the page started, from a Chromium net log."""
    log = json.loads(Path(netlog).read_text(encoding="utf-8", errors="replace"))
    start = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"]
    jobs = [e.get("params", {}) for e in log["events"] if e["type"] == start]
    return sorted({job["url"] for job in jobs if "url" in job and job.get("initiator") != BROWSER_INITIATOR})


def named_urls(text):
    """http(s) URLs the page names outside the inlined three.js and OrbitControls."""
    for lib in (THREE, ORBIT):
        text = text.replace(lib.read_text(encoding="utf-8"), "")
    return sorted(set(re.findall(r"https?://[^\s\"'<>)]+", text)))


def png_pixels(path):
    """(width, height, rows of RGB tuples) of an 8-bit RGB or RGBA PNG, decoded with zlib alone."""
    data = Path(path).read_bytes()
    at, idat, width = 8, b"", 0
    while at < len(data):
        length, kind = struct.unpack_from(">I4s", data, at)
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack_from(">IIBB", body)
            if depth != 8 or colour not in (2, 6):
                raise RuntimeError(f"screenshot {path}: PNG of bit depth {depth}, colour type {colour}")
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    raw, stride, rows, previous = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
    for y in range(height):
        line = raw[y * (stride + 1):(y + 1) * (stride + 1)]
        kind, row = line[0], bytearray(line[1:])
        for i in range(stride):
            left = row[i - channels] if i >= channels else 0
            up, corner = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                row[i] = (row[i] + left) & 0xff
            elif kind == 2:
                row[i] = (row[i] + up) & 0xff
            elif kind == 3:
                row[i] = (row[i] + (left + up) // 2) & 0xff
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                row[i] = (row[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 0xff
        rows.append([tuple(row[x * channels:x * channels + 3]) for x in range(width)])
        previous = row
    return width, height, rows


def canvas_problems(path):
    """What is wrong with the 3-D canvas in the screenshot: not rendered, or nothing in it."""
    width, height, rows = png_pixels(path)
    # The canvas: under the header and any notes (a recorded reference's note and the comparison's
    # banner push it down by a third of the window), above the controls, left of a scroll bar
    band = [p for row in rows[height // 3:2 * height // 3] for p in row[:width - 40]]
    counts = {}
    for p in band:
        counts[p] = counts.get(p, 0) + 1
    common = max(counts, key=counts.get)
    drawn = len(band) - counts[common]
    # A canvas three.js did not draw is one colour: the page's (the scene's background) or black
    if drawn < len(band) // 100:
        if max(abs(a - b) for a, b in zip(common, CANVAS_BACKGROUND)) > 8:
            return [f"the canvas was not rendered: it is {common} all over, not the scene's background {CANVAS_BACKGROUND}"]
        return [f"the canvas shows almost nothing: {drawn} of {len(band)} pixels differ from its background"]
    return []


def expected_frames(text):
    """The frame count the page should show: of its first replay."""
    match = re.search(r'<script type="application/json" id="physlab-data">(.*?)</script>', text, re.S)
    data = json.loads(match.group(1))
    if "error" in data:
        raise ReplayError(f"the page shows an error: {data['error']}")
    first = data["replays"][0]
    return len(parse_replay(base64.b64decode(first["base64"]), first["name"])["frames"])


def element_text(dom, element_id):
    match = re.search(rf'<[^>]*\bid="{element_id}"[^>]*>([^<]*)<', dom)
    return html.unescape(match.group(1)) if match else None


def measure(browser, page):
    """The page's own timing of showing every frame (#measure), as it writes it into #measured."""
    with tempfile.TemporaryDirectory(prefix="physlab-view-") as tmp:
        dom = chromium(browser, page, Path(tmp) / "profile", ["--dump-dom"], "#frame=1&contacts&measure",
                       virtual_time=False)
    return element_text(dom, "measured") or "no timing: the page did not finish showing its frames"


def check(browser, page):
    problems = []
    text = page.read_text(encoding="utf-8")
    urls = named_urls(text)
    if urls:
        problems.append(f"names URLs outside three.js: {', '.join(urls[:5])}")
    frames = expected_frames(text)
    with tempfile.TemporaryDirectory(prefix="physlab-view-") as tmp:
        netlog, shot = Path(tmp) / "netlog.json", Path(tmp) / "shot.png"
        chromium(browser, page, Path(tmp) / "profile-1", [f"--log-net-log={netlog}", f"--screenshot={shot}"],
                 "#frame=last")
        requests = page_requests(netlog)
        if requests:
            problems.append(f"asked the network for {', '.join(requests[:5])}")
        problems += canvas_problems(shot)
        dom = chromium(browser, page, Path(tmp) / "profile-2", ["--dump-dom"], "#frame=last")
    shown = (element_text(dom, "frame-index"), element_text(dom, "frame-count"))
    if shown != (str(frames), str(frames)):
        problems.append(f"at #frame=last it shows frame {shown[0]} of {shown[1]}, not {frames} of {frames}")
    legend = re.search(r'<span id="energy-legend">(.*?)</span><span id="legend-reference"', dom, re.S)
    if not legend or not re.search(r"\[J\]|drift", legend.group(1)):
        problems.append("the energy plot's legend names neither joules nor drift: "
                        f"{legend.group(1) if legend else 'no legend'}")
    error = re.search(r'<div id="error"(?![^>]*hidden)[^>]*>([^<]*)<', dom)
    if error:
        problems.append(f"shows an error: {html.unescape(error.group(1))}")
    return problems, frames


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("pages", nargs="+", type=Path)
    parser.add_argument("--measure", action="store_true", help="also print the time each page takes per frame")
    args = parser.parse_args()
    browser = headless.find_browser()
    if browser is None:
        print("check_view: skipped: chromium not installed (apt-get install chromium)")
        return 0
    failed = False
    for page in args.pages:
        try:
            problems, frames = check(browser, page)
        except (OSError, RuntimeError, ReplayError, subprocess.TimeoutExpired) as e:
            problems, frames = [str(e)], 0
        for problem in problems:
            print(f"{page}: {problem}")
        if not problems:
            print(f"{page}: ok (offline, no request, canvas drawn, frame {frames} of {frames} at #frame=last)")
        if args.measure and not problems:
            print(f"{page}: showing every frame in turn, contacts drawn: {measure(browser, page)}")
        failed |= bool(problems)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
