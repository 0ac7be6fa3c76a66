"""The rpr2 suite: problems, start values of Table 4.9, graceful infeasible designs, one short run."""

import numpy as np
import pytest

from manipulators.synthesis.rpr2_suite import SUITE, e_problem, evaluate, o_problem, p_problem
from solvers import solve


def test_suite_cases():
    ids = [c.case_id for c in SUITE.cases()]
    assert len(ids) == 11 and "rpr2-p3/n=3/d0" in ids and "rpr2-o/n=5/SP4" in ids
    assert {"dynamic-q", "sqsd", "scipy-cobyla"} <= set(SUITE.solvers)
    assert SUITE.case("rpr2-o/n=5/SP1").problem.form == frozenset()
    assert SUITE.case("rpr2-e/n=5/SP1").problem.form == {"eq"}
    assert SUITE.case("rpr2-p1/n=3/d0").problem.form == {"ineq"}


@pytest.mark.parametrize("name,f0", [("P1", 0.780), ("P2", 0.823), ("P3", 0.786)])
def test_p_start_values_of_table_4_9(name, f0):
    p = p_problem(name)
    assert round(-p.objective(p.x0), 3) == f0
    assert p.ineq(p.x0)[0] > 0  # d0 does not enclose P (Fig. 4.12a)


@pytest.mark.parametrize("d", [[-4, -1, 4, -3, 3], [0, 0, 0, 3, 3], [-50, 0, 50, 1, 1], [np.nan, 0, 1, 3, 3]])
def test_infeasible_designs_do_not_raise(d):
    fo = o_problem("SP1").objective(np.array(d, float))
    fe, he = e_problem("SP1").objective(np.array(d, float)), e_problem("SP1").eq(np.array(d, float))
    area = 4.966
    assert fo == pytest.approx(area / 2, abs=1e-2) and fe == 0.0 and he[0] == pytest.approx(area, abs=1e-2)
    p = p_problem("P1")
    assert np.isfinite(p.objective(np.array(d[:3], float))) or np.isnan(d[0])


def test_thesis_p1_optimum_evaluates_to_its_published_values():
    ev = evaluate("p", [-3.892, -1.016, 3.882], "P1")
    assert ev["f"] == pytest.approx(0.952, abs=5e-4) and ev["g"] < 0
    assert ev["f_thesis_points"] == pytest.approx(ev["f"], abs=1e-4)


def test_p3_synthesis_short_cobyla_run_improves_and_encloses():
    p = p_problem("P3")
    r = solve(p, "scipy-cobyla", rhobeg=0.2, tol=1e-3, maxfev=60)
    assert -r.f > 0.88 and r.max_violation <= 1e-6
    assert evaluate("p", r.x, "P3")["enclosed"]


# ---------------------------------------------------------------- the exact E problem (4.14)
def test_exact_e_problem_derivatives_against_finite_differences():
    from scipy.optimize import approx_fprime

    from manipulators.synthesis.rpr2_exact import exact_e_problem

    f, cons = exact_e_problem(k=64)
    d = np.array([-4.2, -2.4, 3.9, 5.5, 5.4])
    assert np.allclose(f(d)[1], approx_fprime(d, lambda x: f(x)[0], 1e-7), atol=1e-5)
    J = np.array([approx_fprime(d, lambda x, i=i: cons(x)[0][i], 1e-7) for i in range(4 * 64 + 1)])
    assert np.allclose(cons(d)[1], J, atol=1e-5)


def test_exact_e_value_is_dwc_of_the_shapely_geometry_when_enclosed():
    from manipulators.synthesis.rpr2_exact import exact_e_problem

    f, cons = exact_e_problem()
    d = np.array([-4.8, -2.4, 4.8, 5.8, 5.8])  # encloses P1 with margin
    assert cons(d)[0].min() > 0
    ev = evaluate("e", d)
    assert ev["dwp_exact"] < 1e-9 and f(d)[0] == pytest.approx(ev["dwc_exact"], abs=1e-4)


def test_exact_e_minima_and_polish_from_a_narrow_base_design():
    from manipulators.synthesis.rpr2_exact import exact_optimum, exact_polish

    opt = exact_optimum("e", n_starts=8)
    # two local minima: base line through W_p's lowest point (y = 1.82), and below W_p
    assert [round(m[0], 3) for m in opt["minima"]] == [2.309, 3.144]
    assert opt["d"][1] == pytest.approx(1.82, abs=1e-6) and opt["f"] == opt["minima"][0][0]
    for f_m, d_m, _ in opt["minima"]:
        ev = evaluate("e", d_m)
        assert ev["dwp_exact"] < 1e-6 and ev["dwc_exact"] == pytest.approx(f_m, abs=1e-4)
    # Dynamic-Q's d* from SP1 (Table 4.7, narrow base): not a local minimum of the exact problem
    pol = exact_polish([-2.863, -2.967, 2.812, 5.305, 5.288])
    assert pol["viol"] < 1e-7 and pol["drop"] > 0.9 and pol["f"] == pytest.approx(3.1436, abs=1e-3)
    assert pol["box_drop"] > 0.03
    # at a local minimum the box test finds no descent
    assert abs(exact_polish(opt["minima"][1][1])["box_drop"]) < 1e-6


def test_table_rows_follow_the_suite_solver_order_not_completion_order():
    import pandas as pd

    from harness.tables.rpr2 import _ours
    from manipulators.synthesis.rpr2_suite import SOLVERS

    done = ["scipy-cobyla", "dynamic-q", "my-solver", "sqsd", "ipopt"]  # order the runs finished in
    runs = pd.DataFrame({"problem": "rpr2-e", "start": "SP1", "solver": done})
    got = list(_ours(runs, "rpr2-e", "SP1")["solver"])
    assert got == sorted(done[:2] + done[3:], key=SOLVERS.index) + ["my-solver"]


def test_e_and_p_constraints_see_a_workspace_beside_the_prescribed_one():
    # designs whose workspace lies beside W_p: the triangle scheme alone reported h = 0 there
    # (Dynamic-Q+'s and SLSQP's former E ends from SP3), now h = area(W_p) uncovered
    from manipulators.prescribed import P1
    from manipulators.synthesis.rpr2_suite import e_problem, evaluate

    for d in ([-1.54, 0.0677, 4.389, 1.530, 2.500], [1.049, 1.505, 2.066, 0.2659, 0.9543]):
        h = e_problem("SP3").eq(np.asarray(d))[0]
        assert h == pytest.approx(P1.area(), rel=1e-3)
        assert evaluate("e", d)["h"] == pytest.approx(h)
