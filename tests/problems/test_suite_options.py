"""Every option a suite sets for a named solver is one that solver has (the harness would
otherwise store an error row); ``"*"`` options apply only where the solver has them."""

import pytest

from problems import get_suite, suite_names
from solvers import get_solver_class, make_solver


@pytest.mark.parametrize("suite", suite_names())
def test_case_options_are_valid_for_their_solvers(suite):
    for case in get_suite(suite).cases():
        for solver in case.options:
            if solver == "*":
                continue
            valid = [o["name"] for o in get_solver_class(solver).options()]
            make_solver(solver, **case.options_for(solver, valid))  # raises on an unknown name


@pytest.mark.parametrize("suite", suite_names())
def test_default_solvers_exist(suite):
    for solver in get_suite(suite).solvers:
        get_solver_class(solver)
