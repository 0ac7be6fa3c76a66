"""Tables 4.7x and 4.9x (suite ``rpr2-exact``): E synthesis (4.14) and P synthesis (4.21) in exact
smooth form, every constrained solver at its defaults.

Table 4.7x, one row per (start, solver): the end's f* (= dW_c when W_p is enclosed), its
constraint violation as the harness measured it, the local minimum of the exact problem it
reached (from the stored multistart, `rpr2_exact_suite.reference`), the end's exact dW_p and,
for comparison with Table 4.7, the thesis formulation's f and h (chord method, triangle
scheme) at the same design.  Flagged: an end that is not one of the exact problem's local
minima.

Table 4.9x, one row per (P, solver): t* = min kappa^-1 at the end, its violation, whether it
is the exact problem's best design (stored multistart), the area of P outside the exact
workspace and, for comparison with Table 4.9, the chord formulation's g (4.16) at the same
design.  Flagged: an end that is not at the exact optimum.
"""

from __future__ import annotations

import math
from typing import Any

import pandas as pd

from ._base import Table, column_flags, count_cell, run_end
from .rpr2 import _decoded, _evaluate, _fmt_d, _num, _status

__all__ = ["tables", "AT_MINIMUM_REL", "FEAS_TOL"]

AT_MINIMUM_REL = 1e-5  # |f* - f_min| / (1 + |f_min|): the success rule of the hs and CUTEst tables
FEAS_TOL = 1e-6  # largest constraint violation of an end counted as enclosing (solvers.solve's default)


def _minimum_of(f: float, viol: float, minima: list[float]) -> tuple[str, bool]:
    """Which local minimum f is at ('3.1436', or 'none'), and whether it is one."""
    if not (math.isfinite(f) and math.isfinite(viol)) or viol > FEAS_TOL:
        return "none (infeasible)" if math.isfinite(viol) and viol > FEAS_TOL else "none", False
    for f_m in minima:
        if abs(f - f_m) <= AT_MINIMUM_REL * (1.0 + abs(f_m)):
            return f"{f_m:.4f}", True
    return "none", False


def tables(runs: pd.DataFrame, reference: dict | None = None) -> list[Table]:
    runs = _decoded(runs)
    if "problem" in runs:
        e = runs[runs["problem"] == "rpr2-e-exact"]
        p = runs[runs["problem"].astype(str).str.match(r"rpr2-p\d-exact$")]
    else:  # rows without a problem column are E rows (the suite had only those until Table 4.9x)
        e, p = runs, runs.iloc[0:0]
    return [_e_table(e, reference), _p_table(p, reference)]


def _order(runs: pd.DataFrame, by: str) -> pd.DataFrame:
    from manipulators.synthesis.rpr2_exact_suite import SOLVERS

    order = {s: k for k, s in enumerate(SOLVERS)}
    return runs.assign(_o=[order.get(s, len(order)) for s in runs["solver"]]).sort_values([by, "_o"])


def _e_table(runs: pd.DataFrame, reference: dict | None) -> Table:
    opt = (reference or {}).get("exact_optimum") or {"minima": [], "starts": 0}
    minima = [float(m[0]) for m in opt.get("minima", [])]
    rows: list[dict[str, Any]] = []
    flags: list[bool] = []
    for i, (f_m, d_m, c) in enumerate(opt.get("minima", [])):
        ev = _evaluate("e", d_m)
        rows.append({"start": "all", "solver": "(exact-model optimum)" if i == 0 else "(exact-model local min)",
                     "status": f"{c} of {opt.get('starts', 0)} starts", "N^fg": "", "f*": _num(f_m, ".6g"),
                     "violation": "", "local minimum": f"{float(f_m):.4f}",
                     "dW_p exact": _num(ev.get("dwp_exact"), ".2g"), "chord f": _num(ev.get("f"), ".4f"),
                     "chord h": _num(ev.get("h"), ".2g"), "d*": _fmt_d(d_m), "time_s": ""})
        flags.append(False)
    if not runs.empty:
        for _, r in _order(runs, "start").iterrows():
            x, f, viol = run_end(r)
            ev = _evaluate("e", x) if x.size == 5 else {}
            at, ok = _minimum_of(f, viol, minima)
            rows.append({"start": r["start"], "solver": r["solver"], "status": _status(r),
                         "N^fg": count_cell(r["nfg"]), "f*": _num(f, ".6g"), "violation": _num(viol, ".1e"),
                         "local minimum": at, "dW_p exact": _num(ev.get("dwp_exact"), ".2g"),
                         "chord f": _num(ev.get("f"), ".4f"), "chord h": _num(ev.get("h"), ".2g"),
                         "d*": _fmt_d(x) if x.size else "", "time_s": _num(r.get("wall_time_s"), ".3g")})
            flags.append(not ok and r["status"] != "not_applicable")
    frame = pd.DataFrame(rows)
    flag_frame = column_flags(frame, **{"local minimum": flags})
    return Table(
        name="table_4_7x",
        title="Table 4.7x: E synthesis (4.14) in exact smooth form from SP1-SP4, every constrained solver at its "
              "defaults",
        frame=frame, flags=flag_frame,
        notes=["Problem (manipulators.synthesis.rpr2_exact_suite.e_exact_problem): min area(W_c) - area(W_p) "
               "subject to every leg length on W_p's boundary (512 points) within [l_min, 1.5 l_min] and W_p above "
               "the base line - exactly W_p inside W_c, with analytic derivatives; no chord method, no finite "
               "differences. Table 4.7 poses the same synthesis with the equality h = dW_p = 0 on chord workspaces: "
               "a constraint that is zero on the whole enclosing region, so its gradient vanishes where it holds.",
               "f* = area(W_c) - area(W_p) at the end (= dW_c when W_p is enclosed); violation = the largest "
               "constraint violation, measured by the harness's oracle; 'local minimum' = the exact problem's local "
               f"minimum the end is at (|f* - f_min| <= {AT_MINIMUM_REL:g} (1 + |f_min|), violation <= "
               f"{FEAS_TOL:g}), from the stored multistart (rpr2_exact.exact_optimum: SLSQP from SP1-SP4, the "
               "thesis's d* and 24 seeded designs; the '(exact-model ...)' rows); flagged when none.",
               "'dW_p exact': area of W_p outside the exact workspace (shapely); 'chord f', 'chord h': Table 4.7's "
               "dW_c and dW_p (chord 0.1, triangle scheme) at the same design, for comparison with that table.",
               "No thesis numbers: this formulation is ours (docs/manipulators.md, 'E synthesis in exact form'). "
               "Regenerate: python -m harness run --suite rpr2-exact."])


