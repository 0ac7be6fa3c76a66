"""The layers import downward only: problems/, solvers/ and manipulators/ never import the
harness (the thesis's reference tables live in problems/reference, which all of them own)."""

import ast
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("package", ["problems", "solvers", "manipulators"])
def test_lower_layers_do_not_import_the_harness(package):
    offenders = []
    for path in sorted((ROOT / package).rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else (
                [node.module or ""] if isinstance(node, ast.ImportFrom) and node.level == 0 else [])
            offenders += [f"{path.relative_to(ROOT)}:{node.lineno} imports {n}" for n in names
                          if n == "harness" or n.startswith("harness.")]
    assert not offenders, "\n".join(offenders)
