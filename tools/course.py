#!/usr/bin/env python3
"""An instructor's course: which labs and sections count, their points, which tests are hidden or
left out, and the grader's time limits, from a TOML file (the Grading page, "A course file").

    course.py check FILE          validate FILE against this tree; print each lab's points
    course.py publish FILE DEST   trim the student copy DEST (written by ./physlab publish) to the
                                  course; print the labs left out that a course lab builds on

The grader (`grade --course`), `./physlab publish --course` and `./physlab gradescope --course`
read the file through `load()`. Without a file the course is every lab, section and test of the
tree at the points of their tags: today's grading exactly.
"""

import json
import math
import re
import shutil
import sys
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
STAGE_RE = re.compile(r"^(\d\d)_[a-z0-9_]+$")
# Every graded test's name and tags are on its TEST_CASE line (the project's rule), so the course
# is checked against the sources, before anything is built or graded.
TEST_CASE_RE = re.compile(r'^TEST_CASE\("((?:[^"\\]|\\.)*)",\s*"([^"]*)"\)', re.MULTILINE)
SECTIONS_RE = re.compile(r"^// Lab \d+, sections? ([0-9, and-]+):")
TOP_KEYS = {"name", "limits", "labs"}
LIMIT_KEYS = {"deadline": 600.0 * 10, "test": 3600.0, "compile": 3600.0}  # key -> largest value
LAB_KEYS = {"points", "sections", "section_points", "hidden", "drop"}
DEFAULT_LIMITS = {"deadline": 540.0, "test": 30.0, "compile": 120.0}


class CourseError(ValueError):
    """A course file that cannot be used; the message names the file, key, lab, test or value."""


@dataclass
class Test:
    stage: str
    name: str
    tags: list
    raw: float                 # the points of its [pts=N] tag
    points: float = 0.0        # in this course
    hidden: bool = False       # shown to students only after publication

    @property
    def sections(self) -> list:
        return sorted({int(t[4:]) for t in self.tags if re.fullmatch(r"sec=\d+", t)})

    @property
    def group(self) -> int:
        """The test group (handout section) whose points it shares: its highest [sec=N] (a test
        of several sections is a scene that ends in the last of them)."""
        return self.sections[-1] if self.sections else 0


@dataclass
class Lab:
    stage: str
    points: float = 0.0
    sections: list = field(default_factory=list)
    tests: dict = field(default_factory=dict)  # name -> Test, the lab's tests in the course


@dataclass
class Course:
    name: str
    path: object                               # the file, or None for the default course
    labs: dict                                 # stage -> Lab, in lab order
    limits: dict

    def test(self, stage: str, name: str):
        lab = self.labs.get(stage)
        return lab.tests.get(name) if lab else None

    def summary(self) -> str:
        lines = [f"course: {self.name}" + (f" ({self.path})" if self.path else " (default: the whole tree)")]
        for lab in self.labs.values():
            visible = sum(1 for t in lab.tests.values() if not t.hidden)
            lines.append(f"  lab {lab.stage}: {lab.points:g} points, sections "
                         f"{', '.join(map(str, lab.sections))}; {len(lab.tests)} tests "
                         f"({visible} visible, {len(lab.tests) - visible} hidden)")
        lines.append("  limits: " + ", ".join(f"{k} {v:g} s" for k, v in self.limits.items()))
        return "\n".join(lines)


def stages(root: Path = ROOT) -> list:
    return sorted(p.name for p in (root / "tests").iterdir() if p.is_dir() and STAGE_RE.match(p.name))


def section_table(root: Path, stage: str) -> dict:
    """Handout section -> lab file, from the first line of each labs/NN_name/*.cpp."""
    table = {}
    for path in sorted((root / "labs" / stage).glob("*.cpp")):
        first = path.read_text(encoding="utf-8", errors="replace").split("\n", 1)[0]
        m = SECTIONS_RE.match(first)
        for low, high in re.findall(r"(\d+)(?:-(\d+))?", m.group(1) if m else ""):
            for number in range(int(low), int(high or low) + 1):
                table[number] = path.stem
    return table


