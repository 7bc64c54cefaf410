#!/usr/bin/env bash
# Gradescope image set-up. The autograder zip (./physlab gradescope) unpacks the instructor's tree
# to /autograder/source/physlab. This installs the Debian packages, builds the instructor's side
# of every graded link once, creates the sandbox users and compiles the stubs into the grader's
# cache by grading them, so that grading a submission only compiles its changed lab files.
# AUTOGRADER_ROOT (default /autograder) stands for Gradescope's folder when trying the zip elsewhere.
set -euo pipefail
cd "${AUTOGRADER_ROOT:-/autograder}/source/physlab"
./physlab setup
course=()
[ ! -f course.toml ] || course=(--course course.toml)
./physlab grade labs --out /tmp/physlab-warm-up "${course[@]}" >/dev/null
# The warm-up grades the stubs: a failure there (a stub that does not compile, a build that timed
# out) would otherwise surface only at the first submission, as a zero.
if grep -q "GRADING FAILED\|did not compile" /tmp/physlab-warm-up/report.txt; then
  echo "setup: grading the stubs failed:" >&2
  grep -m 5 "GRADING FAILED\|NOT GRADED\|did not compile" /tmp/physlab-warm-up/report.txt >&2
  exit 1
fi
