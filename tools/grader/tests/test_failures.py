"""describe_failure(): what a failed test's Catch2 XML report says, in a few lines."""

import unittest

from grader.failures import FAILURE_LINES, describe_failure, fit


def catch(*nodes: str) -> str:
    return f"noise before <Catch><Group><TestCase>{''.join(nodes)}</TestCase></Group></Catch> after"


def check(line: int, original: str, expanded: str, kind: str = "CHECK") -> str:
    return (f'<Expression success="false" type="{kind}" filename="/src/tests/t.cpp" line="{line}">'
            f"<Original>{original}</Original><Expanded>{expanded}</Expanded></Expression>")


class DescribeFailure(unittest.TestCase):
    def test_a_failed_check_with_its_values_and_notes(self):
        status, text, checks, captured = describe_failure(catch(
            "<Info>k := 10.000001</Info>", check(7, "f == Approx(3.5)", "-3.5 == Approx( 3.5 )")))
        self.assertEqual(status, "failed")
        self.assertEqual(text.splitlines(), ["CHECK( f == Approx(3.5) ) failed at t.cpp:7",
                                             "  actual: -3.5 == Approx( 3.5 )", "  note: k := 10.000001"])
        self.assertEqual(checks, ["t.cpp:7: f == Approx(3.5)"])
        self.assertEqual(captured, {"k": "10", "lhs": "-3.5", "rhs": "Approx( 3.5 )"})

    def test_a_check_in_a_loop_is_shown_once_with_its_count(self):
        _, text, checks, _ = describe_failure(catch(*(check(5, "x == 1", f"{i} == 1") for i in range(3))))
        self.assertEqual(text.splitlines(), ["CHECK( x == 1 ) failed 3 times at t.cpp:5; the first:",
                                             "  actual: 0 == 1"])
        self.assertEqual(checks, ["t.cpp:5: x == 1"])

    def test_an_exception_outside_any_check(self):
        node = ('<Expression success="false" filename="t.cpp" line="9"><Original>'
                '{Unknown expression after the reported line}</Original><Expanded>x</Expanded>'
                '<Exception filename="t.cpp" line="9">not implemented: step (see Lab 1 handout, section 3)'
                '</Exception></Expression>')
        status, text, _, _ = describe_failure(catch(node))
        self.assertEqual(status, "not implemented")
        self.assertEqual(text, "threw outside any check, after t.cpp:9: not implemented: step "
                               "(see Lab 1 handout, section 3)")

    def test_no_report_explains_nothing(self):
        self.assertEqual(describe_failure("Segmentation fault"), ("failed", "", [], {}))
        self.assertEqual(describe_failure("<Catch><unclosed></Catch>"), ("failed", "", [], {}))

    def test_many_failures_fit_the_lines_and_count_the_rest(self):
        _, text, checks, _ = describe_failure(catch(*(check(n, f"x{n} == 0", "1 == 0") for n in range(20))))
        lines = text.splitlines()
        self.assertEqual(len(lines), FAILURE_LINES)
        self.assertEqual(lines[-1], "and 15 more failed checks")
        self.assertEqual(len(checks), 20)

    def test_fit_keeps_headlines_before_details(self):
        blocks = [["a", "a1", "a2", "a3"], ["b", "b1", "b2"]]
        self.assertEqual(fit(blocks, 5), ["a", "a1", "a2", "b", "b1"])
        self.assertEqual(fit(blocks, 3), ["a", "a1", "and 1 more failed check"])


if __name__ == "__main__":
    unittest.main()
