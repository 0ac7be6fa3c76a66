"""Table 3.1 plug-in on a synthetic runs frame: markers, E^r, summary, notes."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from harness.tables import hs
from problems.hs import problem

F_REF = {pid: problem(pid).f_ref for pid in ("hs002", "hs010", "hs013", "hs015", "hs036", "hs071")}


def _row(pid, solver, f, nfg, viol=0.0, status="converged"):
    return {"suite": "hs", "problem": pid, "n": problem(pid).n, "solver": solver, "nfg": nfg, "f": f,
            "f_ref": F_REF[pid], "max_violation": viol, "status": status}


@pytest.fixture(scope="module")
def runs():
    return pd.DataFrame([
        _row("hs010", "dynamic-q", -1.0 + 1e-9, 13),
        _row("hs002", "dynamic-q", 4.941229317989184, 7),        # the local minimum (x1 < 0)
        _row("hs013", "dynamic-q", 0.959, 50, status="max_iter"),
        _row("hs071", "scipy-slsqp", F_REF["hs071"], 6, viol=1e-3),  # optimal value but infeasible
        _row("hs015", "ipopt", 360.38, 12),                      # thesis's local min, printed as 360
        _row("hs036", "dynamic-q", 99.0, 5),                     # stale run, replaced by the next row
        _row("hs036", "dynamic-q", F_REF["hs036"], 100),         # 100 vs thesis 15: > 2x
        _row("hs010", "scipy-slsqp", 5.0, 3, status="failed"),
    ])


def _cell(table, pid, col):
    frame = table.frame.set_index("Prob. #")
    return frame.loc[int(pid[2:]), col]


def test_relative_error_is_eq_3_12():
    assert hs.relative_error(-1.0, -0.5) == pytest.approx(0.25)
    assert math.isnan(hs.relative_error(float("nan"), 1.0))


def test_markers_follow_the_rules(runs):
    main, summary = hs.tables(runs)
    assert _cell(main, "hs010", "dynamic-q N^fg") == "13"
    assert _cell(main, "hs002", "dynamic-q N^fg") == "7*"
    assert float(_cell(main, "hs002", "dynamic-q E^r")) < 1e-12  # relative to the local minimum
    assert _cell(main, "hs013", "dynamic-q N^fg") == "50$"
    assert _cell(main, "hs071", "scipy-slsqp N^fg") == "6~"  # infeasible: never solved
    assert _cell(main, "hs015", "ipopt N^fg") == "12*"
    assert _cell(main, "hs036", "dynamic-q N^fg") == "100"
    assert _cell(main, "hs010", "scipy-slsqp N^fg") == "3~"


def test_thesis_columns_are_beside_ours(runs):
    main, _ = hs.tables(runs)
    cols = list(main.frame.columns)
    assert cols[:3] == ["Prob. #", "n", "f_act"]
    assert cols.index("SQP (thesis) N^fg") < cols.index("Dynamic-Q (thesis) N^fg") < cols.index("dynamic-q N^fg")
    assert _cell(main, "hs002", "Dynamic-Q (thesis) N^fg") == "7*"
    assert _cell(main, "hs013", "Dynamic-Q (thesis) N^fg") == "50$"
    assert _cell(main, "hs010", "Dynamic-Q (thesis) E^r").startswith("<")


def test_summary_counts_and_medians(runs):
    _, summary = hs.tables(runs)
    s = summary.frame.set_index("solver")
    dq = s.loc["dynamic-q"]
    assert (dq["problems"], dq["solved"], dq["local min (*)"], dq["cap ($)"], dq["failed (~)"]) == (4, 2, 1, 1, 0)
    assert dq["total N^fg"] == 13 + 7 + 50 + 100
    assert dq["median N^fg"] == pytest.approx((13 + 50) / 2)
    assert dq["total N^fg (solved)"] == 113
    assert s.loc["scipy-slsqp", "solved"] == 0
    # the thesis's own columns judged by the same rule, over the problems present
    assert s.loc["Dynamic-Q (thesis)", "problems"] == 6
    assert s.loc["Dynamic-Q (thesis)", "local min (*)"] == 2  # HS2 and HS15


def test_notes_list_problems_differing_by_more_than_2x(runs):
    main, summary = hs.tables(runs)
    text = "\n".join(main.notes)
    assert "HS36, dynamic-q" in text and "100 vs 15" in text
    assert "HS10, dynamic-q" not in text  # 13 vs 13
    assert "Svanberg" in text
    assert main.flags.set_index(main.frame["Prob. #"]).loc[36, "dynamic-q N^fg"]
    assert any("ratio" in n for n in summary.notes)  # dynamic-q total vs the thesis's


def test_empty_runs_still_render_the_thesis_columns():
    empty = pd.DataFrame(columns=["suite", "problem", "n", "solver", "nfg", "f", "f_ref", "max_violation", "status"])
    main, summary = hs.tables(empty)
    assert len(main.frame) == 40
    assert list(summary.frame["solver"]) == ["SQP (thesis)", "Dynamic-Q (thesis)"]
