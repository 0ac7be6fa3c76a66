"""Issue 15's targets for Dynamic-Q+, judged on the committed results (docs/dynamic_q_plus_targets.md).

Each test reads the stored runs (or, for the manipulator suites, whose tables need minutes of
exact geometry, the committed tables regenerated from those runs) and checks one acceptance
item of issue 15 with Dynamic-Q+ at its defaults.  So a re-run that loses a target fails here,
and the page's figures can be regenerated with ``python -m pytest -q -rA
tests/harness/test_dynamic_q_plus_targets.py``.

The items the chord-model formulations keep out of reach are ``xfail(strict=True)`` with the
measured reason: if a change ever meets them, the test fails until the page and the marker are
updated.  Nothing here runs a solver.
"""

from __future__ import annotations

import json
import pathlib
import re

import pandas as pd
import pytest

from harness import load_results

ROOT = pathlib.Path(__file__).resolve().parents[2]
RESULTS = ROOT / "results"
PLUS, LITERAL = "dynamic-q-plus", "dynamic-q"

pytestmark = pytest.mark.skipif(not (RESULTS / "hs" / "runs.parquet").is_file(),
                                reason="the committed results are not in this checkout")


def _cell(cell: object) -> tuple[float, str]:
    """(N^fg, outcome marker) of a campaign-table cell such as '47', '12*' or '101$'; marker ''
    is solved, 't' a time-out (no count)."""
    m = re.fullmatch(r"(\d+)?([^\d]*)", str(cell).strip())
    assert m, cell
    return (float(m.group(1)) if m.group(1) else float("nan")), m.group(2)


# -- hs (thesis Table 3.1) ---------------------------------------------------------------------

@pytest.fixture(scope="module")
def table_3_1():
    from harness.tables.hs import tables

    main, summary = tables(load_results("hs", RESULTS))
    return main.frame, summary.frame.set_index("solver")


def test_hs_solved_or_at_the_thesis_local_minimum(table_3_1):
    """'hs (Table 3.1): >= 39 of 40 solved or at the thesis's local minimum'."""
    _, summary = table_3_1
    row = summary.loc[PLUS]
    print(f"hs: {row['solved']} solved + {row['local min (*)']} at a local minimum of {row['problems']}")
    assert row["problems"] == 40 and row["solved"] + row["local min (*)"] >= 39


def test_hs_nfg_at_most_the_literal_dynamic_q_on_commonly_solved(table_3_1):
    """'total N^fg <= the literal dynamic-q's on commonly solved problems'."""
    main, _ = table_3_1
    both = [(_cell(a), _cell(b)) for a, b in zip(main[f"{PLUS} N^fg"], main[f"{LITERAL} N^fg"])]
    common = [(a[0], b[0]) for a, b in both if a[1] == "" and b[1] == ""]
    plus, literal = sum(a for a, _ in common), sum(b for _, b in common)
    print(f"hs: total N^fg over the {len(common)} problems both solve: {plus:g} against {literal:g}")
    assert len(common) >= 30 and plus <= literal


# -- hs-all (every HS problem of CUTEst) --------------------------------------------------------

@pytest.fixture(scope="module")
def hs_all():
    from harness.tables.hs_all import tables

    reference = json.loads((RESULTS / "hs-all" / "reference.json").read_text())
    summary, per_case = tables(load_results("hs-all", RESULTS), reference)
    return summary.frame.set_index("solver"), per_case.frame


def test_hs_all_solved_count(hs_all):
    """'solved count >= scipy-slsqp's and within 3 of Ipopt's'."""
    summary, _ = hs_all
    solved = summary["solved"]
    print(f"hs-all solved: {PLUS} {solved[PLUS]}, scipy-slsqp {solved['scipy-slsqp']}, ipopt {solved['ipopt']}")
    assert solved[PLUS] >= solved["scipy-slsqp"] and solved[PLUS] >= solved["ipopt"] - 3


