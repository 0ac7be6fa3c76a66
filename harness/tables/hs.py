"""Table 3.1 of the thesis (Dynamic-Q vs SQP on Hock–Schittkowski problems), ours beside it.

Layout as in the thesis: problem number, n, f_act and, per method, N^fg, f*, E^r
(eq. 3.12: E^r = |f_act - f*| / (1 + |f_act|)). The thesis's SQP and Dynamic-Q columns
come first, then one column group per solver we ran. f_act is the best known optimum
of the vendored JSON (full precision; the thesis prints 3 digits).

Markers (thesis footnote), applied to our runs by these rules:

* solved (no marker): E^r <= 1e-5 against f_act AND max_violation <= 1e-6. The run's
  status is not consulted (an end at the optimum flagged ROUNDOFF_LIMITED is still a
  solution), but an infeasible end is never solved;
* ``*`` local minimum: not solved, feasible, and f* within E^r <= 1e-5 of a known
  secondary local minimum of that problem — a precise value from the JSON's
  ``other_published_values`` (if worse than f_act), or a value the thesis marked ``*``
  for that problem, matched to the thesis's printed 3 digits. E^r is then relative to
  that local minimum, as in the thesis;
* ``$`` the run ended on its iteration/evaluation cap (status ``max_iter``);
* ``~`` any other end (failure, error, infeasible, or a non-optimal point).

The summary table gives per solver: problems run, solved, local minima, failures,
caps, total and median N^fg (over all runs and over solved runs), and the same for the
thesis's columns judged by the same rule on its printed numbers.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pandas as pd

from problems.reference import thesis_table

from ._base import Table, count

__all__ = ["tables", "classify", "relative_error", "SOLVED_ER", "FEAS_TOL", "THESIS_STEM"]

THESIS_STEM = "table_3_1_dynamic_q_vs_sqp"
SOLVED_ER = 1e-5     # E^r at or below which a run counts as solved
FEAS_TOL = 1e-6      # largest constraint violation of a solved run
RATIO_NOTE = 2.0     # N^fg differing from the thesis by more than this factor is listed in the notes
THESIS_METHODS = {"sqp": "SQP (thesis)", "dynamic_q": "Dynamic-Q (thesis)"}
#: our solver -> the thesis column it is compared with for the "more than 2x" notes
COMPARE = {"dynamic-q": "dynamic_q", "scipy-slsqp": "sqp"}
SOLVER_ORDER = ("dynamic-q", "dynamic-q-plus", "lfopc", "etopc", "scipy-slsqp", "nlopt-slsqp", "scipy-trust-constr",
                "ipopt", "nlopt-mma", "scipy-cobyla")

# Known reasons for differences, by problem (cited in the notes when the problem is listed).
REASONS = {
    "hs002": "two minima: the global one (x1 > 0) and the local one f = 4.9412 (x1 < 0) "
    "that the thesis's Dynamic-Q found",
    "hs013": "degenerate (LICQ fails at x* = (1, 0)); a violation of 1e-12..1e-8 buys a lower f, so the count depends "
    "on how a method treats near-feasible points (the thesis's Dynamic-Q hit its step cap here)",
    "hs055": "rank-deficient equalities: SLSQP's least-squares subproblem is sensitive to rounding here, so its "
    "N^fg depends on the BLAS thread count (docs/hs.md); local minimum 20/3 at the other end of the feasible segment",
    "hs106": "badly scaled (x up to 1e4); the thesis's step limit for 106 is our reading rho = 100. The thesis's "
    "E^r = 1.18e-5 is against the HS book's 7049.33, which is not optimal (f_act here = 7049.248)",
    "hs072": "step limit rho = 100 by our reading of the garbled Sec. 3.4 sentence",
}


def relative_error(f_ref: float, f: float) -> float:
    """E^r = |f_ref - f| / (1 + |f_ref|)  (eq. 3.12)."""
    if not (math.isfinite(f_ref) and math.isfinite(f)):
        return math.nan
    return abs(f_ref - f) / (1.0 + abs(f_ref))


def _num(s: Any) -> float:
    try:
        return float(s)
    except (TypeError, ValueError):
        return math.nan


def _digits3(v: float) -> float:
    """One unit in the third significant digit of v (the thesis prints 3 digits)."""
    return 10.0 ** (math.floor(math.log10(abs(v))) - 2) if v != 0 else 1e-3


def _local_minima(pid: str, f_act: float, thesis: dict[str, dict[str, Any]]) -> list[tuple[float, bool]]:
    """Known secondary local minima of ``pid`` as (value, precise?) pairs."""
    out: list[tuple[float, bool]] = []
    try:
        from problems.hs._build import load_data

        entry = load_data().get(pid, {})
    except Exception:  # noqa: BLE001  (the table still renders without the JSON)
        entry = {}
    for other in entry.get("other_published_values", []):
        v = _num(other.get("value"))
        if math.isfinite(v) and relative_error(f_act, v) > SOLVED_ER and v > f_act:
            out.append((v, True))
    for row in thesis.values():
        if row.get("flag") == "*" and math.isfinite(row["f_star"]):
            out.append((row["f_star"], False))
    return out


def classify(f: float, f_act: float, max_violation: float, status: str,
             local_minima: list[tuple[float, bool]]) -> tuple[str, float]:
    """(marker, E^r) of one run by the rules of this module's docstring."""
    er = relative_error(f_act, f)
    feasible = math.isfinite(max_violation) and max_violation <= FEAS_TOL
    if feasible and er <= SOLVED_ER:
        return "", er
    if feasible and math.isfinite(f):
        precise = [v for v, p in local_minima if p and relative_error(v, f) <= SOLVED_ER]
        printed = [v for v, p in local_minima if not p and abs(f - v) <= _digits3(v)]
        if precise:  # E^r relative to the local minimum, as the thesis does
            return "*", relative_error(precise[0], f)
        if printed:  # only the thesis's 3 digits are known: E^r against them (see notes)
            return "*", relative_error(printed[0], f)
    if status == "max_iter":
        return "$", er
    return "~", er


