"""csv_text(): a field of scores.csv (why a submission was not graded) that keeps the table whole;
shard_of(): every submission in exactly one shard, the same share whatever the order given;
write_record()/load_record(): what a merge reads is what the grade had; merge_shards(): refuses
shards that are not one whole split."""

import json
import tempfile
import unittest
from pathlib import Path

from grader.classes import RECORD, SHARD, csv_text, load_record, merge_shards, shard_of, write_record
from grader.common import StageResult, TestCase


class CsvText(unittest.TestCase):
    def test_no_comma_quote_or_line_break(self):
        self.assertEqual(csv_text('a, "b"\r\nc'), "a   b c")
        self.assertEqual(csv_text("the compiler was killed (status -9)"), "the compiler was killed (status -9)")

    def test_at_most_200_characters(self):
        self.assertEqual(len(csv_text("x" * 500)), 200)


class Shards(unittest.TestCase):
    names = [f"/subs/student-{i:02d}" for i in range(1, 21)]

    def test_every_submission_in_exactly_one_shard(self):
        for n in (1, 3, 4, 20, 25):
            shares = [shard_of(self.names, (i, n)) for i in range(1, n + 1)]
            self.assertEqual(sorted(p for s in shares for p in s), sorted(self.names))
            self.assertLessEqual(max(map(len, shares)) - min(map(len, shares)), 1)  # balanced

    def test_the_order_given_does_not_matter(self):
        self.assertEqual(shard_of(list(reversed(self.names)), (2, 4)), shard_of(self.names, (2, 4)))
        self.assertEqual(shard_of(self.names, (2, 4)), ["/subs/student-02", "/subs/student-06", "/subs/student-10",
                                                       "/subs/student-14", "/subs/student-18"])

    def test_no_shard_is_everything(self):
        self.assertEqual(shard_of(self.names, None), self.names)


def graded_folder(root: Path, name: str, status: str) -> None:
    (root / name).mkdir(parents=True)
    (root / name / "results.json").write_text(json.dumps({"score": 1.0, "max_score": 2.0, "tests": []}))
    case = TestCase("03_rigid_bodies", "rates", ["pts=2", "sec=3"], status=status, checks=["a.cpp:3: x == 1"],
                    course_points=1.5, course_hidden=True)
    write_record(root / name, [StageResult("03_rigid_bodies", [case])], 12.34)


class Records(unittest.TestCase):
    def test_round_trip(self):
        with tempfile.TemporaryDirectory() as tmp:
            graded_folder(Path(tmp), "s", "failed")
            data, results, seconds = load_record(Path(tmp) / "s")
            case = results[0].tests[0]
            self.assertEqual((data["score"], seconds, results[0].stage), (1.0, 12.3, "03_rigid_bodies"))
            self.assertEqual((case.name, case.status, case.checks, case.points, case.hidden, case.sections),
                             ("rates", "failed", ["a.cpp:3: x == 1"], 1.5, True, [3]))


class Merge(unittest.TestCase):
    def shard(self, root: Path, i: int, n: int, names: list) -> Path:
        folder = root / f"shard{i}"
        folder.mkdir()
        for name in names:
            graded_folder(folder, name, "passed")
        (folder / SHARD).write_text(json.dumps({"shard": [i, n], "course": None, "submissions": names,
                                                "cpu_seconds": 1.0}))
        return folder

    def test_refuses_a_missing_shard_a_repeated_one_and_a_folder_of_no_grade(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            one, two = self.shard(root, 1, 3, ["a"]), self.shard(root, 2, 3, ["b"])
            _, problems = merge_shards([one, two], root / "out")
            self.assertEqual(problems, ["shard 3 of 3 is missing"])
            _, problems = merge_shards([one, one, two], root / "out")
            self.assertIn(f"shard 1 of 3 twice: {one} and {one}", problems)
            _, problems = merge_shards([root], root / "out")
            self.assertTrue(problems[0].startswith(f"{root}: not the output of a class grade"))
            self.assertFalse((root / "out").exists())

    def test_a_submission_in_two_shards_and_one_without_its_record(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            one, two = self.shard(root, 1, 2, ["a"]), self.shard(root, 2, 2, ["a", "b"])
            (two / "b" / RECORD).unlink()
            _, problems = merge_shards([one, two], root / "out")
            self.assertIn(f"submission a is in two shards: {one} and {two}", problems)
            self.assertIn(f"{two / 'b'}: no {RECORD} (graded by an older grader, or not finished)", problems)


if __name__ == "__main__":
    unittest.main()