def unescape(name: str) -> str:
    return re.sub(r"\\(.)", r"\1", name)


def tree_tests(root: Path, stage: str) -> list:
    """The graded tests of a lab, visible and hidden, from their TEST_CASE lines."""
    found = []
    files = sorted((root / "tests" / stage).glob("*.cpp")) + sorted((root / "tests" / "hidden" / stage).glob("*.cpp"))
    for path in files:
        for name, tags in TEST_CASE_RE.findall(path.read_text(encoding="utf-8", errors="replace")):
            tag_list = re.findall(r"\[([^\]]*)\]", tags)
            pts = [float(t[4:]) for t in tag_list if re.fullmatch(r"pts=\d+(\.\d+)?", t)]
            if pts and pts[0] > 0 and "common" not in tag_list:
                found.append(Test(stage, unescape(name), tag_list, pts[0], pts[0], "hidden" in tag_list))
    return found


def pick_stage(key: str, all_stages: list, where: str) -> str:
    """The stage a course key names: "01", "1" or "01_particles"."""
    for s in all_stages:
        if key == s or (key.isdigit() and len(key) <= 2 and s[:2] == key.zfill(2)):
            return s
    raise CourseError(f"{where}: no lab '{key}' in this tree (labs: {', '.join(all_stages)})")


def number(value, where: str, allow_zero: bool = True) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or value != value:
        raise CourseError(f"{where}: {value!r} is not a number")
    if value < 0 or (value == 0 and not allow_zero) or value == float("inf"):
        raise CourseError(f"{where}: {value!r} must be {'positive' if not allow_zero else 'zero or more'} and finite")
    return float(value)


def matches(test: Test, selector: str) -> bool:
    if selector.startswith("[") and selector.endswith("]"):
        return selector[1:-1] in test.tags
    return test.name == selector


def select(tests: list, selectors, where: str) -> set:
    """The names of the tests a list of names and [tags] picks; each entry must pick one."""
    if not isinstance(selectors, list) or not all(isinstance(s, str) for s in selectors):
        raise CourseError(f"{where}: a list of test names and [tags] was expected, got {selectors!r}")
    picked = set()
    for s in selectors:
        hit = {t.name for t in tests if matches(t, s)}
        if not hit:
            kind = "tag" if s.startswith("[") else "test"
            raise CourseError(f"{where}: no {kind} {s!r} among this lab's graded tests"
                              + (" in the course" if "hidden" in where else ""))
        picked |= hit
    return picked


def scale(lab: Lab, section_points: dict, where: str) -> None:
    """Rescales the lab's tests: each section with points of its own to those points, the other
    sections together to what is left of the lab's points (or kept as they are)."""
    groups = {}
    for t in lab.tests.values():
        groups.setdefault(t.group, []).append(t)
    for s in section_points:
        if s not in groups:
            raise CourseError(f"{where}.section_points: section {s} has no graded test in this course")
    fixed = sum(section_points.values())
    rest = [t for t in lab.tests.values() if t.group not in section_points]
    rest_raw = sum(t.raw for t in rest)
    if lab.points is None:
        factor = 1.0
        lab.points = fixed + rest_raw
    else:
        if fixed > lab.points + 1e-9:
            raise CourseError(f"{where}: section_points add up to {fixed:g}, more than the lab's {lab.points:g} points")
        if not rest and abs(fixed - lab.points) > 1e-9:
            raise CourseError(f"{where}: section_points add up to {fixed:g}, not the lab's {lab.points:g} points, "
                              f"and no other section is left to take the rest")
        factor = (lab.points - fixed) / rest_raw if rest_raw else 0.0
    apportion(rest, factor * rest_raw)
    for s, total in section_points.items():
        apportion(groups[s], total)


def apportion(tests: list, total: float) -> None:
    """Shares `total` among `tests` in proportion to their tags' points, each share a whole number
    of 1e-4 points and the shares adding up to `total` to 1e-4 exactly (largest remainder): rounding
    each share alone would let a lab of 100 points grade out of 100.0001."""
    raw = sum(t.raw for t in tests)
    units = round(total * 10000)
    exact = [t.raw * units / raw if raw else 0.0 for t in tests]
    shares = [math.floor(e) for e in exact]
    by_remainder = sorted(range(len(tests)), key=lambda i: shares[i] - exact[i])
    for i in by_remainder[:units - sum(shares)]:
        shares[i] += 1
    for t, share in zip(tests, shares):
        t.points = share / 10000

