"""csv_text(): a field of scores.csv (why a submission was not graded) that keeps the table whole."""

import unittest

from grader.classes import csv_text


class CsvText(unittest.TestCase):
    def test_no_comma_quote_or_line_break(self):
        self.assertEqual(csv_text('a, "b"\r\nc'), "a   b c")
        self.assertEqual(csv_text("the compiler was killed (status -9)"), "the compiler was killed (status -9)")

    def test_at_most_200_characters(self):
        self.assertEqual(len(csv_text("x" * 500)), 200)


if __name__ == "__main__":
    unittest.main()
