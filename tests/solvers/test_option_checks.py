"""Declarative option checks: every solver validates its options once, in AbstractSolver."""

from __future__ import annotations

import dataclasses

import pytest

from solvers import make_solver
from solvers._registry import get_solver_class, solver_names

THESIS = ["sqsd", "dynamic-q", "lfopc", "etopc"]


@pytest.mark.parametrize("name", THESIS)
def test_defaults_pass_their_own_checks(name: str) -> None:
    make_solver(name)


@pytest.mark.parametrize("spec, words", [
    ("dynamic-q[rho=abc]", ["dynamic-q", "rho", "'abc'", "a number"]),
    ("dynamic-q[rho=-1]", ["dynamic-q", "rho=-1", "> 0"]),
    ("sqsd[rho=inf]", ["sqsd", "rho", "finite"]),
    ("lfopc[m=0]", ["lfopc", "m=0", ">= 1"]),
    ("lfopc[dt_mode='slow']", ["lfopc", "dt_mode", "'fixed'", "'auto'"]),
    ("lfopc[mu0=1e5]", ["lfopc", "mu0", "mu1"]),
    ("etopc[eta=1.5]", ["etopc", "eta", "(0, 1)"]),
    ("etopc[max_line=2.5]", ["etopc", "max_line", "integer"]),
    ("scipy-slsqp[maxiter=0]", ["scipy-slsqp", "maxiter", ">= 1"]),
])
def test_bad_value_names_solver_option_and_valid_range(spec: str, words: list[str]) -> None:
    with pytest.raises(ValueError) as exc:
        make_solver(spec)
    for w in words:
        assert w in str(exc.value), (w, str(exc.value))


def test_unknown_option_lists_valid_names() -> None:
    with pytest.raises(ValueError, match=r"unknown option\(s\) rhoo for solver 'dynamic-q'; valid options: rho, "):
        make_solver("dynamic-q[rhoo=1]")
    with pytest.raises(ValueError, match="valid options: .*mu0"):
        make_solver(make_solver("lfopc"), mu00=1)


def test_lfopc_and_etopc_share_the_penalty_options() -> None:
    from solvers._penalty_phases import PenaltyPhases

    shared = [f.name for f in dataclasses.fields(PenaltyPhases)]
    assert len(shared) == 6
    for name in ("lfopc", "etopc"):
        assert issubclass(get_solver_class(name), PenaltyPhases)
        assert [f.name for f in dataclasses.fields(get_solver_class(name))][:6] == shared


def test_concrete_solvers_are_final() -> None:
    for name in THESIS:
        cls = get_solver_class(name)
        with pytest.raises(TypeError, match="final"):
            type("Sub", (cls,), {})


def test_listing_prints_the_checks() -> None:
    from harness._listing import list_solvers

    text = "\n".join(list_solvers())
    assert "rho = 1.0: move limit" in text and "(valid: a finite number > 0)" in text
    assert len([n for n in solver_names()]) > 4
