"""PhysLab's test runner and autograder.

Runs every Catch2 test case in its own process group with a time limit and resource limits, takes
each verdict from an authenticated channel (tests/support/runner.cpp) rather than from anything the
test prints, and writes a readable report plus Gradescope's results.json. `grade` compiles a
submission's lab files apart from the instructor's tree (in bubblewrap where allowed), checks what
the objects define, and links them with the instructor's prebuilt objects (Lab 4) or into a
sandboxed worker that the instructor's checker calls (Labs 1, 2, 3, 5, 6: Isolation, Program), running
everything as this run's own identities when run as root. The design and its limits are on the
Grading page (docs/grading.md).
"""

# The path of a submission through the modules, each importing only those above it:
#   common      limits, text for a report, the records of tests and results
#   policy      what a lab file may contain, define and call
#   kit         the instructor's build: toolchain, commands, precompiled headers, symbol tables
#   sandbox     this run's identities, resource limits, kill and sweep
#   isolation   bubblewrap and seccomp around workers and compiles
#   failures    a failed test's Catch2 report, explained
#   runner      listing and running tests, verdicts, the deadline
#   hints       the handout section and the hint of a failed test
#   report      report.txt and results.json
#   objects     checks of a compiled lab file
#   build       compiling and linking a submission
#   submission  reading the submitted folder without following links
#   tree        ./physlab test on the tree's own executables
#   partial     partial credit: a lab file linked with the reference of the others
#   grade       one submission, start to finish
#   classes     a class of submissions
#   gradescope  the autograder zip
#   cli         the commands (python3 tools/grader run|grade|gradescope|stages)
