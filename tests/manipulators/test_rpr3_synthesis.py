"""Suite ``rpr3``: SO, MO and D synthesis problems (thesis Sections 5.6-5.8)."""

import math

import numpy as np
import pandas as pd
import pytest

from manipulators.synthesis.rpr3_suite import SETTINGS, SUITE, evaluate, exact_enclosure, synthesis_problem


@pytest.mark.parametrize("pname,expect", [("P1", 0.759), ("P2", 0.768), ("P3", 0.747)])
def test_so_start_objective_reproduces_table_5_3(pname, expect):
    prob = synthesis_problem("so", pname)
    assert -prob.objective(prob.x0) == pytest.approx(expect, abs=3e-3)
    # the start design does not enclose the prescribed workspace (Fig. 5.7a)
    assert prob.ineq(prob.x0)[0] > 0


def test_suite_cases_and_settings():
    cases = SUITE.cases()
    ids = [c.problem_id for c in cases]
    assert ids == [f"rpr3-{k}-p{i}" for k in ("so", "mo", "d") for i in (1, 2, 3)]
    for c in cases:
        kind = c.meta["kind"]
        assert c.problem.fd == SETTINGS[kind]["fd"] and c.problem.fd_step == SETTINGS[kind]["fd_step"]
        assert c.problem.f_ref < -0.85  # -f* of Tables 5.3-5.5
        dq = c.options.get("dynamic-q", {})
        if dq:
            assert dq["rho"] == SETTINGS[kind]["rho"] and dq["eps_x"] == 1e-4
    assert SETTINGS["d"]["fd"] == "central" and SETTINGS["d"]["rho"] == 0.05
    assert SETTINGS["mo"]["phis"] == pytest.approx((-5 * math.pi / 180, 0.0, 5 * math.pi / 180))
    assert SUITE.solvers[0] == "dynamic-q"


@pytest.mark.parametrize("kind", ["so", "mo", "d"])
def test_infeasible_designs_are_graceful(kind):
    prob = synthesis_problem(kind, "P2")
    area = 0.0
    for d in ([-1, 0, 1, 2, -0.5], [np.nan, 0, 1, 2, 1], [-20.0, 0.0, 20.0, 40.0, 0.5]):
        f = prob.objective(np.asarray(d, float))
        g = prob.ineq(np.asarray(d, float))[0]
        assert np.isfinite(f) and np.isfinite(g) and g > 0
        area = max(area, g)
    # the far design's g grows with its distance from feasibility (slope for the optimizer)
    g1 = prob.ineq(np.array([-20.0, 0.0, 20.0, 40.0, 0.5]))[0]
    g2 = prob.ineq(np.array([-30.0, 0.0, 30.0, 60.0, 0.5]))[0]
    assert g2 > g1


def test_feasible_design_has_negative_g_and_is_enclosed():
    # a design found by Dynamic-Q for SO/P2 (close to Table 5.3's d*)
    d = np.array([-1.153, 0.3003, 1.275, 1.906, 0.9401]) + np.array([0.0, -0.02, 0.0, 0.0, 0.0])
    prob = synthesis_problem("so", "P2")
    g = prob.ineq(d)[0]
    ex = exact_enclosure("so", d, "P2")
    assert (g <= 0) == ex["enclosed"]


def test_centre_outside_workspace_is_not_feasible():
    """Regression: a design whose +-5 degree workspaces miss W_p entirely (found by SLSQP on
    MO/P2 when the triangle scheme was applied about an O' outside the workspace) must not
    pass g <= 0; g agrees with the exact polygon check."""
    d = np.array([-0.70516325, 0.62283715, 1.8635125, 1.88859408, 0.98672821])
    ex = exact_enclosure("mo", d, "P2")
    g = synthesis_problem("mo", "P2").ineq(d)[0]
    assert not ex["enclosed"] and g > 0.1


def test_evaluate_reports_thesis_style_kappa_and_exact_check():
    prob = synthesis_problem("so", "P3")
    out = evaluate("so", prob.x0, "P3")
    assert out["kinv"] == pytest.approx(0.747, abs=3e-3)
    assert out["kinv_thesis"] >= out["kinv"] - 1e-12  # sampled at fewer angles
    assert out["enclosed"] is False and out["ratio"] > 0.05
    with pytest.raises(ValueError, match="kind"):
        evaluate("xx", prob.x0)
    with pytest.raises(ValueError, match="valid"):
        synthesis_problem("so", "P7")


def test_dynamic_q_improves_so_p2_quickly():
    """A short Dynamic-Q run (capped) moves from the infeasible start to a better design."""
    from solvers import solve

    prob = synthesis_problem("so", "P2")
    res = solve(prob, "dynamic-q", rho=0.1, eps_f=1e-6, eps_x=1e-4, max_iter=8)
    assert res.nfg <= 9
    assert -res.f > 0.80  # from 0.768