def test_hs_all_median_nfg_on_problems_both_solve(hs_all):
    """'median N^fg over commonly solved problems <= scipy-slsqp's', read pairwise: over the
    problems that both Dynamic-Q+ and SLSQP solve (the table's own column, over the cases every
    solver solves, is printed too: it is not the target's reading)."""
    summary, per_case = hs_all
    cells = pd.DataFrame({s: [_cell(c) for c in per_case[s]] for s in (PLUS, "scipy-slsqp")})
    both = cells[[a[1] == "" and b[1] == "" for a, b in zip(cells[PLUS], cells["scipy-slsqp"])]]
    med = {s: float(pd.Series([c[0] for c in both[s]]).median()) for s in both}
    every = summary["median N^fg (commonly solved)"]
    print(f"hs-all median N^fg over the {len(both)} problems both solve: {med}; over the "
          f"{summary['commonly solved'][PLUS]} every solver solves: {PLUS} {every[PLUS]}, "
          f"scipy-slsqp {every['scipy-slsqp']}")
    assert len(both) >= 90 and med[PLUS] <= med["scipy-slsqp"]


# -- 2-RPR (thesis Ch. 4) -----------------------------------------------------------------------

def _csv(suite: str, stem: str) -> pd.DataFrame:
    return pd.read_csv(RESULTS / suite / f"{stem}.csv", dtype=str, keep_default_na=False)


def _num(s: str) -> float:
    return float(str(s).replace("⚑", "").strip())


E_TARGET, DW_TARGET = 3.2, 0.01
TARGET_COLUMN = f"f* <= {E_TARGET}, dW_p <= {DW_TARGET}"  # the spread tables' count of ends meeting the target


def test_rpr2_exact_E_synthesis_from_every_start():
    """'2-RPR E synthesis from SP1-SP4: exact dW_p <= 0.01 at every end and f* <= 3.2', in the
    exact smooth form of (4.14) (suite rpr2-exact: leg limits on W_p's boundary, analytic
    derivatives)."""
    t = _csv("rpr2-exact", "table_4_7x")
    rows = t[t["solver"] == PLUS].set_index("start")
    print("rpr2-exact E:", {s: (_num(r["f*"]), _num(r["dW_p exact"])) for s, r in rows.iterrows()})
    assert sorted(rows.index) == ["SP1", "SP2", "SP3", "SP4"]
    assert all(_num(r["f*"]) <= E_TARGET and _num(r["dW_p exact"]) <= DW_TARGET for _, r in rows.iterrows())


def test_rpr2_chord_E_spread_with_forward_differences():
    """What docs/dynamic_q_plus_targets.md says of Table 4.7s (forward differences, 44 starts):
    SLSQP meets the E target from 38 of them (11 / 10 / 7 / 10 per thesis start), Dynamic-Q+
    from 12 (2 / 10 / 0 / 0)."""
    t = _csv("rpr2-spread", "table_4_7s")
    e = t[t["synthesis"] == "E"]
    met = {solver: [int(v.split(" of ")[0]) for v in g.sort_values("start")[TARGET_COLUMN]]
           for solver, g in e.groupby("solver")}
    assert met["scipy-slsqp"] == [11, 10, 7, 10]
    assert met[PLUS] == [2, 10, 0, 0]


@pytest.mark.xfail(strict=True, reason="chord formulation (4.14): h = dW_p >= 0 vanishes with its gradient on "
                   "the feasible set and is linearized by forward differences of a chord-0.1 boundary; the ends "
                   "are enclosing designs above the basin's minimum 3.1436 from SP1, SP3, SP4, and the E cells "
                   "are a spread for every solver (Table 4.7s: SLSQP meets the target from 38 of 44 starts, "
                   "Dynamic-Q+ from 12, from 28-34 with mu0 in 0.1-3, none of which meets it from all four); "
                   "with central differences (a diagnostic) the target holds from every start "
                   "(docs/dynamic_q_plus_targets.md)")
def test_rpr2_chord_E_synthesis_from_every_start():
    """The same target on suite rpr2's chord formulation (Table 4.7)."""
    t = _csv("rpr2", "table_4_7")
    rows = t[t["solver"] == PLUS].set_index("start")
    print("rpr2 E (chord):", {s: (_num(r["f exact"]), _num(r["dW_p exact"])) for s, r in rows.iterrows()})
    assert len(rows) == 4
    assert all(_num(r["f exact"]) <= E_TARGET and _num(r["dW_p exact"]) <= DW_TARGET for _, r in rows.iterrows())


