"""The grade's Deadline, and judge(): a test passes on the notary's line with this run's key only."""

import time
import unittest

from grader.common import TestCase
from grader.runner import Deadline, judge

KEY = "k" * 64


class Deadlines(unittest.TestCase):
    def test_none_is_no_limit(self):
        self.assertEqual(Deadline(None).left(), float("inf"))

    def test_the_time_left_runs_down(self):
        deadline = Deadline(10)
        first = deadline.left()
        time.sleep(0.01)
        self.assertTrue(9 < deadline.left() < first <= 10)
        self.assertLessEqual(Deadline(0).left(), 0)


class Judge(unittest.TestCase):
    def judged(self, code, verdicts: str, output: str = "") -> TestCase:
        case = TestCase("01_alpha", "a test", ["pts=1"])
        judge(case, code, 30.0, KEY, verdicts, output)
        return case

    def test_the_notarys_exit_0_passes(self):
        self.assertEqual(self.judged(0, f"physlab-verdict {KEY} exit 0\n").status, "passed")

    def test_a_line_without_the_key_is_no_verdict(self):
        case = self.judged(0, f"physlab-verdict {'x' * 64} exit 0\n", "All tests passed")
        self.assertEqual((case.status, case.output), ("crashed", "the test process ended without a verdict"))

    def test_a_signal_and_a_time_out(self):
        self.assertEqual(self.judged(1, f"physlab-verdict {KEY} signal 11\n").output, "crashed (SIGSEGV)")
        self.assertEqual(self.judged(None, "").output, "killed after 30 s")

    def test_asserting_nothing_fails(self):
        case = self.judged(3, f"physlab-verdict {KEY} exit 3\n")
        self.assertEqual((case.status, case.output), ("failed", "the test ran but asserted nothing"))


if __name__ == "__main__":
    unittest.main()