def _thesis_rows() -> dict[str, dict[str, dict[str, Any]]]:
    out: dict[str, dict[str, dict[str, Any]]] = {}
    for r in thesis_table(THESIS_STEM).to_dict("records"):
        pid = f"hs{int(r['problem']):03d}" if r["problem"].isdigit() else "svanberg"
        out.setdefault(pid, {})[r["method"]] = {
            "n": int(r["n"]), "f_act": _num(r["f_act"]), "nfg": _num(r["nfg"]), "f_star": _num(r["f_star"]),
            "er": _num(r["er"]), "lt": r["er_is_upper_bound"] == "true", "flag": r["flag"],
        }
    return out


def _fmt(v: float, spec: str = ".3e") -> str:
    return "" if not math.isfinite(v) else format(v, spec)


def _latest(runs: pd.DataFrame) -> pd.DataFrame:
    """One run per (problem, solver): the last stored."""
    if runs.empty:
        return runs
    return runs.drop_duplicates(subset=["problem", "solver"], keep="last")


def _solver_order(solvers: list[str]) -> list[str]:
    known = [s for s in SOLVER_ORDER if s in solvers]
    return known + sorted(s for s in solvers if s not in SOLVER_ORDER)


def tables(runs: pd.DataFrame) -> list[Table]:
    """Table 3.1 (ours beside the thesis's) and its per-solver summary."""
    thesis = _thesis_rows()
    runs = _latest(runs[runs["suite"] == "hs"] if "suite" in runs and not runs.empty else runs)
    solvers = _solver_order(sorted(runs["solver"].unique())) if not runs.empty else []
    pids = sorted(set(runs["problem"]) if not runs.empty else set(), key=lambda p: int(p[2:]))
    if not pids:
        pids = [p for p in thesis if p != "svanberg"]
    by_key = {(r["problem"], r["solver"]): r for r in runs.to_dict("records")} if not runs.empty else {}

    rows, flags = [], []
    per_solver: dict[str, list[dict[str, Any]]] = {s: [] for s in solvers}
    ratio_notes: list[str] = []
    for pid in pids:
        th = thesis.get(pid, {})
        any_run = next((by_key[(pid, s)] for s in solvers if (pid, s) in by_key), None)
        f_act = _num(any_run["f_ref"]) if any_run is not None else th.get("sqp", {}).get("f_act", math.nan)
        n = int(any_run["n"]) if any_run is not None else th.get("sqp", {}).get("n", 0)
        row: dict[str, Any] = {"Prob. #": int(pid[2:]), "n": n, "f_act": _fmt(f_act, ".6g")}
        flag: dict[str, bool] = {k: False for k in row}
        for m, label in THESIS_METHODS.items():
            t = th.get(m)
            if t is None:
                row.update({f"{label} N^fg": "", f"{label} f*": "", f"{label} E^r": ""})
            else:
                nfg_th = "" if not math.isfinite(t["nfg"]) else f"{int(t['nfg'])}"
                row[f"{label} N^fg"] = nfg_th + t["flag"]
                row[f"{label} f*"] = _fmt(t["f_star"], ".3g") if math.isfinite(t["f_star"]) else t["flag"]
                row[f"{label} E^r"] = ("<" if t["lt"] else "") + _fmt(t["er"], ".2e")
            flag.update({f"{label} N^fg": False, f"{label} f*": False, f"{label} E^r": False})
        minima = _local_minima(pid, f_act, th)
        for s in solvers:
            r = by_key.get((pid, s))
            if r is None:
                row.update({f"{s} N^fg": "", f"{s} f*": "", f"{s} E^r": ""})
                flag.update({f"{s} N^fg": False, f"{s} f*": False, f"{s} E^r": False})
                continue
            if str(r["status"]) == "not_applicable":  # the solver cannot take this problem: no run, no failure
                row.update({f"{s} N^fg": "n/a", f"{s} f*": "", f"{s} E^r": ""})
                flag.update({f"{s} N^fg": False, f"{s} f*": False, f"{s} E^r": False})
                continue
            mark, er = classify(_num(r["f"]), f_act, _num(r["max_violation"]), str(r["status"]), minima)
            nfg = count(r["nfg"])  # None: error or time-out, a failure without counts
            per_solver[s].append({"pid": pid, "nfg": nfg, "mark": mark})
            row[f"{s} N^fg"] = f"{r['status'] if nfg is None else nfg}{mark}"
            row[f"{s} f*"] = _fmt(_num(r["f"]), ".6g")
            row[f"{s} E^r"] = _fmt(er, ".2e")
            differs = False
            ref_m = COMPARE.get(s)
            t = th.get(ref_m) if ref_m else None
            if nfg is not None and t is not None and math.isfinite(t["nfg"]) and t["nfg"] > 0:
                ratio = nfg / t["nfg"]
                if ratio > RATIO_NOTE or ratio < 1 / RATIO_NOTE:
                    differs = True
                    why = REASONS.get(pid, "")
                    outcome = (
                        f" (ours '{mark or 'solved'}', thesis '{t['flag'] or 'solved'}')" if mark != t["flag"] else ""
                    )
                    ratio_notes.append(f"HS{int(pid[2:])}, {s} vs {THESIS_METHODS[str(ref_m)]}: N^fg {nfg} vs "
                                       f"{int(t['nfg'])} ({ratio:.2f}x){outcome}" + (f" - {why}" if why else ""))
            flag.update({f"{s} N^fg": differs, f"{s} f*": False, f"{s} E^r": mark not in ("", "*")})
        rows.append(row)
        flags.append(flag)

    frame = pd.DataFrame(rows)
    flag_frame = pd.DataFrame(flags, columns=frame.columns).fillna(False).astype(bool)
    notes = [
        f"Solved: E^r <= {SOLVED_ER:g} against f_act (eq. 3.12) and max constraint violation <= {FEAS_TOL:g}; "
        "an infeasible end is never solved. Markers: * local minimum (E^r relative to it), ~ failure, "
        "$ iteration/evaluation cap; n/a: the solver cannot take the problem's constraints (left out of the "
        "summary's counts); the same rules are applied to the thesis's printed numbers in the summary. "
        "Where a local minimum is known only from the thesis's 3 printed digits (HS15: 360, HS108: -0.697), a '*' "
        "run's E^r is against those digits.",
        "f_act: best known optimum (problems/hs/hock_schittkowski.json; the thesis prints 3 digits). The thesis's SQP "
        "columns are Powell's SQP as reported by Hock & Schittkowski, not rerun.",
        "Svanberg's 12-corner polytope problem (thesis row 'Svan', n = 21, f_act = 2.80E+02) is not reproduced: its "
        "definition could not be found in any available source (problems/hs/hock_schittkowski.md).",
        "Dynamic-Q settings (Sec. 3.4): rho = 1, eps_f = 1e-8, eps_x = 1e-5, eps_c = 1e-6; rho = 100 for problems 72 "
        "and 106 (our reading of a garbled sentence; thesis_tables/README.md).",
        f"Flagged N^fg cells differ from the thesis's column for the same kind of method by more than {RATIO_NOTE:g}x "
        "(dynamic-q vs Dynamic-Q, scipy-slsqp vs SQP); flagged E^r cells are failures (~, $).",
    ]
    if ratio_notes:
        notes.append(f"Problems whose N^fg differs from the thesis by more than {RATIO_NOTE:g}x:")
        notes.extend("  " + s for s in ratio_notes)
    main = Table(name="table_3_1", title="Table 3.1: Dynamic-Q, SQP and established solvers on Hock-Schittkowski "
                 "problems (thesis columns beside ours)", frame=frame, flags=flag_frame, notes=notes)
    return [main, _summary(per_solver, thesis, pids)]