def test_rpr2_central_E_synthesis_from_every_start():
    """The same target with central differences and suite rpr2's settings otherwise (suite
    rpr2-central, Table 4.7c): from every thesis start; the spread over the 11 starts per SP is
    printed."""
    t = _csv("rpr2-central", "table_4_7c")
    rows = t[t["solver"] == PLUS].set_index("start")
    print("rpr2-central E:", {s: (r["f* from the start itself"], r[TARGET_COLUMN])
                              for s, r in rows.iterrows()})
    assert sorted(rows.index) == ["SP1", "SP2", "SP3", "SP4"]
    assert all(_num(r["f* from the start itself"]) <= E_TARGET for _, r in rows.iterrows())
    assert all(float(r["dW_p exact"].split("-")[-1]) <= DW_TARGET for _, r in rows.iterrows())


def test_rpr2_chord_E_ends_enclose_W_p():
    """The part of the E target the chord formulation does allow: every end leaves at most 0.01 of
    W_p uncovered in exact geometry."""
    t = _csv("rpr2", "table_4_7")
    dw = [_num(v) for v in t.loc[t["solver"] == PLUS, "dW_p exact"]]
    assert len(dw) == 4 and max(dw) <= DW_TARGET


@pytest.mark.parametrize("stem", ["table_4_3", "table_4_4", "table_4_5", "table_4_6"])
def test_rpr2_o_synthesis_no_worse_than_the_literal_dynamic_q(stem):
    """'O ... synthesis no worse than the literal dynamic-q' (Tables 4.3-4.6, SP1-SP4: f* is
    minimized)."""
    t = _csv("rpr2", stem).set_index("solver")
    plus, literal = _num(t.loc[PLUS, "f* (disc.)"]), _num(t.loc[LITERAL, "f* (disc.)"])
    print(f"{stem}: O f* {plus} against the literal {literal}")
    assert plus <= literal


#: Table 4.9's own tolerance for f* (its note: flagged when more than 0.005 below the thesis's)
P_TOL = 0.005


def test_rpr2_p_synthesis_objective_no_worse_than_the_literal_dynamic_q():
    """'P synthesis no worse than the literal dynamic-q' in f* = min kappa^-1 (maximized), to
    Table 4.9's tolerance."""
    t = _csv("rpr2", "table_4_9").set_index(["P", "solver"])
    got = {p: (_num(t.loc[(p, PLUS), "f*"]), _num(t.loc[(p, LITERAL), "f*"])) for p in ("P1", "P2", "P3")}
    print("rpr2 P f* (Dynamic-Q+, literal):", got)
    assert all(plus >= literal - P_TOL for plus, literal in got.values())


@pytest.mark.xfail(strict=True, reason="P1: Dynamic-Q+ (and SLSQP, at the same design) ends on the chord "
                   "model's constraint boundary (g* = -7e-11), where exact geometry leaves 0.00089 of P outside "
                   "the workspace, above Table 4.9's 1e-4 area(P); the literal Dynamic-Q stops 3e-4 inside "
                   "(g* = -3e-4) and encloses P")
def test_rpr2_p_synthesis_encloses_wherever_the_literal_dynamic_q_does():
    t = _csv("rpr2", "table_4_9").set_index(["P", "solver"])
    got = {p: (t.loc[(p, PLUS), "enclosed"], t.loc[(p, LITERAL), "enclosed"]) for p in ("P1", "P2", "P3")}
    print("rpr2 P enclosed (Dynamic-Q+, literal):", got)
    assert all(plus == "True" or literal != "True" for plus, literal in got.values())


def test_rpr2_exact_p_synthesis_at_the_exact_optimum():
    """The P target in the exact form of (4.21) (suite rpr2-exact, Table 4.9x: kappa^-1 >= t at
    the same 2048 points, leg limits on dP): Dynamic-Q+ ends at the exact optimum for P1-P3,
    so at or above the literal Dynamic-Q's t* wherever that end is feasible."""
    t = _csv("rpr2-exact", "table_4_9x").set_index(["P", "solver"])
    got = {p: t.loc[(p, PLUS), "reached"] for p in ("P1", "P2", "P3")}
    print("rpr2-exact P:", got, {p: t.loc[(p, PLUS), "t*"] for p in got})
    assert all(v == "exact optimum" for v in got.values())


