#!/usr/bin/env bash
# Gradescope image set-up: the instructor repository (with solutions/ and tests/hidden/) is
# expected at /autograder/source. Installs the Debian packages and builds the reference once,
# so grading a submission only compiles the student's files.
set -euo pipefail
cd /autograder/source
./physlab setup
./physlab build
