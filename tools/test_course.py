#!/usr/bin/env python3
"""Tests of the course file (tools/course.py), the grader's checks of submission folders and the
hint tables: python3 tools/test_course.py (CI runs it; about a second, nothing built)."""

import json
import subprocess
import sys
import tempfile
import tomllib
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import course  # noqa: E402
from grader import common, failures, hints, submission, tree  # noqa: E402

LAB_A = {
    "labs/01_alpha/forces.cpp": "// Lab 1, sections 1-2: forces.\n",
    "labs/01_alpha/steps.cpp": "// Lab 1, section 3: steps.\n",
    "tests/01_alpha/test_a.cpp": (
        'TEST_CASE("gravity pulls down", "[lab01][pts=2][sec=1]") {}\n'
        'TEST_CASE("springs pull back", "[lab01][pts=2][sec=2]") {}\n'
        'TEST_CASE("a \\"quoted\\" step", "[lab01][pts=1][sec=3]") {}\n'
        'TEST_CASE("a scene of forces and steps", "[lab01][pts=3][sec=1][sec=3]") {}\n'
        'TEST_CASE("framework helper", "[common]") {}\n'),
    "tests/hidden/01_alpha/test_h.cpp":
        'TEST_CASE("hidden: drag slows", "[lab01][pts=2][hidden][sec=2]") {}\n',
    "labs/02_beta/solve.cpp": "// Lab 2, section 1: solving.\n",
    "tests/02_beta/test_b.cpp": 'TEST_CASE("it solves", "[lab02][pts=4][sec=1]") {}\n'
                                'TEST_CASE("it solves fast", "[lab02][pts=6][sec=1]") {}\n',
}