def _prescribed_of(problem: str) -> str:
    return f"P{problem.split('-')[1][1:]}"  # rpr2-p1-exact -> P1


def _p_table(runs: pd.DataFrame, reference: dict | None) -> Table:
    best = (reference or {}).get("exact_p_optimum") or {}
    rows: list[dict[str, Any]] = []
    flags: list[bool] = []
    for P in ("P1", "P2", "P3"):
        opt = best.get(P) or {}
        if opt.get("d") is not None:
            ev = _evaluate("p", opt["d"], P)
            reached_by = (opt.get("minima") or [[None, None, 0]])[0][2]
            rows.append({"P": P, "solver": "(exact-model optimum)", "status": f"{reached_by} of "
                         f"{opt.get('starts', 0)} starts", "N^fg": "", "t*": _num(opt["f"], ".6f"),
                         "violation": "", "reached": "", "outside P (exact)": _num(ev.get("dwp_exact"), ".2g"),
                         "chord g": _num(ev.get("g"), ".2g"), "d*": _fmt_d(opt["d"]), "time_s": ""})
            flags.append(False)
        sub = runs[runs["problem"].map(_prescribed_of) == P] if not runs.empty else runs
        for _, r in (_order(sub, "start").iterrows() if not sub.empty else ()):
            x, f, viol = run_end(r)
            t = -f  # the problem minimizes -t
            ev = _evaluate("p", x[:3], P) if x.size == 4 else {}
            label, at = _minimum_of(t, viol, [float(opt["f"])] if "f" in opt else [])
            reached = "exact optimum" if at else label
            rows.append({"P": P, "solver": r["solver"], "status": _status(r), "N^fg": count_cell(r["nfg"]),
                         "t*": _num(t, ".6f"), "violation": _num(viol, ".1e"), "reached": reached,
                         "outside P (exact)": _num(ev.get("dwp_exact"), ".2g"), "chord g": _num(ev.get("g"), ".2g"),
                         "d*": _fmt_d(x[:3]) if x.size else "", "time_s": _num(r.get("wall_time_s"), ".3g")})
            flags.append(not at and r["status"] != "not_applicable")
    frame = pd.DataFrame(rows)
    flag_frame = column_flags(frame, reached=flags) if rows else None
    return Table(
        name="table_4_9x",
        title="Table 4.9x: P synthesis (4.21) in exact smooth form for P1-P3, every constrained solver at its defaults",
        frame=frame, flags=flag_frame,
        notes=["Problem (manipulators.synthesis.rpr2_exact_suite.p_exact_problem): max t over z = [xA, yA, xB, t] "
               "subject to kappa^-1 >= t at the 2048 boundary points over which suite rpr2 takes its P objective "
               "(eq. 4.23), every leg length on P's boundary (512 points) within [4, 7] and P above the base line - "
               "exactly P inside the workspace, with analytic derivatives; started at Section 4.7.3's d0 with t = "
               "min kappa^-1 there. Table 4.9 poses the same synthesis with g (4.16) on chord workspaces (chord "
               "0.1), which lets slivers of P fall outside the exact workspace at an end on g = 0.",
               "t* = min kappa^-1 at the end (maximized); violation = the largest constraint violation, measured by "
               "the harness's oracle; 'reached': the exact problem's best design (|t* - t_opt| <= "
               f"{AT_MINIMUM_REL:g} (1 + |t_opt|), violation <= {FEAS_TOL:g}), from the stored multistart "
               "(rpr2_exact.exact_optimum('p'): SLSQP from d0 and 24 seeded designs; the '(exact-model optimum)' "
               "rows); flagged when not.",
               "'outside P (exact)': area of P outside the exact workspace (shapely); 'chord g': Table 4.9's "
               "constraint (4.16) at the same design, for comparison with that table.",
               "No thesis numbers: this formulation is ours (docs/manipulators.md, 'P synthesis in exact form'). "
               "Regenerate: python -m harness run --suite rpr2-exact."])
