"""Tables 4.3-4.7 and 4.9 (2-RPR synthesis, thesis Chapter 4): ours beside the thesis's.

Every row also shows the *exact* objective at its d* (polygon geometry with exact annulus
arcs, `manipulators.synthesis.rpr2_suite.evaluate`), for our designs and for the thesis's
published ones: the O-synthesis objective minimized with chord 0.5 is strongly
discretized (ERRATA.md).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd

from harness.reference import thesis_table

from ._base import Table

__all__ = ["tables"]

THESIS_NAMES = {"Dynamic-Q": "dynamic-q", "SQSD": "sqsd", "LfopC": "lfopc", "EtopC": "etopc"}
O_TABLES = {"SP1": "4.3", "SP2": "4.4", "SP3": "4.5", "SP4": "4.6"}
O_LIMIT = 0.66  # issue 5 acceptance: discretized f* <= 0.66 (thesis 0.596-0.648)
P_TOL = 0.005  # issue 5 acceptance: P-synthesis f* within 0.005 of Table 4.9 (or higher)
E_REL = 0.05  # issue 5 acceptance: E-synthesis f* within 5 % of Table 4.7


def _fmt_d(x) -> str:
    try:
        return "[" + ", ".join(f"{float(v):.4g}" for v in x) + "]"
    except TypeError:
        return ""


def _num(v, fmt=".6g") -> str:
    try:
        v = float(v)
    except (TypeError, ValueError):
        return ""
    return "" if not math.isfinite(v) else format(v, fmt)


def _evaluate(kind, x, prescribed="P1"):
    from manipulators.synthesis.rpr2_suite import evaluate

    try:
        return evaluate(kind, np.asarray(x, dtype=float), prescribed)
    except Exception:  # noqa: BLE001  (a broken row must not break the table)
        return {}


def _status(row) -> str:
    s = str(row.get("status", ""))
    return "not applicable" if s == "not_applicable" else s


def _ours(runs: pd.DataFrame, problem: str, start: str) -> pd.DataFrame:
    if runs is None or runs.empty or "problem" not in runs:
        return pd.DataFrame()
    return runs[(runs["problem"] == problem) & (runs["start"] == start)]


def _o_table(runs: pd.DataFrame, start: str, thesis: pd.DataFrame) -> Table:
    rows, flags = [], []
    th = thesis[thesis["start"] == start]
    for _, t in th.iterrows():  # the thesis's rows, recomputed exactly
        d = [float(t[c]) for c in ("x_A", "y_A", "x_B", "l1_min", "l2_min")]
        ev = _evaluate("o", d)
        rows.append({"source": "thesis", "solver": t["algorithm"], "N^g": t["ng"], "N^fg": "",
                     "f* (disc.)": t["f_star"], "f ours at d* (disc.)": _num(ev.get("f")),
                     "f exact at d*": _num(ev.get("f_exact")), "d*": _fmt_d(d), "status": ""})
        flags.append(False)
    for _, r in _ours(runs, "rpr2-o", start).iterrows():
        applicable = r["status"] != "not_applicable"
        ev = _evaluate("o", r["x"]) if applicable and len(r["x"]) == 5 else {}
        f = r["f"]
        rows.append({"source": "ours", "solver": r["solver"], "N^g": r["ng"], "N^fg": r["nfg"],
                     "f* (disc.)": _num(f), "f ours at d* (disc.)": _num(ev.get("f")),
                     "f exact at d*": _num(ev.get("f_exact")), "d*": _fmt_d(r["x"]) if applicable else "",
                     "status": _status(r)})
        thesis_alg = r["solver"] in THESIS_NAMES.values()
        flags.append(bool(applicable and thesis_alg and not (np.isfinite(f) and f <= O_LIMIT)))
    frame = pd.DataFrame(rows)
    fl = pd.DataFrame(False, index=frame.index, columns=frame.columns)
    if len(frame):
        fl["f* (disc.)"] = flags
    return Table(
        name=f"table_{O_TABLES[start].replace('.', '_')}",
        title=f"Table {O_TABLES[start]}: O synthesis from {start} (chord 0.5, triangle scheme)",
        frame=frame, flags=fl,
        notes=["f* (disc.) is the objective minimized: 0.5 dW_p + 0.5 dW_c by the triangle scheme (4.9) on "
               "the chord-0.5 boundary; 'f ours at d*' recomputes it with our chord method at the printed d* (it "
               "equals the thesis's f* to 1e-4 for 10 of its 16 rows; at the others the 4-digit d* falls on a "
               "different number of chord points), 'f exact' uses exact annulus geometry.",
               f"Flagged: a thesis algorithm of ours ending above {O_LIMIT} (issue 5 acceptance).",
               "Dynamic-Q from SP3 reaches f = 0.642 and then cycles (period 7, f between 0.665 and 1.03) "
               "until its 300-iteration cap; at the cap it returns its best feasible iterate (option "
               "on_cap='best'; the literal last iterate, on_cap='last', is at 0.885). Not reproduced "
               "(flagged): ETOPC is a reconstruction (Sec. 4.4 gives no details); from SP3 it ends at 0.6609.",
               "SLSQP and Ipopt ending at 2.483 = area(W_p)/2 stepped to a design with an empty workspace "
               "(dW_c = 0, dW_p = area(W_p)), a flat region where every difference gradient is 0.",
               "Complex [84] is the literature value of Gosselin and Guillot.",
               "N^g counts gradient evaluations (forward differences, Gamma = 1e-5); N^fg distinct points."])


def _e_table(runs: pd.DataFrame, thesis: pd.DataFrame) -> Table:
    rows, flags = [], []
    for _, t in thesis.iterrows():
        start = t["start"]
        d = [float(t[c]) for c in ("x_A", "y_A", "x_B", "l1_min", "l2_min")]
        ev = _evaluate("e", d)
        rows.append({"start": start, "source": "thesis", "solver": "Dynamic-Q", "N^g": t["ng"], "N^fg": "",
                     "f*": t["f_star"], "h*": t["h_star"], "f exact": _num(ev.get("dwc_exact")),
                     "dW_p exact": _num(ev.get("dwp_exact"), ".3g"), "d*": _fmt_d(d), "status": ""})
        flags.append(False)
        f_th = float(t["f_star"])
        for _, r in _ours(runs, "rpr2-e", start).iterrows():
            applicable = r["status"] != "not_applicable"
            ev = _evaluate("e", r["x"]) if applicable and len(r["x"]) == 5 else {}
            rows.append({"start": start, "source": "ours", "solver": r["solver"], "N^g": r["ng"], "N^fg": r["nfg"],
                         "f*": _num(r["f"]), "h*": _num(ev.get("h"), ".2g"), "f exact": _num(ev.get("dwc_exact")),
                         "dW_p exact": _num(ev.get("dwp_exact"), ".3g"),
                         "d*": _fmt_d(r["x"]) if applicable else "", "status": _status(r)})
            bad = (r["solver"] == "dynamic-q" and applicable
                   and not (abs(float(r["f"]) - f_th) <= E_REL * f_th and ev.get("dwp_exact", 1.0) <= 0.01))
            flags.append(bool(bad))
    frame = pd.DataFrame(rows)
    fl = pd.DataFrame(False, index=frame.index, columns=frame.columns)
    if len(frame):
        fl["f*"] = flags
    return Table(name="table_4_7", title="Table 4.7: E synthesis (chord 0.1): min dW_c s.t. dW_p = 0",
                 frame=frame, flags=fl,
                 notes=["f* = dW_c and h* = dW_p by the triangle scheme; 'exact' columns from exact geometry.",
                        f"Flagged: Dynamic-Q f* not within {E_REL:.0%} of the thesis or exact dW_p > 0.01.",
                        "Dynamic-Q stops on (3.10) as printed (at infeasible iterates too, as the thesis's h* > 0 show). "
                        "From SP2 it reproduces the thesis (f* 2.836 vs 2.850). Not reproduced from SP1, SP3, SP4: it "
                        "ends with the prescribed workspace enclosed to exact dW_p < 0.01 but at designs with a narrower "
                        "base (x_B - x_A = 5.7-6.5, f* 4.2-4.4) than the thesis's (8.2-9.1, f* 2.9-3.2).",
                        "Ipopt steps to a design with an empty workspace (h = dW_p = area(W_p) = 4.966, constant there) "
                        "and reports a locally infeasible problem."])


def _p_table(runs: pd.DataFrame, thesis: pd.DataFrame) -> Table:
    rows, flags = [], []
    for _, t in thesis.iterrows():
        P = t["workspace"]
        d = [float(t[c]) for c in ("x_A", "y_A", "x_B")]
        ev = _evaluate("p", d, P)
        rows.append({"P": P, "source": "thesis", "solver": "Dynamic-Q", "N^g": t["ng"], "N^fg": "",
                     "f(d0)": t["f_d0"], "f*": t["f_star"], "g*": t["g_star"],
                     "f exact": _num(ev.get("kinv_exact"), ".4f"), "dW_p exact": _num(ev.get("dwp_exact"), ".2g"),
                     "enclosed": ev.get("enclosed", ""), "d*": _fmt_d(d), "status": ""})
        flags.append(False)
        f0 = _evaluate("p", (-4.0, -0.1, 4.0), P).get("f")
        for _, r in _ours(runs, f"rpr2-p{P[-1]}", "d0").iterrows():
            applicable = r["status"] != "not_applicable"
            ev = _evaluate("p", r["x"], P) if applicable and len(r["x"]) == 3 else {}
            fstar = -float(r["f"]) if r["f"] is not None and np.isfinite(r["f"]) else float("nan")
            rows.append({"P": P, "source": "ours", "solver": r["solver"], "N^g": r["ng"], "N^fg": r["nfg"],
                         "f(d0)": _num(f0, ".3f"), "f*": _num(fstar, ".4f"), "g*": _num(ev.get("g"), ".2g"),
                         "f exact": _num(ev.get("kinv_exact"), ".4f"), "dW_p exact": _num(ev.get("dwp_exact"), ".2g"),
                         "enclosed": ev.get("enclosed", ""), "d*": _fmt_d(r["x"]) if applicable else "",
                         "status": _status(r)})
            bad = (r["solver"] == "dynamic-q" and applicable
                   and not (fstar >= float(t["f_star"]) - P_TOL and ev.get("enclosed", False)))
            flags.append(bool(bad))
    frame = pd.DataFrame(rows)
    fl = pd.DataFrame(False, index=frame.index, columns=frame.columns)
    if len(frame):
        fl["f*"] = flags
    return Table(name="table_4_9", title="Table 4.9: P synthesis: max min kappa^-1 over dP s.t. g(d) <= 0 (4.16)",
                 frame=frame, flags=fl,
                 notes=["f = min kappa^-1 over the prescribed boundary (2048 points); g* from (4.16) with the "
                        "triangle scheme; 'enclosed' = exact dW_p <= 1e-4 area(P).",
                        f"Flagged: Dynamic-Q f* more than {P_TOL} below the thesis's, or P not enclosed."])


def tables(runs: pd.DataFrame) -> list[Table]:
    """Tables 4.3-4.6 (O synthesis per start), 4.7 (E synthesis), 4.9 (P synthesis)."""
    runs = runs.copy() if runs is not None else pd.DataFrame()
    if "x" in runs:
        runs["x"] = runs["x"].apply(lambda v: list(json.loads(v)) if isinstance(v, str) else list(v) if v is not None else [])
    o = thesis_table("table_4_3_to_4_6_O_synthesis")
    out = [_o_table(runs, sp, o) for sp in O_TABLES]
    out.append(_e_table(runs, thesis_table("table_4_7_E_synthesis")))
    out.append(_p_table(runs, thesis_table("table_4_9_P_synthesis")))
    return out
