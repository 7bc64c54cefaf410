#!/usr/bin/env python3
"""GitHub Classroom autograding for a student copy of PhysLab, one runner per lab.

  classroom.py workflow   prints .github/workflows/classroom.yml for the labs in tests/
  classroom.py results    runs ./physlab test and prints one `labNN=<base64 JSON>` line per lab
                          for $GITHUB_OUTPUT, in the form the Classroom grading reporter reads:
                          each graded test with its points, so a lab earns the points of the
                          tests it passes (not all or nothing).
"""
import base64
import json
import re
import subprocess
import sys
from pathlib import Path

# The tree's root: the folder with the driver (tools/ in a student copy, tools/student/ here)
ROOT = next(p for p in Path(__file__).resolve().parents if (p / "physlab").is_file())
MESSAGE_LIMIT = 1000  # characters of a failed test's explanation shown in Classroom


def labs() -> list:
    return sorted(p.name for p in (ROOT / "tests").iterdir() if re.match(r"^\d\d_[a-z0-9_]+$", p.name))


def workflow() -> str:
    runners = [f"lab{s[:2]}" for s in labs()]
    env = "\n".join(f'          {r.upper()}_RESULTS: "${{{{ steps.grade.outputs.{r} }}}}"' for r in runners)
    return f"""# GitHub Classroom autograding: every graded test of every lab with its points.
name: Autograding Tests
on: [push, repository_dispatch]
permissions:
  checks: write
  actions: read
  contents: read
jobs:
  run-autograding-tests:
    name: Autograding Tests
    runs-on: ubuntu-latest
    if: github.actor != 'github-classroom[bot]'
    container: debian:bookworm
    steps:
      - run: apt-get update && apt-get install -y git g++ make cmake
      - uses: actions/checkout@v4
      - run: ./physlab setup
      - name: Grade
        id: grade
        run: python3 tools/classroom.py results >> "$GITHUB_OUTPUT"
      - uses: classroom-resources/autograding-grading-reporter@v1
        env:
{env}
        with:
          runners: {",".join(runners)}
"""


def encode(result: dict) -> str:
    return base64.b64encode(json.dumps(result).encode()).decode()


def results() -> str:
    subprocess.run([str(ROOT / "physlab"), "test"], cwd=ROOT, stdout=sys.stderr, stderr=sys.stderr)
    path = ROOT / "build" / "report-labs" / "results.json"
    tests = json.loads(path.read_text())["tests"] if path.exists() else []
    lines = []
    for stage in labs():
        mine = [t for t in tests if t["name"].startswith(f"lab {stage}: ")]
        if not mine:
            # No report (the build itself failed): say so rather than score a lab that never ran
            report = {"version": 1, "status": "error", "max_score": 0, "tests": [
                {"name": f"lab {stage}", "status": "error", "score": 0,
                 "message": "no results: see the Grade step's log (did the build fail?)"}]}
        else:
            report = {"version": 1, "status": "pass" if all(t["status"] == "passed" for t in mine) else "fail",
                      "max_score": sum(t["max_score"] for t in mine),
                      "tests": [{"name": t["name"], "status": "pass" if t["status"] == "passed" else "fail",
                                 "score": t["score"], "message": t.get("output", "")[:MESSAGE_LIMIT]}
                                for t in mine]}
        lines.append(f"lab{stage[:2]}={encode(report)}")
    return "\n".join(lines)


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1] not in ("workflow", "results"):
        sys.exit(__doc__)
    print(workflow() if sys.argv[1] == "workflow" else results())