class Tree(unittest.TestCase):
    """A made-up tree of two labs, so that each rule is checked on numbers worked out by hand."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name)
        for path, text in LAB_A.items():
            (self.root / path).parent.mkdir(parents=True, exist_ok=True)
            (self.root / path).write_text(text)

    def tearDown(self):
        self.tmp.cleanup()

    def parse(self, text: str) -> course.Course:
        return course.parse(tomllib.loads(text), self.root, "c.toml")

    def refused(self, text: str, *words) -> str:
        with self.assertRaises(course.CourseError) as caught:
            self.parse(text)
        message = str(caught.exception)
        for word in words:
            self.assertIn(word, message)
        return message


class DefaultCourse(Tree):
    def test_every_graded_test_at_its_tags_points(self):
        c = course.default(self.root)
        self.assertEqual(list(c.labs), ["01_alpha", "02_beta"])
        self.assertEqual(c.labs["01_alpha"].points, 2 + 2 + 1 + 3 + 2)  # the framework test grades nothing
        self.assertEqual(c.test("01_alpha", 'a "quoted" step').points, 1)  # escaped quotes read back
        self.assertTrue(c.test("01_alpha", "hidden: drag slows").hidden)
        self.assertEqual(c.limits, course.DEFAULT_LIMITS)

    def test_the_real_tree_default_is_its_tags(self):
        c = course.default()
        for lab in c.labs.values():
            for t in lab.tests.values():
                self.assertEqual(t.points, t.raw, t.name)


class Scaling(Tree):
    def test_lab_points_rescale_every_test(self):
        c = self.parse("[labs.01]\npoints = 20\n")
        lab = c.labs["01_alpha"]
        self.assertEqual(lab.points, 20)
        self.assertAlmostEqual(sum(t.points for t in lab.tests.values()), 20)
        self.assertAlmostEqual(c.test("01_alpha", "gravity pulls down").points, 2 * 20 / 10)
        self.assertEqual(list(c.labs), ["01_alpha"])  # lab 2 left out

    def test_section_points_then_the_rest(self):
        # section 3's group: the step (1) and the scene (3, its highest section is 3) -> 6 points;
        # the other 6 raw points (sections 1, 2 and hidden 2) share the 14 left
        c = self.parse("[labs.1]\npoints = 20\nsection_points = { 3 = 6 }\n")
        self.assertAlmostEqual(c.test("01_alpha", 'a "quoted" step').points, 1.5)
        self.assertAlmostEqual(c.test("01_alpha", "a scene of forces and steps").points, 4.5)
        self.assertAlmostEqual(c.test("01_alpha", "gravity pulls down").points, 2 * 14 / 6, delta=1e-4)

    def test_shares_add_up_to_the_points_exactly(self):
        # 14 points in thirds: 4.6667 + 4.6667 + 4.6666, never 14.0001 (each share rounded alone)
        c = self.parse("[labs.1]\npoints = 20\nsection_points = { 3 = 6 }\n")
        rest = [t.points for t in c.labs["01_alpha"].tests.values() if t.group != 3]
        self.assertEqual(round(sum(rest) * 10000), 140000)
        self.assertEqual(sorted(round(p * 10000) for p in rest), [46666, 46667, 46667])
        for points in (100, 7, 0.0001):  # a fixed lab total, one that divides badly, one unit
            lab = self.parse(f"[labs.01]\npoints = {points}\n").labs["01_alpha"]
            self.assertEqual(round(sum(t.points for t in lab.tests.values()) * 10000), round(points * 10000))

    def test_section_points_without_lab_points_keep_the_rest(self):
        c = self.parse("[labs.01_alpha]\nsection_points = { 3 = 8 }\n")
        self.assertEqual(c.labs["01_alpha"].points, 8 + 6)
        self.assertEqual(c.test("01_alpha", "springs pull back").points, 2)

    def test_sections_leave_out_tests_that_need_another_section(self):
        c = self.parse("[labs.01]\nsections = [1, 2]\n")
        names = set(c.labs["01_alpha"].tests)
        self.assertEqual(names, {"gravity pulls down", "springs pull back", "hidden: drag slows"})

    def test_hidden_and_drop_by_name_and_tag(self):
        c = self.parse('[labs.01]\nhidden = ["[sec=1]"]\ndrop = ["springs pull back"]\n')
        lab = c.labs["01_alpha"]
        self.assertNotIn("springs pull back", lab.tests)
        self.assertTrue(lab.tests["gravity pulls down"].hidden)
        self.assertTrue(lab.tests["a scene of forces and steps"].hidden)
        self.assertFalse(lab.tests['a "quoted" step'].hidden)

    def test_limits(self):
        c = self.parse("[limits]\ntest = 10\ndeadline = 300\n[labs.02]\n")
        self.assertEqual(c.limits, {"deadline": 300.0, "test": 10.0, "compile": 120.0})


class Refusals(Tree):
    def test_unknown_lab(self):
        self.refused("[labs.07]\n", "labs.07", "no lab '07'", "01_alpha, 02_beta")

    def test_unknown_section(self):
        self.refused("[labs.01]\nsections = [1, 9]\n", "labs.01.sections", "no section 9", "1, 2, 3")

    def test_unknown_test_and_tag(self):
        self.refused('[labs.01]\nhidden = ["gravity pushes up"]\n', "labs.01.hidden", "gravity pushes up")
        self.refused('[labs.01]\ndrop = ["[sec=8]"]\n', "labs.01.drop", "no tag '[sec=8]'")

    def test_negative_points(self):
        self.refused("[labs.01]\npoints = -5\n", "labs.01.points", "-5")
        self.refused("[labs.01]\nsection_points = { 2 = -1 }\n", "labs.01.section_points.2", "-1")

    def test_points_that_are_no_number(self):
        self.refused('[labs.01]\npoints = "ten"\n', "labs.01.points", "'ten'")
        self.refused("[labs.01]\npoints = true\n", "labs.01.points")

    def test_section_points_beyond_the_lab(self):
        self.refused("[labs.01]\npoints = 5\nsection_points = { 3 = 6 }\n", "add up to 6", "5 points")

    def test_unknown_keys(self):
        self.refused("[labs.01]\npoint = 5\n", "labs.01", "unknown key 'point'")
        self.refused("title = 'x'\n[labs.01]\n", "unknown key 'title'")
        self.refused("[limits]\ntimeout = 5\n[labs.01]\n", "limits", "unknown key 'timeout'")

    def test_bad_limits(self):
        self.refused("[limits]\ntest = 0\n[labs.01]\n", "limits.test", "positive")
        self.refused("[limits]\ndeadline = -1\n[labs.01]\n", "limits.deadline")

    def test_no_labs_and_a_lab_named_twice(self):
        self.refused("name = 'x'\n", "no labs")
        self.refused("[labs.01]\n[labs.1]\n", "named twice")

    def test_everything_dropped(self):
        self.refused('[labs.02]\ndrop = ["[sec=1]"]\n', "labs.02", "no graded test left")

    def test_a_section_point_of_a_section_left_out(self):
        self.refused("[labs.01]\nsections = [1]\nsection_points = { 2 = 3 }\n", "section 2 is not in")

    def test_load_names_the_file(self):
        bad = self.root / "bad.toml"
        bad.write_text("[labs.01\n")
        with self.assertRaises(course.CourseError) as caught:
            course.load(bad, self.root)
        self.assertIn("bad.toml: not valid TOML", str(caught.exception))
        with self.assertRaises(course.CourseError):
            course.load(self.root / "missing.toml", self.root)


class Submissions(Tree):
    def test_missing_file_and_empty_folders(self):
        empty = self.root / "empty"
        empty.mkdir()
        afile = self.root / "a.zip"
        afile.write_text("x")
        good = self.root / "labs"
        problems = submission.submission_problems([str(empty), str(afile), str(self.root / "nope"), str(good)])
        self.assertEqual(len(problems), 3, problems)
        self.assertIn("empty: the folder is empty", problems[0])
        self.assertIn("a.zip: not a folder", problems[1])
        self.assertIn("nope: no such folder", problems[2])

    def test_two_submissions_of_one_name(self):
        (self.root / "x" / "alice").mkdir(parents=True)
        (self.root / "y" / "alice").mkdir(parents=True)
        for d in ("x", "y"):
            (self.root / d / "alice" / "f").write_text("")
        problems = submission.submission_problems([str(self.root / "x" / "alice"), str(self.root / "y" / "alice")])
        self.assertEqual(problems, ["two submissions named alice: each is graded into --out/<name>/"])


class Publish(Tree):
    def test_a_copy_keeps_only_the_course(self):
        (self.root / "CMakeLists.txt").write_text("physlab_add_lab(01_alpha)\n"
                                                  "physlab_add_lab(02_beta DEPENDS 01_alpha)\n")
        (self.root / "docs").mkdir()
        (self.root / "docs" / "lab01_alpha.md").write_text("# Lab 1 {#lab01_alpha}\n")
        (self.root / "docs" / "mainpage.md").write_text(
            "| 1 | alpha | \\ref lab01_alpha |\n| 2 | beta | \\ref lab02_beta |\nsee \\ref lab01_forces.\n")
        c = self.parse("[labs.02]\npoints = 5\n")
        needed = course.publish(c, self.root)
        self.assertEqual(needed, ["01_alpha"])  # lab 2 builds on it: it ships released
        self.assertFalse((self.root / "labs" / "01_alpha").exists())
        self.assertFalse((self.root / "tests" / "01_alpha").exists())
        self.assertFalse((self.root / "docs" / "lab01_alpha.md").exists())
        self.assertIn("physlab_add_lab(01_alpha)", (self.root / "CMakeLists.txt").read_text())
        self.assertEqual((self.root / "docs" / "mainpage.md").read_text(),
                         "| 2 | beta | \\ref lab02_beta |\nsee Lab 1's handout (not part of this course).\n")
        points = json.loads((self.root / course.POINTS_FILE).read_text())
        self.assertEqual(points, {"02_beta": {"it solves": 2.0, "it solves fast": 3.0}})
        # the copy's ./physlab test (and so its Classroom workflow) grades at the course's points
        saved, tree.ROOT = tree.ROOT, self.root
        try:
            cases = [common.TestCase("02_beta", "it solves fast", ["lab02", "pts=6", "sec=1"]),
                     common.TestCase("02_beta", "not in the course", ["lab02", "pts=1", "sec=1"])]
            self.assertEqual([(c.name, c.points) for c in tree.course_points("02_beta", cases)],
                             [("it solves fast", 3.0)])
        finally:
            tree.ROOT = saved

    def test_a_lab_nothing_builds_on_leaves_cmake(self):
        (self.root / "CMakeLists.txt").write_text("physlab_add_lab(01_alpha)\n"
                                                  "physlab_add_lab(02_beta DEPENDS 01_alpha)\n")
        (self.root / "docs").mkdir()
        self.assertEqual(course.publish(self.parse("[labs.01]\n"), self.root), [])
        self.assertEqual((self.root / "CMakeLists.txt").read_text(), "physlab_add_lab(01_alpha)\n")


class GradeBuilds(unittest.TestCase):
    """`./physlab grade` builds the tests of the labs it grades only (tools/grader stages)."""

    def stages(self, *args) -> list:
        out = subprocess.run([sys.executable, str(Path(common.__file__).parent), "stages", *args],
                             check=True, capture_output=True, text=True).stdout
        return out.split()

    def test_a_course_builds_its_labs_only(self):
        example = Path(common.__file__).parent.parent / "course-example.toml"
        self.assertEqual(self.stages("labs", "--course", str(example)), list(course.load(example).labs))

    def test_labs_named_on_the_command_line(self):
        self.assertEqual(self.stages("labs", "--labs", "5", "03"), ["05_impulses", "03_rigid_bodies"])

    def test_a_bad_course_or_lab_builds_every_lab_for_the_grade_to_refuse(self):
        every = common.discover_stages(common.ROOT)
        with tempfile.NamedTemporaryFile("w", suffix=".toml") as bad:
            bad.write("labs = 3\n")
            bad.flush()
            self.assertEqual(self.stages("labs", "--course", bad.name), every)
        self.assertEqual(self.stages("labs", "--labs", "99"), every)
        self.assertEqual(self.stages("labs"), every)


class Hints(Tree):
    """The hint tables: shown for a test that broke, measured values only when found, and no
    hidden test's hint that could give its expected value away."""

    def setUp(self):
        super().setUp()
        self.saved = hints.ROOT
        hints.ROOT = self.root
        hints.hint_table.cache_clear()
        (self.root / "tests" / "01_alpha" / "hints.toml").write_text(
            '"gravity pulls down" = "gravity is m g on every free particle"\n'
            '["springs pull back"]\ntext = "the force points along the spring"\n'
            'measured = "Your force was {lhs} at k = {k}."\n')

    def tearDown(self):
        hints.ROOT = self.saved
        hints.hint_table.cache_clear()
        super().tearDown()

    def case(self, name: str, status: str, captured: dict) -> common.TestCase:
        return common.TestCase("01_alpha", name, ["lab01", "pts=2", "sec=1"], status=status, captured=captured)

    def test_shown_when_the_test_broke(self):
        self.assertEqual(hints.hint_of(self.case("gravity pulls down", "failed", {})),
                         "hint: gravity is m g on every free particle")
        self.assertEqual(hints.hint_of(self.case("gravity pulls down", "timed out", {})),
                         "hint: gravity is m g on every free particle")
        for status in ("passed", "not implemented", "not compiled", "not run"):
            self.assertEqual(hints.hint_of(self.case("gravity pulls down", status, {})), "", status)

    def test_measured_only_with_every_field(self):
        whole = self.case("springs pull back", "failed", {"lhs": "-3.5", "rhs": "3.5", "k": "10"})
        self.assertEqual(hints.hint_of(whole), "hint: the force points along the spring "
                                                "Your force was -3.5 at k = 10.")
        part = self.case("springs pull back", "failed", {"lhs": "-3.5"})
        self.assertEqual(hints.hint_of(part), "hint: the force points along the spring")

    def test_the_failure_gives_the_fields(self):
        output = ('<Catch><Group><TestCase><Info>k := 10</Info><Expression success="false" type="CHECK" '
                  'filename="t.cpp" line="7"><Original>f == Approx(3.5)</Original><Expanded>-3.5 == '
                  'Approx( 3.5 )</Expanded></Expression></TestCase></Group></Catch>')
        status, _, checks, captured = failures.describe_failure(output)
        self.assertEqual((status, checks), ("failed", ["t.cpp:7: f == Approx(3.5)"]))
        self.assertEqual(captured, {"k": "10", "lhs": "-3.5", "rhs": "Approx( 3.5 )"})
        wrapped = output.replace("-3.5 == Approx( 3.5 )", "-3.50000012\n==\nApprox( 3.5 )")
        self.assertEqual(failures.describe_failure(wrapped)[3]["lhs"], "-3.5")

    def test_problems(self):
        self.assertEqual(hints.hint_problems(["01_alpha"]), [])
        (self.root / "tests" / "hidden" / "01_alpha" / "hints.toml").write_text(
            '"hidden: drag slows" = "drag is 0.5 v"\n'
            '"springs pull back" = "a visible test in the hidden table"\n'
            '["hidden: drag slows x"]\ntext = "t"\nmeasured = "expected {rhs}"\n')
        problems = "\n".join(hints.hint_problems(["01_alpha"]))
        self.assertIn("'hidden: drag slows': a hidden test's hint may hold no number", problems)
        self.assertIn("no hidden graded test named 'springs pull back'", problems)
        self.assertIn("{rhs} is a hidden test's expected side", problems)

    def test_the_trees_tables(self):
        hints.ROOT = self.saved
        hints.hint_table.cache_clear()
        self.assertEqual(hints.hint_problems(common.discover_stages(self.saved)), [])


if __name__ == "__main__":
    unittest.main()
