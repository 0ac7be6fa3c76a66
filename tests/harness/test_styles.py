"""One look per solver in every figure (harness/_styles.py): fixed for the built-in solvers,
distinct within a figure, and independent of the order of the stored rows."""

import itertools
import pathlib

import pytest

import harness
from harness import _plots
from harness._styles import COLOURS, solver_order, solver_styles
from solvers import solver_names
from solvers._registry import get_solver_class

RESULTS = pathlib.Path(__file__).resolve().parents[2] / "results"
BUILTIN = [n for n in solver_names() if get_solver_class(n).__module__.startswith("solvers.")]


def _look(style):
    return style["color"], str(style["linestyle"])


def test_every_builtin_solver_has_a_colour_and_its_familys_line_style():
    assert set(BUILTIN) == set(COLOURS)
    styles = solver_styles(BUILTIN)
    family_style = {"thesis": "-", "own": "-.", "established": "--"}
    for name in BUILTIN:
        assert styles[name]["linestyle"] == family_style[get_solver_class(name).family], name
    assert len(set(COLOURS.values())) == len(COLOURS)  # no two built-ins share a colour


def test_a_builtin_solvers_look_does_not_depend_on_the_others_drawn():
    alone = {n: solver_styles([n])[n] for n in BUILTIN}
    for a, b in itertools.combinations(BUILTIN, 2):
        both = solver_styles([b, a, "mine"])
        assert both[a] == alone[a] and both[b] == alone[b]


def test_option_variants_keep_the_colour_with_patterns_of_their_own():
    labels = ["sqsd", "sqsd[rho=0.1]", "sqsd[rho=1.0]", "dynamic-q[rho=0.5]"]
    s = solver_styles(labels)
    assert s["sqsd[rho=0.1]"]["color"] == s["sqsd[rho=1.0]"]["color"] == COLOURS["sqsd"]
    assert s["dynamic-q[rho=0.5]"]["color"] == COLOURS["dynamic-q"]
    assert len({_look(s[k]) for k in labels}) == len(labels)


@pytest.mark.parametrize("n", [1, 8, 30])
def test_user_solvers_drawn_together_look_different(n):
    labels = [f"user-{i:02d}" for i in range(n)]
    s = solver_styles(labels + list(BUILTIN))
    looks = [_look(s[k]) for k in labels]
    assert len(set(looks)) == n
    assert not set(looks) & {_look(s[k]) for k in BUILTIN}
    assert solver_styles(labels) == {k: s[k] for k in labels}  # the built-ins beside them change nothing


def test_solver_order_lists_builtins_first_then_others_by_name():
    got = sorted(["zeta", "ipopt", "alpha", "sqsd[rho=1]", "sqsd", "dynamic-q-plus"], key=solver_order)
    assert got == ["sqsd", "sqsd[rho=1]", "dynamic-q-plus", "ipopt", "alpha", "zeta"]


def test_history_figure_does_not_depend_on_the_order_of_stored_rows(tmp_path):
    """Same runs, same bytes, whatever the row order."""
    runs = harness.load_results("hs", RESULTS)
    runs = runs[runs["problem"] == "hs071"]
    assert runs["solver"].nunique() >= 5
    a = _plots._histories("hs", runs, tmp_path / "a", "hs071")
    b = _plots._histories("hs", runs.iloc[::-1], tmp_path / "b", "hs071")
    # the SVG too: it carries no date and fixed ids (harness.figures.save_figure)
    assert {p.suffix for p in a} == {".png", ".svg"} and len(b) == len(a)
    assert all(p.read_bytes() == (tmp_path / "b" / p.name).read_bytes() for p in a)
