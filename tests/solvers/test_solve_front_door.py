"""solve(): options validation, unknown names, errors recorded not raised."""

import numpy as np
import pytest

from problems import Problem
from solvers import NotApplicable, Status, UnknownSolver, solve


def quad():
    return Problem(name="quad", x0=[3.0, 3.0], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x, f_ref=0.0)


def test_unknown_solver_lists_valid_names():
    with pytest.raises(UnknownSolver, match="valid solvers: .*sqsd"):
        solve(quad(), "no-such-solver")


def test_unknown_option_lists_valid_options():
    with pytest.raises(ValueError, match="valid options: rho"):
        solve(quad(), "sqsd", step=3)


def test_bracket_syntax():
    r = solve(quad(), "sqsd[rho=0.5]")
    assert r.options["rho"] == 0.5 and r.status is Status.CONVERGED


def test_exception_in_problem_is_recorded():
    def f(x):
        raise RuntimeError("boom")

    p = Problem(name="bad", x0=[1.0], objective=lambda x: 0.0, gradient=lambda x: np.array([1.0]))
    p = p.replace(objective=f)
    r = solve(p, "sqsd")
    assert r.status is Status.ERROR and "boom" in r.message and not r.success


def test_constrained_problem_rejected_by_unconstrained_solver():
    p = Problem(name="c", x0=[1.0], objective=lambda x: x[0] ** 2, ineq=lambda x: np.array([-x[0]]))
    with pytest.raises(NotApplicable):
        solve(p, "sqsd")