def default(root: Path = ROOT) -> Course:
    """Every lab, section and test of the tree at their tags' points."""
    labs = {}
    for stage in stages(root):
        tests = tree_tests(root, stage)
        labs[stage] = Lab(stage, sum(t.raw for t in tests), sorted(section_table(root, stage)),
                          {t.name: t for t in tests})
    return Course("default", None, labs, dict(DEFAULT_LIMITS))


def parse(data: dict, root: Path = ROOT, path=None) -> Course:
    """A course from the parsed TOML `data`; raises CourseError naming what is wrong."""
    where = str(path or "course")
    unknown = set(data) - TOP_KEYS
    if unknown:
        raise CourseError(f"{where}: unknown key '{sorted(unknown)[0]}' (keys: {', '.join(sorted(TOP_KEYS))})")
    name = data.get("name", Path(path).stem if path else "course")
    if not isinstance(name, str):
        raise CourseError(f"{where}: name: {name!r} is not text")
    limits = dict(DEFAULT_LIMITS)
    given = data.get("limits", {})
    if not isinstance(given, dict):
        raise CourseError(f"{where}: limits must be a table ([limits])")
    for key, value in given.items():
        if key not in LIMIT_KEYS:
            raise CourseError(f"{where}: limits: unknown key '{key}' (keys: {', '.join(LIMIT_KEYS)})")
        limits[key] = number(value, f"{where}: limits.{key}", allow_zero=False)
        if limits[key] > LIMIT_KEYS[key]:
            raise CourseError(f"{where}: limits.{key}: {value!r} seconds is more than {LIMIT_KEYS[key]:g}")
    if "labs" not in data or not isinstance(data["labs"], dict) or not data["labs"]:
        raise CourseError(f"{where}: no labs: name at least one, e.g. [labs.01]")
    all_stages = stages(root)
    labs = {}
    for key, spec in data["labs"].items():
        at = f"{where}: labs.{key}"
        stage = pick_stage(key, all_stages, at)
        if stage in labs:
            raise CourseError(f"{at}: lab {stage} is named twice")
        if not isinstance(spec, dict):
            raise CourseError(f"{at}: must be a table ([labs.{key}])")
        unknown = set(spec) - LAB_KEYS
        if unknown:
            raise CourseError(f"{at}: unknown key '{sorted(unknown)[0]}' (keys: {', '.join(sorted(LAB_KEYS))})")
        table = section_table(root, stage)
        sections = spec.get("sections", sorted(table))
        if not isinstance(sections, list) or not sections or \
                not all(isinstance(s, int) and not isinstance(s, bool) for s in sections):
            raise CourseError(f"{at}.sections: a list of section numbers was expected, got {sections!r}")
        for s in sections:
            if s not in table:
                raise CourseError(f"{at}.sections: lab {stage} has no section {s} "
                                  f"(its sections: {', '.join(map(str, sorted(table)))})")
        tests = [t for t in tree_tests(root, stage) if t.sections and set(t.sections) <= set(sections)]
        dropped = select(tree_tests(root, stage), spec.get("drop", []), f"{at}.drop")
        tests = [t for t in tests if t.name not in dropped]
        made_hidden = select(tests, spec.get("hidden", []), f"{at}.hidden")
        for t in tests:
            t.hidden = t.hidden or t.name in made_hidden
        if not tests:
            raise CourseError(f"{at}: no graded test left in this lab (sections {sections}, drop)")
        section_points = {}
        given = spec.get("section_points", {})
        if not isinstance(given, dict):
            raise CourseError(f"{at}.section_points: a table of section = points was expected")
        for s, pts in given.items():
            if not str(s).isdigit() or int(s) not in table:
                raise CourseError(f"{at}.section_points: lab {stage} has no section {s!r}")
            if int(s) not in sections:
                raise CourseError(f"{at}.section_points: section {s} is not in this lab's sections {sections}")
            section_points[int(s)] = number(pts, f"{at}.section_points.{s}")
        lab = Lab(stage, None if "points" not in spec else number(spec["points"], f"{at}.points"),
                  sorted(sections), {t.name: t for t in tests})
        scale(lab, section_points, at)
        labs[stage] = lab
    return Course(name, path, dict(sorted(labs.items())), limits)


