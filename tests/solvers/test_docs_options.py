"""The option tables of docs/thesis_solvers.md list every option of the thesis solvers."""

import pathlib

import pytest

from solvers import get_solver_class

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "thesis_solvers.md"


@pytest.mark.parametrize("name", ["lfopc", "dynamic-q", "etopc"])
def test_every_option_documented(name):
    text = DOC.read_text(encoding="utf-8")
    section = text.split(f"### `{name}`", 1)[1].split("\n### ", 1)[0]
    missing = [o["name"] for o in get_solver_class(name).options() if f"| `{o['name']}` |" not in section]
    assert not missing, f"{name}: options not in docs/thesis_solvers.md: {missing}"
