"""The package's design: modules of one job each, short, each saying its job, importing only the
modules before it (no cycle)."""

import ast
import unittest
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent
MODULES = sorted(PACKAGE.glob("*.py"))
MAX_LINES = 400


def imported(path: Path) -> set:
    """The package's modules that `path` imports (from .x import ...)."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.level == 1 and node.module:
            found.add(node.module)
    return found


class Design(unittest.TestCase):
    def test_no_module_over_the_limit(self):
        long = {p.name: n for p in MODULES if (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_LINES}
        self.assertEqual(long, {}, f"split a module of more than {MAX_LINES} lines by what its code does")

    def test_every_module_says_its_job(self):
        for path in MODULES:
            self.assertTrue(ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))), path.name)

    def test_imports_have_no_cycle(self):
        graph = {p.stem: imported(p) for p in MODULES}
        done, path = set(), []

        def visit(module: str) -> None:
            self.assertNotIn(module, path, f"an import cycle: {' -> '.join(path + [module])}")
            if module in done:
                return
            path.append(module)
            for other in sorted(graph.get(module, ())):
                visit(other)
            path.pop()
            done.add(module)

        for module in sorted(graph):
            visit(module)


if __name__ == "__main__":
    unittest.main()
