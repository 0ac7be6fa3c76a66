"""Suite rpr2-exact (E synthesis (4.14) in exact smooth form) and its table plug-in (Table 4.7x)."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import minimize

from harness.tables import build_tables
from manipulators.prescribed import PRESCRIBED
from manipulators.synthesis import rpr2_exact_suite as S
from manipulators.synthesis.rpr2_exact import EXACT_K
from manipulators.synthesis.rpr2_suite import STARTS, evaluate
from problems import get_suite
from solvers import solve


def _central(fun, x, h=1e-6):
    cols = [(np.atleast_1d(fun(x + h * e)) - np.atleast_1d(fun(x - h * e))) / (2 * h) for e in np.eye(x.size)]
    return np.column_stack(cols)


def test_suite_is_registered_with_every_start_and_constrained_solver():
    suite = get_suite("rpr2-exact")
    cases = suite.cases()
    assert [c.start for c in cases] == list(STARTS)
    assert "sqsd" not in suite.solvers and {"dynamic-q", "dynamic-q-plus", "scipy-slsqp"} <= set(suite.solvers)
    for c in cases:
        np.testing.assert_array_equal(c.problem.x0, STARTS[c.start])
        assert c.problem.ineq(c.problem.x0).shape == (4 * EXACT_K + 1,)
        assert not c.options  # every solver at its defaults


@pytest.mark.parametrize("d", [STARTS["SP1"], STARTS["SP4"], [-4.6, -2.2, 4.5, 5.5, 5.5], [-5.9, 1.7, 5.9, 4.9, 4.8]])
def test_gradient_and_jacobian_match_central_differences(d):
    p = S.e_exact_problem("SP1", k=64)
    d = np.asarray(d, dtype=float)
    np.testing.assert_allclose(p.gradient(d), _central(p.objective, d).ravel(), rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(p.ineq_jacobian(d), _central(p.ineq, d), rtol=1e-5, atol=1e-6)


def test_constraints_hold_exactly_where_w_p_is_enclosed():
    p = S.e_exact_problem("SP2")
    for d in (STARTS["SP1"], STARTS["SP3"], [-4.803, -2.181, 4.803, 5.652, 5.652]):
        enclosed = evaluate("e", d, exact=True)["dwp_exact"] <= 1e-6
        assert (p.ineq(np.asarray(d, dtype=float)).max() <= 1e-3) == enclosed


@pytest.mark.parametrize("kw", [{"start": "SP5"}, {"prescribed": "P9"}, {"k": 2}, {"k": 10.5}])
def test_bad_arguments_name_what_is_valid(kw):
    with pytest.raises(ValueError, match="SP1|P1|integer"):
        S.e_exact_problem(**kw)


def test_dynamic_q_plus_ends_at_the_local_minimum_scipy_slsqp_finds_from_sp1():
    p = S.e_exact_problem("SP1")
    ref = minimize(p.objective, p.x0, jac=p.gradient, method="SLSQP",
                   bounds=[(None, None)] * 3 + [(S.L_MIN_LOWER, None)] * 2,
                   constraints=[{"type": "ineq", "fun": lambda d: -p.ineq(d), "jac": lambda d: -p.ineq_jacobian(d)}],
                   options={"maxiter": 300, "ftol": 1e-12})
    r = solve(p, "dynamic-q-plus")
    assert r.success and r.max_violation <= 1e-6
    assert abs(r.f - ref.fun) <= 1e-6 * (1 + abs(ref.fun))


def test_table_names_the_minimum_reached_and_flags_other_ends():
    minima = [[2.3087, [-5.949, 1.82, 5.949, 4.859, 4.859], 7], [3.14363, [-4.803, -2.181, 4.803, 5.652, 5.652], 25]]
    runs = pd.DataFrame([
        {"solver": "dynamic-q-plus", "start": "SP1", "f": 3.143631, "max_violation": 0.0, "nfg": 8,
         "status": "converged", "x": [-4.803, -2.181, 4.803, 5.652, 5.652], "wall_time_s": 0.3},
        {"solver": "nlopt-mma", "start": "SP1", "f": -4.97, "max_violation": 30.0, "nfg": 1368,
         "status": "converged", "x": [-4.8, -2.1, 4.2, 35.6, 7.1], "wall_time_s": 16.0},
        {"solver": "scipy-cobyla", "start": "SP1", "f": 3.5, "max_violation": 0.0, "nfg": 100,
         "status": "converged", "x": [-5.1, -2.2, 5.1, 5.9, 5.9], "wall_time_s": 3.0},
    ])
    (t,) = build_tables("rpr2-exact", runs, reference={"exact_optimum": {"minima": minima, "starts": 32}})
    ours = t.frame[t.frame["start"] == "SP1"].set_index("solver")
    assert ours.loc["dynamic-q-plus", "local minimum"] == "3.1436"
    assert ours.loc["nlopt-mma", "local minimum"] == "none (infeasible)"
    assert ours.loc["scipy-cobyla", "local minimum"] == "none"
    flagged = t.flags[t.frame["start"] == "SP1"]["local minimum"].tolist()
    assert flagged == [False, True, True]


_P = S.e_exact_problem("SP1")
_DENSE = PRESCRIBED["P1"].points(4096)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.floats(-5.5, -4.0), st.floats(-3.0, -1.5), st.floats(4.0, 5.5), st.floats(-0.2, 1.2), st.floats(-0.2, 1.2))
def test_inequalities_hold_iff_the_exact_workspace_encloses_w_p(xa, ya, xb, u1, u2):
    """The invariant the formulation rests on: g(d) <= 0 (sampled leg limits, base line) exactly when
    W_p lies inside the exact workspace (shapely).  l_min is drawn across the interval [max l / 1.5,
    min l] of leg lengths over W_p's boundary, so designs inside and outside both occur; a margin
    absorbs the 512-point sampling."""
    r = []
    for xp, u in ((xa, u1), (xb, u2)):
        ll = np.hypot(_DENSE[:, 0] - xp, _DENSE[:, 1] - ya)
        lo, hi = ll.max() / 1.5, ll.min()
        r.append(lo + u * (hi - lo))
    d = np.array([xa, ya, xb, *r])
    g = float(_P.ineq(d).max())
    dwp = evaluate("e", d, exact=True)["dwp_exact"]
    if g < -1e-3:
        assert dwp <= 1e-9
    elif g > 1e-3:
        assert dwp > 0.0
