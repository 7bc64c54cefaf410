"""The Gradescope autograder zip: the tracked files grading needs (GRADING_FILES) under physlab/,
with setup.sh and run_autograder at its top level, and a course file if given.
"""

import re
import subprocess
import sys
import zipfile
from pathlib import Path

import course as course_file  # tools/course.py, beside the package

from .common import ROOT

# What grading needs, and all the autograder zip holds (the Grading page, "The Gradescope zip"):
# the driver and the CMake files that configure the tree (PhysLabDocs.cmake reads Doxyfile.in when
# Doxygen is installed), the framework, the reference, the stubs (the grader compiles a
# submission's missing files from them), the visible and hidden tests with their support, the
# handouts (a failed test's report names a section) and this grader (its modules, not its tests). No mutant catalogue, no
# hostile submissions, no demos or benchmarks (their folders are globbed: absent, they add no
# target), no other tool.
GRADING_FILES = re.compile(r"^(physlab|CMakeLists\.txt|cmake/PhysLab(Dependencies|Docs)?\.cmake|"
                           r"common/.*|solutions/.*|labs/.*|tests/(?!hidden/(mutants|adversarial)/).*|"
                           r"docs/lab\d\d_[a-z0-9_]+\.md|docs/Doxyfile\.in|tools/(course|remote_gen)\.py|"
                           r"tools/grader/[a-z_]+\.py)$")


def cmd_gradescope(args) -> int:
    """Writes the Gradescope autograder zip: the tracked files grading needs (GRADING_FILES) under
    physlab/, with setup.sh and run_autograder at its top level; with a course file, that file as
    physlab/course.toml, which run_autograder then grades with."""
    course = None
    if args.course:
        try:
            course = course_file.load(args.course)
        except course_file.CourseError as error:
            print(f"grader: course file {error}; no zip written", file=sys.stderr)
            return 2
        print(course.summary())
    listing = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True)
    if listing.returncode != 0:  # not a checkout, or one git will not read (owned by another user)
        why = listing.stderr.decode(errors="replace").strip().splitlines()
        print(f"grader: gradescope: the zip holds the files git tracks, and git cannot list them in {ROOT}: "
              f"{why[0] if why else 'status ' + str(listing.returncode)}"
              + (f"\n  if you trust this folder: git config --global --add safe.directory {ROOT}"
                 if any("safe.directory" in line for line in why) else "") + "\nno zip written", file=sys.stderr)
        return 2
    tracked = listing.stdout.decode().split("\0")
    files = [f for f in tracked if GRADING_FILES.match(f)]
    out = Path(args.out).resolve()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        for name in files:
            z.write(ROOT / name, f"physlab/{name}")
        for script in ("setup.sh", "run_autograder"):
            info = zipfile.ZipInfo(script)
            info.external_attr = 0o755 << 16
            z.writestr(info, (ROOT / "tools" / "gradescope" / script).read_text())
        if course is not None:
            z.write(Path(args.course), "physlab/course.toml")
    print(f"wrote {out} ({len(files)} of the {len([f for f in tracked if f])} tracked files"
          f"{', and the course file' if course else ''}, {out.stat().st_size // 1024} KiB)")
    return 0
