"""The option tables of the docs list every option of the thesis solvers and of the multistart."""

import pathlib

import pytest

from solvers import get_solver_class

DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs"


@pytest.mark.parametrize("name, page", [("lfopc", "thesis_solvers.md"), ("dynamic-q", "thesis_solvers.md"),
                                        ("etopc", "thesis_solvers.md"), ("multistart", "multistart.md")])
def test_every_option_documented(name, page):
    text = (DOCS / page).read_text(encoding="utf-8")
    section = text.split(f"### `{name}`", 1)[1].split("\n### ", 1)[0]
    missing = [o["name"] for o in get_solver_class(name).options() if f"| `{o['name']}` |" not in section]
    assert not missing, f"{name}: options not in docs/{page}: {missing}"
