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
    cases = [c for c in suite.cases() if c.problem.name.startswith("rpr2-e-exact")]
    assert [c.start for c in cases] == list(STARTS)
    assert [c.problem.name for c in suite.cases()[len(cases):]] == [f"rpr2-p{i}-exact" for i in (1, 2, 3)]
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
    t, _ = build_tables("rpr2-exact", runs, reference={"exact_optimum": {"minima": minima, "starts": 32}})
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


# -- P synthesis (4.21) in exact form (Table 4.9x) -----------------------------------------------

@pytest.mark.parametrize("prescribed", S.P_CASES)
@pytest.mark.parametrize("z", [[-4.0, -0.1, 4.0, 0.5], [-3.9, -1.0, 3.9, 0.95], [-3.4, -0.65, 4.1, 0.9],
                               [-2.0, -2.5, 2.5, 0.1]])
def test_p_exact_jacobian_matches_central_differences(prescribed, z):
    p = S.p_exact_problem(prescribed, k=64)
    z = np.asarray(z, dtype=float)
    np.testing.assert_allclose(p.gradient(z), _central(p.objective, z).ravel(), atol=1e-9)
    np.testing.assert_allclose(p.ineq_jacobian(z), _central(p.ineq, z), rtol=1e-5, atol=1e-6)


def test_p_exact_problem_starts_at_d0_as_feasible_as_d0():
    """x0 = [d0, min kappa^-1(d0)]: the kappa rows hold with equality at the minimizing point, and
    t is the suite's P objective at d0."""
    from manipulators.synthesis.rpr2_suite import P_START, p_problem

    p = S.p_exact_problem("P1")
    np.testing.assert_array_equal(p.x0[:3], P_START)
    assert p.x0[3] == pytest.approx(-p_problem("P1").objective(np.asarray(P_START, dtype=float)), abs=1e-12)
    assert p.ineq(p.x0)[:2048].max() == 0.0
    assert p.ineq(p.x0).shape == (2048 + 4 * EXACT_K + 1,)
    with pytest.raises(ValueError, match="unknown prescribed workspace 'P4'; valid: P1, P2, P3"):
        S.p_exact_problem("P4")


def test_dynamic_q_plus_reaches_the_exact_p_optimum():
    from manipulators.synthesis.rpr2_exact import exact_optimum

    opt = exact_optimum("p", "P2", n_starts=4)
    r = solve(S.p_exact_problem("P2"), "dynamic-q-plus")
    assert r.success and r.max_violation <= 1e-6
    assert -r.f == pytest.approx(opt["f"], rel=1e-6)
    ev = evaluate("p", r.x[:3], "P2")
    # t* is the suite's objective there, up to the violation the kappa rows may keep
    assert ev["enclosed"] and abs(ev["f"] - (-r.f)) <= r.max_violation + 1e-12


_PP = S.p_exact_problem("P1")
_DENSE_P = PRESCRIBED["P1"].points(4096)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.floats(-4.6, -3.2), st.floats(-1.6, -0.4), st.floats(3.2, 4.6))
def test_p_leg_rows_hold_iff_the_exact_workspace_encloses_p(xa, ya, xb):
    """The leg-limit and base-line rows of the exact P problem are <= 0 exactly when P lies inside the
    exact workspace (shapely); t = 0 keeps the kappa rows out of it (kappa^-1 > 0 above the base)."""
    g = float(_PP.ineq(np.array([xa, ya, xb, 0.0]))[2048:].max())
    dwp = evaluate("p", np.array([xa, ya, xb]), "P1", exact=True)["dwp_exact"]
    if g < -1e-3:
        assert dwp <= 1e-9
    elif g > 1e-3:
        assert dwp > 0.0


def test_table_4_9x_names_the_exact_optimum_and_flags_other_ends():
    opt = {"P1": {"d": [-3.86085158, -1.03714935, 3.86085158], "f": 0.9563311236, "starts": 25,
                  "minima": [[0.9563311236, [-3.86085158, -1.03714935, 3.86085158], 25]]}}
    runs = pd.DataFrame([
        {"problem": "rpr2-p1-exact", "solver": "dynamic-q-plus", "start": "d0", "f": -0.9563311260, "nfg": 5,
         "max_violation": 3e-9, "status": "converged", "x": [-3.86085, -1.03715, 3.86085, 0.95633113],
         "wall_time_s": 0.5},
        {"problem": "rpr2-p1-exact", "solver": "dynamic-q", "start": "d0", "f": -0.9563321, "nfg": 101,
         "max_violation": 1.5e-6, "status": "max_iter", "x": [-3.86085, -1.03715, 3.86085, 0.9563321],
         "wall_time_s": 7.0},
    ])
    _, t = build_tables("rpr2-exact", runs, reference={"exact_p_optimum": opt})
    assert t.name == "table_4_9x"
    ours = t.frame.set_index("solver")
    assert ours.loc["(exact-model optimum)", "t*"] == "0.956331"
    assert ours.loc["dynamic-q-plus", "reached"] == "exact optimum"
    assert ours.loc["dynamic-q", "reached"] == "none (infeasible)"
    flagged = dict(zip(t.frame["solver"], t.flags["reached"]))
    assert flagged == {"(exact-model optimum)": False, "dynamic-q-plus": False, "dynamic-q": True}
