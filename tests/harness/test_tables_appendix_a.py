"""Tables 2.1/2.2 plug-in: layout, ours beside the thesis's, tolerance flags."""

import pandas as pd
import pytest

from harness._record import result_to_row
from harness.tables import appendix_a as plugin
from problems.appendix_a import make_case
from solvers import get_solver_class, solve


def _row(case, solver, **override):
    valid = [o["name"] for o in get_solver_class(solver).options()]
    row = result_to_row("appendix-a", case, solve(case.problem, solver, **case.options_for(solver, valid)))
    row.update(override)
    return row


@pytest.fixture(scope="module")
def runs():
    a01, a02, a04 = make_case("a01"), make_case("a02"), make_case("a04")
    rows = [_row(a01, s) for s in ("sqsd", "sd", "fletcher-reeves", "polak-ribiere", "scipy-cg", "scipy-lbfgsb")]
    rows.append(_row(a02, "sqsd", nfg=93))  # 3x the thesis's 31: must be flagged
    rows.append(_row(a02, "sd", status="max_iter"))  # thesis converged: must be flagged
    rows.append(_row(a04, "sqsd"))
    # SD on problem 4 stopped by the "> 20000" cap, as in the thesis (not flagged)
    rows.append(_row(make_case("a04"), "fletcher-reeves") | {"solver": "sd", "status": "max_iter", "nfg": 20000})
    return pd.DataFrame(rows)


def test_three_tables_in_thesis_layout(runs):
    t21, t22, tsp = plugin.tables(runs)
    assert (t21.name, t22.name, tsp.name) == ("table_2_1", "table_2_2", "appendix_a_scipy")
    # every thesis line appears, including problem 14's rho = 10 lines
    assert len(t21.frame) == 32 and len(t22.frame) == 27
    assert list(t21.frame.columns[:5]) == ["Prob.", "n", "rho", "SQSD N^fg", "SQSD N^fg thesis"]
    assert {"FR N^it", "FR N^it thesis", "PR E^r/I^inf", "PR E^r/I^inf thesis"} <= set(t22.frame.columns)
    assert t21.flags.shape == t21.frame.shape
    r1 = t21.frame.iloc[0]
    assert (r1["Prob."], r1["n"], r1["rho"], r1["SQSD N^fg thesis"], r1["SD N^fg thesis"]) == (
        "1",
        "3",
        "1",
        "12",
        "41",
    )
    assert r1["SD N^fg"] == "41" and r1["SD N^it"] == "20"
    assert t21.frame.iloc[3]["SD N^fg"] == "> 20000" and t21.frame.iloc[3]["SD N^fg thesis"] == "> 20000"
    iinf = t21.frame[(t21.frame["Prob."] == "14") & (t21.frame["n"] == "200")].iloc[0]
    assert iinf["SD E^r/I^inf thesis"].endswith("(I)")
    assert t21.frame[t21.frame["Prob."] == "8"].iloc[0]["SD N^fg thesis"] == "12050*"
    assert any("N^fg" in n for n in t21.notes)


def test_flags_mark_cells_outside_the_tolerance(runs):
    t21, t22, _ = plugin.tables(runs)
    f = t21.flags
    assert not f.iloc[0].any()  # problem 1: every method within tolerance
    assert f.iloc[1]["SQSD N^fg"] and f.iloc[1]["SD N^fg"]  # problem 2: 3x N^fg; SD did not converge
    assert not f.iloc[3]["SD N^fg"]  # problem 4: SD capped like the thesis
    assert not f.iloc[3]["SQSD N^fg"]
    assert not t22.flags.iloc[0].any()
    assert "SQSD: 2 of 3 rows within tolerance" in " ".join(t21.notes)


def _with(s, **kw):
    out = s.copy()
    for k, v in kw.items():
        out[k] = v
    return out


def test_within_tolerance_rules():
    th = pd.Series({"nfg": "100", "er": "1.E-12", "er_kind": "Er", "problem": "13", "nfg_bound": ""})
    ok = pd.Series({"status": "converged", "nfg": 149, "rel_error": 1e-9, "inf_error": 0.0})
    assert plugin.within_tolerance("SQSD", "13", 100, th, ok) == {"nfg": True, "err": True}
    assert plugin.within_tolerance("SQSD", "12", 200, th, ok)["nfg"] is False  # +-15% there
    assert plugin.within_tolerance("SQSD", "13", 100, th, _with(ok, rel_error=2e-8))["err"] is False
    capped = _with(th, nfg="", nfg_bound="20000")
    assert plugin.within_tolerance("SD", "13", 100, capped, ok)["nfg"] is False  # thesis did not converge
    assert plugin.within_tolerance("SD", "13", 100, capped, _with(ok, status="failed"))["nfg"] is True
    assert plugin.within_tolerance("SD", "13", 100, th, None) == {"nfg": False, "err": False}


def test_scipy_table_lists_each_case_once(runs):
    tsp = plugin.tables(runs)[2]
    assert list(tsp.frame["Prob."]) == ["a01", "a02", "a04"]
    assert tsp.frame.iloc[0]["scipy-cg N^fg"] != "—" and tsp.frame.iloc[0]["scipy-bfgs N^fg"] == "—"
