"""Unit tests of the grader's pure parts: python3 -m unittest discover -s tools/grader/tests -t tools
(./physlab test runs them with the framework's other checks)."""
