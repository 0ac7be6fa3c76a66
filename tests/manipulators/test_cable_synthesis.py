"""Suite ``tdpm`` (thesis Section 6.6), its table and figure plug-ins."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from manipulators.cable import BETA_MIN
from manipulators.synthesis.tdpm_suite import SUITE, dextrous_area, published, separations, tdpm_problem


def test_separations_wrap_around():
    s = separations([0.1, 6.2, 3.0])
    np.testing.assert_allclose(s, [2 * np.pi - 6.1, 2 * np.pi - 3.2, 2.9])
    assert np.all((s >= 0) & (s <= np.pi))
    np.testing.assert_allclose(separations([-0.3146, 2.379, 5.794]), separations([2 * np.pi - 0.3146, 2.379, 5.794]))


def test_suite_cases_and_starts():
    cases = SUITE.cases()
    assert len(cases) == 30
    assert {c.problem_id for c in cases} == {f"tdpm{n}-l{k}" for n in (3, 4) for k in (1, 2, 3)}
    assert {c.start for c in cases} == {"R1", "R2", "R3", "R4", "R5"}
    for c in cases:
        p = c.problem
        assert p.fd == "central" and p.fd_step == (0.05 if p.n == 3 else 0.1)
        assert np.all(p.ineq(p.x0) <= 0)            # (6.29) at the start
        if c.start == "R1":                         # (all starts are screened by random_starts)
            assert -p.objective(p.x0) > 0           # non-empty dextrous workspace
        assert p.f_ref == -max(r["A_dstar"] for r in published()[(p.n, c.meta["load"])])
    assert SUITE.solvers == ("dynamic-q", "dynamic-q-plus", "scipy-slsqp", "nlopt-mma", "scipy-cobyla")
    # deterministic: a rebuild gives the same starts
    from manipulators.synthesis import tdpm_suite

    assert tdpm_suite._build()[0].problem.x0.tolist() == cases[0].problem.x0.tolist()


def test_problem_at_published_design():
    p = tdpm_problem(3, "L3", [0.6543, 2.357, 4.252])
    assert -p.objective(p.x0) == pytest.approx(1.024, rel=0.01)  # ERRATA: 1.024
    g = p.ineq(np.array([0.0, 0.1, 3.0]))
    assert g[0] == pytest.approx(BETA_MIN - 0.1)
    with pytest.raises(ValueError, match="cables"):
        tdpm_problem(5, "L1", [0, 1, 2, 3, 4])
    with pytest.raises(ValueError, match="load"):
        tdpm_problem(3, "L9", [0, 2, 4])
    with pytest.raises(ValueError, match="finite"):
        dextrous_area([0.0, np.nan, 4.0], "L1")


def _fake_runs():
    """Two stored-run rows as the harness writes them (columns of harness._record)."""
    c = SUITE.case("tdpm3-l3/n=3/R1")
    x = np.array([0.6543, 2.357, 4.252])
    f = -dextrous_area(x, "L3")
    return pd.DataFrame([
        {"suite": "tdpm", "problem": "tdpm3-l3", "case_id": c.case_id, "start": "R1", "solver": "dynamic-q",
         "ng": 30, "nfg": 60, "f": f, "x": list(x), "status": "converged"},
        {"suite": "tdpm", "problem": "tdpm3-l3", "case_id": c.case_id, "start": "R1", "solver": "scipy-cobyla",
         "ng": 0, "nfg": 40, "f": -0.5, "x": list(c.problem.x0), "status": "converged"},
    ])


def test_table_plugin():
    from harness.tables.tdpm import tables

    out = {t.name: t for t in tables(_fake_runs())}
    assert {"table_6_5", "table_6_7", "table_6_10", "table_6_best", "table_6_published"} <= set(out)
    t67 = out["table_6_7"].frame
    assert (t67.source == "ours").sum() == 2 and (t67.source != "ours").sum() == 4
    best = out["table_6_best"]
    row = best.frame.set_index("solver").loc["dynamic-q"]
    assert row["A_d* best (ours)"] == pytest.approx(1.024, rel=0.01)
    flags = best.flags.set_index(best.frame.solver)
    assert not flags.loc["dynamic-q", "A_d* best (ours)"]
    assert flags.loc["scipy-cobyla", "A_d* best (ours)"]      # 0.5 < 0.98 x 1.024
    pub = out["table_6_published"]
    assert pub.flags["A_d* ours"].sum() == 1                  # only Table 6.6 run 4


def test_synthesis_figure(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    from harness.figures.tdpm import _synthesis_figs

    paths = _synthesis_figs(_fake_runs(), tmp_path)
    assert [p.name for p in paths] == ["fig_6_12.png"] and paths[0].stat().st_size > 1000