# -- 3-RPR (thesis Ch. 5) -----------------------------------------------------------------------

KINV_TOL = 0.01


def _rpr3(stem: str) -> pd.DataFrame:
    t = _csv("rpr3", stem)
    return t.set_index(["P", "solver"])


@pytest.mark.parametrize("stem", ["table_5_4", "table_5_5"])
def test_rpr3_mo_and_d_ends_enclose_W_p(stem):
    """'every end of the improved variant encloses W_p in exact geometry (at most 0.1% of its
    area outside)'."""
    t = _rpr3(stem)
    out = {p: _num(t.loc[(p, PLUS), "exact dW_p/W_p"]) for p in ("P1", "P2", "P3")}
    print(f"{stem}: uncovered fraction of W_p {out}")
    assert all(v <= 1e-3 for v in out.values())


@pytest.mark.parametrize("stem,p", [(s, p) for s in ("table_5_4", "table_5_5") for p in ("P2", "P3")])
def test_rpr3_chord_p2_p3_at_the_exact_optimum(stem, p):
    """'min kappa^-1 within 0.01 of the exact-model optima' (P2, P3: the exact optimum from d0
    is the best found)."""
    t = _rpr3(stem)
    ours, best = _num(t.loc[(p, PLUS), "f*"]), _num(t.loc[(p, "(exact-model optimum)"), "f*"])
    assert abs(ours - best) <= KINV_TOL, (ours, best)


@pytest.mark.xfail(strict=True, reason="chord formulation: f = min kappa^-1 over W_p's boundary points is a "
                   "kinked min of forward-differenced terms; from d0 Dynamic-Q+ stops 0.017 short of the exact "
                   "local optimum 0.1707, and from starts within 1e-6 of d0 the ends spread "
                   "(Dynamic-Q+ 0.085-0.154, SLSQP 0.103-0.163; Table 5.4s)")
def test_rpr3_chord_mo_p1_at_the_exact_local_optimum():
    t = _rpr3("table_5_4")
    ours, local = _num(t.loc[("P1", PLUS), "f*"]), _num(t.loc[("P1", "(exact local min from d0)"), "f*"])
    print(f"rpr3 MO P1 (chord): {ours} against the exact local optimum from d0 {local}")
    assert ours >= local - KINV_TOL


def test_rpr3_chord_d_p1_no_worse_than_the_exact_local_optimum():
    """D P1 ends above the exact local optimum from d0 (0.1707), in another basin but below the best
    found (0.4291): the target's 'within 0.01' read as 'not more than 0.01 below' (a higher min
    kappa^-1 of an enclosing design is better)."""
    t = _rpr3("table_5_5")
    ours, local = _num(t.loc[("P1", PLUS), "f*"]), _num(t.loc[("P1", "(exact local min from d0)"), "f*"])
    print(f"rpr3 D P1 (chord): {ours}; exact local optimum from d0 {local}")
    assert ours >= local - KINV_TOL


def test_rpr3_exact_mo_and_d_at_the_exact_local_optimum():
    """The 3-RPR target in the exact form (suite rpr3-exact: leg limits and kappa^-1 at W_p's
    boundary points): every MO and D end within 0.01 of the exact local optimum from the start."""
    t = _csv("rpr3-exact", "table_5_3x")
    t = t[t["synthesis"].str.startswith(("MO", "D"))]
    got = {}
    for (syn, p), g in t.groupby(["synthesis", "P"]):
        g = g.set_index("solver")
        got[(syn, p)] = (_num(g.loc[PLUS, "t* = min kappa^-1"]),
                         _num(g.loc["(exact local min from d0)", "t* = min kappa^-1"]))
    print("rpr3-exact:", got)
    assert len(got) == 6
    assert all(abs(a - b) <= KINV_TOL for a, b in got.values())
