"""report(): failures first (visible before hidden), one TODO line per unwritten function, then
the passes and a summary that names the failure to fix first."""

import unittest

from grader.common import StageResult, TestCase
from grader.report import gradescope_json, report

STAGE = "99_made_up"  # no labs/, handout or hints: the report's own lines only


def case(name: str, status: str, points: int = 2, hidden: bool = False, output: str = "") -> TestCase:
    tags = ["lab99", f"pts={points}"] + (["hidden"] if hidden else [])
    return TestCase(STAGE, name, tags, status=status, output=output)


class Report(unittest.TestCase):
    def setUp(self):
        waits = "not implemented: {} (see Lab 7 handout, section {})"
        self.result = StageResult(STAGE, [
            case("passes", "passed"),
            case("todo a", "not implemented", output=waits.format("step", 3)),
            case("hidden broke", "failed", hidden=True, output="CHECK( x ) failed at h.cpp:1"),
            case("todo b", "not implemented", output=waits.format("force", 2)),
            case("visible broke", "crashed", output="crashed (SIGSEGV)"),
            case("todo c", "not implemented", points=1, output=waits.format("force", 2)),
        ])
        self.text = report([self.result], 42, "a title")

    def test_failures_first_visible_before_hidden(self):
        lines = self.text.splitlines()
        self.assertEqual(lines[:3], ["a title", 'random seed: 42 (rerun one test: build/test_NN_name_labs '
                                     '"<test name>" --rng-seed 42)', ""])
        self.assertEqual(lines[3], f"== lab {STAGE}: 2 / 11 points ==")
        order = [n for n in ("visible broke", "hidden broke", "TODO:", "passes")
                 if any(n in line for line in lines)]
        self.assertEqual(order, ["visible broke", "hidden broke", "TODO:", "passes"])
        self.assertLess(self.text.index("visible broke"), self.text.index("hidden broke"))
        self.assertLess(self.text.index("hidden broke"), self.text.index("TODO:"))
        self.assertLess(self.text.index("TODO:"), self.text.index("PASS"))
        self.assertIn(" CRSH    0/2  visible broke\n            crashed (SIGSEGV)", self.text)
        self.assertIn(" FAIL    0/2  hidden broke [hidden]\n            CHECK( x ) failed at h.cpp:1", self.text)

    def test_todo_lines_the_function_most_tests_wait_for_first(self):
        todo = [line for line in self.text.splitlines() if "TODO:" in line]
        self.assertEqual(todo, [" TODO: 2 tests (3 points) wait for force (Lab 7 handout, section 2)",
                                " TODO: 1 test (2 points) waits for step (Lab 7 handout, section 3)"])

    def test_summary_names_the_failure_to_fix_first(self):
        self.assertIn(" summary: 2 / 11 points; 1 pass, 2 fail, 3 todo; fix first: visible broke", self.text)
        self.assertEqual(self.text.splitlines()[-1],
                         f"TOTAL: 2 / 11 points; 1 pass, 2 fail, 3 todo; fix first: lab {STAGE}: visible broke")

    def test_without_passes_only_their_lines_go(self):
        # A run that printed each test's line as it finished repeats no pass, and keeps the rest
        brief = report([self.result], 42, "a title", passes=False)
        self.assertNotIn("PASS", brief)
        self.assertEqual([line for line in self.text.splitlines() if "PASS" not in line], brief.splitlines())

    def test_results_json_hides_hidden_tests_until_published(self):
        data = gradescope_json([self.result], 1.234)
        self.assertEqual((data["score"], data["max_score"], data["execution_time"]), (2.0, 11.0, 1.23))
        visibility = {t["name"]: t["visibility"] for t in data["tests"]}
        self.assertEqual(visibility[f"lab {STAGE}: hidden broke"], "after_published")
        self.assertEqual(visibility[f"lab {STAGE}: passes"], "visible")


if __name__ == "__main__":
    unittest.main()