def load(path, root: Path = ROOT) -> Course:
    """The course of the file at `path` (None: the default course)."""
    if path is None:
        return default(root)
    path = Path(path)
    if not path.is_file():
        raise CourseError(f"{path}: no such course file")
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as error:
        raise CourseError(f"{path}: not valid TOML: {error}") from None
    return parse(data, root, path)


def visible_points(course: Course) -> dict:
    """{stage: {test name: points}} of the course's visible tests: what a student copy's Classroom
    workflow grades (hidden tests and their names stay out of the copy)."""
    return {s: {t.name: t.points for t in lab.tests.values() if not t.hidden}
            for s, lab in course.labs.items()}


ADD_LAB_RE = re.compile(r"^physlab_add_lab\((\d\d_[a-z0-9_]+)(?: DEPENDS ([^)]*))?\)\s*$", re.MULTILINE)
POINTS_FILE = "tools/course-points.json"  # in a student copy: the course's points of its tests


def publish(course: Course, dest: Path) -> list:
    """Trims a student copy to the course: the labs left out lose their stubs, tests, demo,
    benchmark, scenes and handout (links to the handout become plain text); the copy gets the
    course's points of its visible tests (POINTS_FILE, read by ./physlab test and Classroom).
    Returns the labs left out that a lab of the course builds on: they ship as their released
    reference (released/NN_name), which that lab then links, and keep their line in CMakeLists.txt."""
    cmake = dest / "CMakeLists.txt"
    text = cmake.read_text(encoding="utf-8")
    depends = {m.group(1): (m.group(2) or "").split() for m in ADD_LAB_RE.finditer(text)}
    needed = set()
    for stage in course.labs:
        needed |= set(depends.get(stage, []))
    dropped = [s for s in stages(dest) if s not in course.labs]
    for stage in dropped:
        for folder in ("labs", "tests", "demos", "bench", "views"):
            shutil.rmtree(dest / folder / stage, ignore_errors=True)
        for handout in (dest / "docs").glob(f"lab{stage[:2]}_*.md"):
            handout.unlink()
        if stage not in needed:
            text = re.sub(rf"^physlab_add_lab\({stage}\b[^)]*\)\s*\n", "", text, flags=re.MULTILINE)
    cmake.write_text(text, encoding="utf-8")
    gone = tuple(s[:2] for s in dropped)
    for doc in (dest / "docs").glob("*.md"):
        lines = doc.read_text(encoding="utf-8").split("\n")
        # a table row that only points to a handout left out goes; any other link becomes text
        lines = [l for l in lines if not re.match(rf"^\|.*\\ref lab({'|'.join(gone)})_\w+ \|$", l)] if gone else lines
        fixed = "\n".join(lines)
        if gone:
            fixed = re.sub(rf"\\ref lab({'|'.join(gone)})_\w+",
                           lambda m: f"Lab {int(m.group(1))}'s handout (not part of this course)", fixed)
        doc.write_text(fixed, encoding="utf-8")
    (dest / POINTS_FILE).parent.mkdir(parents=True, exist_ok=True)
    (dest / POINTS_FILE).write_text(json.dumps(visible_points(course), indent=1) + "\n", encoding="utf-8")
    return sorted(needed & set(dropped))


def main(argv: list) -> int:
    if not ((len(argv) == 3 and argv[1] == "check") or (len(argv) == 4 and argv[1] == "publish")):
        print(__doc__, file=sys.stderr)
        return 2
    try:
        course = load(argv[2])
    except CourseError as error:
        print(f"course: {error}", file=sys.stderr)
        return 2
    if argv[1] == "check":
        print(course.summary())
    else:
        print("\n".join(publish(course, Path(argv[3]))))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
