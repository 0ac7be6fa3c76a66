"""Best-known points of a campaign: the lowest feasible end any run has reached, kept.

A campaign case without a known optimum (most of ``cutest``) is judged against the best
feasible f that any run reached, as in Moré & Wild's data profiles.  Computed from the
stored runs alone, that reference moves whenever a re-run ends higher: a multistart search
cut by the wall-clock limit finds a low minimum in one campaign and not in the next, and
every other solver's count on that case flips with it (docs/multistart.md).  So the
reference of ``cutest`` and ``hs-all`` is a *stored* one (`harness._reference`): for every
case, the lowest feasible end of any run judged within the campaign's common time limit,
with its point, solver and date.  It only ever goes down, and only to a point a run
reached; ``python -m harness reference --suite S --verify`` re-evaluates every stored point
through the problem's own functions, and ``--fresh`` rebuilds it from the stored runs.

Feasible and within the limit mean what the campaign tables mean (`FEAS_TOL`, the common
wall-clock limit of `harness.tables._campaign`), so a run the tables would not let set the
reference never sets it here.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import pandas as pd

__all__ = ["PERSISTENT", "reference", "best_known_values", "verify"]

#: the stored entries outlive changes of this module's code (they are points, not analyses)
PERSISTENT = True

_KEY = "best_known"
_KEEP = ("solver", "settings", "code_version", "finished_at", "run_key")


def _entry(row: pd.Series) -> dict[str, Any]:
    x = row.get("x")
    point = [float(v) for v in x] if x is not None and len(x) else None
    out: dict[str, Any] = {"f": float(row["f"]), "max_violation": float(row["max_violation"]), "x": point}
    out.update({k: (None if pd.isna(row.get(k)) else str(row.get(k))) for k in _KEEP if k in row.index})
    return out


def reference(runs: pd.DataFrame | None, stored: dict[str, Any] | None = None) -> dict[str, Any]:
    """The stored best-known points, lowered by any run of ``runs`` that ends lower.

    A run counts when the campaign tables would let it set a reference: its end is
    feasible (violation <= `FEAS_TOL`), finite, and it finished within the campaign's
    common wall-clock limit.  A tie keeps the stored entry, so re-running changes nothing.
    """
    from .tables._campaign import FEAS_TOL, common_limit, judged_under

    known: dict[str, Any] = dict((stored or {}).get(_KEY) or {})
    if runs is None or runs.empty:
        return {_KEY: known}
    df = judged_under(runs, common_limit(runs))
    f = pd.to_numeric(df["f"], errors="coerce")
    viol = pd.to_numeric(df["max_violation"], errors="coerce")
    ok = df[(viol <= FEAS_TOL) & np.isfinite(f) & (df["status"] != "timeout")]
    if ok.empty:
        return {_KEY: known}
    lowest = ok.loc[pd.to_numeric(ok["f"]).groupby(ok["case_id"]).idxmin()]
    for _, row in lowest.sort_values("case_id").iterrows():
        case = str(row["case_id"])
        old = known.get(case)
        if old is None or float(row["f"]) < float(old["f"]):
            known[case] = _entry(row)
    return {_KEY: dict(sorted(known.items()))}


def best_known_values(stored: dict[str, Any] | None) -> dict[str, float]:
    """case_id -> best-known f, from a stored reference ({} when there is none)."""
    entries = (stored or {}).get(_KEY) or {}
    return {case: float(e["f"]) for case, e in entries.items() if math.isfinite(float(e.get("f", math.nan)))}


def verify(suite: Any, stored: dict[str, Any], cases: list[str] | None = None, f_rtol: float = 1e-9,
           ) -> pd.DataFrame:
    """Re-evaluate stored best-known points through the problems' own functions.

    Returns one row per checked case: stored f, f and violation at the stored x, and
    ``ok`` (the point is feasible within `FEAS_TOL` and f agrees within ``f_rtol`` relative
    to max(1, |f|)).  ``suite``: a `problems.Suite`; ``cases``: a subset of case ids.
    """
    from .tables._campaign import FEAS_TOL

    entries = (stored or {}).get(_KEY) or {}
    rows = []
    for case in sorted(entries if cases is None else cases):
        e = entries.get(case)
        if e is None:
            rows.append({"case_id": case, "f_stored": math.nan, "f": math.nan, "max_violation": math.nan,
                         "ok": False, "why": "no stored entry"})
            continue
        why, f, v = "", math.nan, math.nan
        try:
            problem = suite.case(case).problem
            x = np.asarray(e.get("x") or [], dtype=float)
            if x.size != problem.n:
                why = f"stored point has {x.size} entries, the problem has n = {problem.n}"
            else:
                with warnings.catch_warnings(), np.errstate(all="ignore"):  # S2MPJ's own overflow warnings
                    warnings.simplefilter("ignore")
                    f, v = float(problem.objective(x)), float(problem.max_violation(x))
        except Exception as exc:  # noqa: BLE001 - a case that cannot be rebuilt is reported, not fatal
            why = f"{type(exc).__name__}: {exc}"
        fs = float(e["f"])
        if not why and not abs(f - fs) <= f_rtol * max(1.0, abs(fs)):
            why = f"f at the stored point is {f!r}, stored {fs!r}"
        if not why and not v <= FEAS_TOL:
            why = f"violation at the stored point is {v:.3g} > {FEAS_TOL:g}"
        rows.append({"case_id": case, "f_stored": fs, "f": f, "max_violation": v, "ok": not why, "why": why})
    return pd.DataFrame(rows, columns=["case_id", "f_stored", "f", "max_violation", "ok", "why"])
