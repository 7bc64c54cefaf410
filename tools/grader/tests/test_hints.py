"""hint_of(): a hint for a test that broke, its measured sentence only when every field was found."""

import tempfile
import unittest
from pathlib import Path

from grader import hints
from grader.common import TestCase


class HintFields(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        root = Path(self.folder.name)
        (root / "tests" / "01_alpha").mkdir(parents=True)
        (root / "tests" / "01_alpha" / "hints.toml").write_text(
            '"plain" = "gravity is m g"\n["springs pull back"]\ntext = "the force points along the spring"\n'
            'measured = "Your force was {lhs} at k = {k}."\n')
        self.saved, hints.ROOT = hints.ROOT, root
        hints.hint_table.cache_clear()

    def tearDown(self):
        hints.ROOT = self.saved
        hints.hint_table.cache_clear()
        self.folder.cleanup()

    def hint(self, name: str, status: str = "failed", **captured) -> str:
        return hints.hint_of(TestCase("01_alpha", name, ["pts=1"], status=status, captured=captured))

    def test_fields_filled_from_the_failure(self):
        self.assertEqual(self.hint("springs pull back", lhs="-3.5", k="10"),
                         "hint: the force points along the spring Your force was -3.5 at k = 10.")

    def test_a_missing_field_leaves_the_measured_sentence_out(self):
        self.assertEqual(self.hint("springs pull back", lhs="-3.5"), "hint: the force points along the spring")

    def test_only_for_a_test_that_ran_and_broke(self):
        self.assertEqual(self.hint("plain", "crashed"), "hint: gravity is m g")
        for status in ("passed", "not implemented", "not compiled", "not run"):
            self.assertEqual(self.hint("plain", status), "", status)
        self.assertEqual(self.hint("no hint"), "")


if __name__ == "__main__":
    unittest.main()