def _stats(items: list[dict[str, Any]]) -> dict[str, Any]:
    nfg_all = [i["nfg"] for i in items if i["nfg"] is not None and math.isfinite(i["nfg"])]
    nfg_ok = [i["nfg"] for i in items if i["mark"] == "" and i["nfg"] is not None and math.isfinite(i["nfg"])]
    return {
        "problems": len(items),
        "solved": sum(i["mark"] == "" for i in items),
        "local min (*)": sum(i["mark"] == "*" for i in items),
        "failed (~)": sum(i["mark"] == "~" for i in items),
        "cap ($)": sum(i["mark"] == "$" for i in items),
        "total N^fg": int(sum(nfg_all)) if nfg_all else 0,
        "median N^fg": float(np.median(nfg_all)) if nfg_all else math.nan,
        "total N^fg (solved)": int(sum(nfg_ok)) if nfg_ok else 0,
        "median N^fg (solved)": float(np.median(nfg_ok)) if nfg_ok else math.nan,
    }


def _thesis_mark(t: dict[str, Any]) -> str:
    if t["flag"]:
        return t["flag"]
    return "" if math.isfinite(t["er"]) and t["er"] <= SOLVED_ER else "~"


def _summary(per_solver: dict[str, list[dict[str, Any]]], thesis: dict[str, dict[str, dict[str, Any]]],
             pids: list[str]) -> Table:
    rows = []
    for m, label in THESIS_METHODS.items():
        items = [{"pid": p, "nfg": thesis[p][m]["nfg"], "mark": _thesis_mark(thesis[p][m])}
                 for p in pids if p in thesis and m in thesis[p]]
        rows.append({"solver": label, **_stats(items)})
    for s, items in per_solver.items():
        rows.append({"solver": s, **_stats(items)})
    frame = pd.DataFrame(rows)
    notes = [f"Same rules as Table 3.1 (solved: E^r <= {SOLVED_ER:g} vs f_act and violation <= {FEAS_TOL:g}). "
             "The thesis's rows apply the rule to its printed E^r (its HS106 E^r = 1.18e-5 is measured against the "
             "HS book's non-optimal 7049.33, so it does not count as solved here)."]
    dq = {i["pid"]: i for i in per_solver.get("dynamic-q", [])}
    both = [p for p in pids if p in dq and dq[p]["mark"] == "" and p in thesis
            and "dynamic_q" in thesis[p] and _thesis_mark(thesis[p]["dynamic_q"]) == ""]
    if both:
        ours = sum(dq[p]["nfg"] for p in both)
        theirs = sum(thesis[p]["dynamic_q"]["nfg"] for p in both)
        notes.append(f"dynamic-q vs the thesis's Dynamic-Q over the {len(both)} problems both solved: total N^fg "
                     f"{ours} vs {int(theirs)} (ratio {ours / theirs:.2f}; acceptance 0.5-2).")
    return Table(name="table_3_1_summary", title="Table 3.1 summary: problems solved and N^fg per solver",
                 frame=frame, notes=notes)