def test_table_plugin_on_a_fake_run():
    from harness.tables.rpr3 import synthesis_table

    d = [-1.15, 0.28, 1.27, 1.91, 0.94]
    runs = pd.DataFrame([{"suite": "rpr3", "problem": "rpr3-so-p2", "solver": "dynamic-q", "status": "converged",
                          "nfg": 10, "nf": 60, "x": d, "wall_time_s": 1.0, "f": -0.9, "max_violation": 0.0,
                          "history": "[]"}])
    from manipulators.synthesis.rpr2_exact import _jsonable
    from manipulators.synthesis.rpr3_exact import exact_optimum

    # the stored reference the table reads (here only P2's, with the local stage from two starts)
    t = synthesis_table(runs, "so", {"so/P2": _jsonable(exact_optimum("so", "P2", n_starts=0))})
    # one row per run plus the published design of every P, checked in our model
    assert t.name == "table_5_3" and len(t.frame) == 7
    assert list(t.frame["solver"]).count("(thesis d*)") == 3
    i = int(np.flatnonzero(t.frame["solver"] == "dynamic-q")[0])
    row = t.frame.iloc[i]
    # P1, P3 have no run here: their thesis f* cannot count as reproduced
    thesis_rows = np.flatnonzero(t.frame["solver"] == "(thesis d*)")
    assert t.flags.iloc[thesis_rows[0]]["f* (thesis)"] and t.flags.iloc[thesis_rows[2]]["f* (thesis)"]
    assert row["f* (thesis)"] == pytest.approx(0.927)
    assert row["f(d0)"] == pytest.approx(0.768, abs=1e-3)
    # the exact-model reference reaches Table 5.3's f* for P2 (0.927) with W_p enclosed
    j = int(np.flatnonzero((t.frame["solver"] == "(exact-model optimum)") & (t.frame["P"] == "P2"))[0])
    assert t.frame.iloc[j]["f*"] >= 0.927 and t.frame.iloc[j]["enclosed"]


def test_enclosing_window_of_published_designs():
    """Exact enclosing orientations (RPR3.enclosing_orientations on W_p's boundary): the
    published MO/P1 design encloses P1 only over [0.67, 2.10] degrees, D/P1's at none
    (legs at least 1.05e-3 over, at phi ~ 0.31 degrees); SO/P2's includes phi = 0."""
    from manipulators.synthesis.rpr3_suite import _thesis_row, enclosing_window

    w = enclosing_window(_thesis_row("5.4", "P1")["d_star"], "P1", kind="mo")
    assert np.degrees(w["intervals"]).ravel() == pytest.approx([0.666, 2.098], abs=2e-3)
    assert w["covers"] is False and w["slack"] == 0.0
    w = enclosing_window(_thesis_row("5.5", "P1")["d_star"], "P1", kind="d")
    assert w["intervals"] == [] and w["slack"] == pytest.approx(1.046e-3, rel=1e-2)
    assert math.degrees(w["phi_slack"]) == pytest.approx(0.313, abs=0.01)
    w = enclosing_window(_thesis_row("5.3", "P2")["d_star"], "P2", kind="so")
    assert w["covers"] and w["intervals"][0][0] < 0.0 < w["intervals"][0][1]


def test_exact_optimum_global_stage_so_p2():
    """Differential evolution over the wide box alone, then SLSQP, reaches Table 5.3's P2 optimum."""
    from manipulators.synthesis.rpr3_exact import exact_optimum

    out = exact_optimum("so", "P2", n_starts=0)
    assert out["de_polished"] >= 0.932 and out["kinv"] >= out["de_polished"] and out["enclosed"]


def test_dextrous_dwp_has_no_jump_where_the_centre_leaves_the_workspace():
    # A Dynamic-Q+ iterate of D/P1: the chord boundary winds once around W_p's centre but
    # folds back, so the triangle scheme gave dW_p = 0.017 (polygons: 0.110) until O' left the
    # workspace between y_C + 9e-4 and + 1e-3, where g jumped to 0.1105; central differences
    # (h = 1e-3) across the jump gave dg/dy_C = +38 where the slope is -0.2
    from manipulators.synthesis.rpr3_suite import PRESCRIBED3, _Evaluator

    ev = _Evaluator("d", PRESCRIBED3["P1"])
    x = np.array([-1.0647, 0.428, 1.2438, 1.7791, 0.8261])
    g = [ev.parts(x + np.array([0.0, t, 0.0, 0.0, 0.0]))["g"] for t in (0.0, 9e-4, 1e-3)]
    assert g[0] == pytest.approx(0.1101, abs=1e-3)
    assert abs(g[2] - g[1]) < 1e-3
