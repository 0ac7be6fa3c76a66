"""Tables 5.4s and 5.5s (suite ``rpr3-spread``): how far the 3-RPR MO and D ends move when the start moves by 1e-6.

One row per (prescribed workspace, solver): the ends of the runs from d0 and from its
perturbed copies (`manipulators.synthesis.rpr3_spread_suite`), each checked in exact
geometry (`rpr3_suite.exact_enclosure`), beside the exact model's optima stored for the
suite (`rpr3_exact.reference`): the best design found and the local optimum from d0.
Diagnostic only: nothing is flagged.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ._base import Table, count
from .rpr2 import _decoded, _num, _span
from .rpr2_spread import _solver_order
from .rpr3 import F_TOL, KINDS

__all__ = ["tables", "spread_table"]


def _enclosed(kind: str, x: np.ndarray, prescribed: str) -> bool:
    from manipulators.synthesis.rpr3_suite import exact_enclosure

    if x.shape != (5,) or not np.all(np.isfinite(x)):
        return False
    try:
        return bool(exact_enclosure(kind, x, prescribed).get("enclosed", False))
    except Exception:  # noqa: BLE001  (a broken row must not break the table)
        return False


def spread_table(runs: pd.DataFrame, kind: str, optima: dict) -> Table:
    """Table 5.4s / 5.5s: every solver's ends from d0 and its perturbed copies, per W_p."""
    from manipulators.synthesis._spread import parse_start
    from manipulators.synthesis.rpr3_spread_suite import EPS, PRESCRIBED

    num, title = KINDS[kind]
    rows = []
    for pname in PRESCRIBED:
        pid = f"rpr3-{kind}-{pname.lower()}"
        sub = runs[runs["problem"] == pid] if len(runs) else runs
        opt = dict(optima.get(f"{kind}/{pname}") or {})
        best, local = float(opt.get("kinv", math.nan)), float(opt.get("local_kinv", math.nan))
        for solver in sorted(sub["solver"].unique(), key=_solver_order) if len(sub) else []:
            g = sub[sub["solver"] == solver]
            kinv = np.array([-float(v) if v is not None else math.nan for v in g["f"]])
            enc = [_enclosed(kind, np.asarray(x, dtype=float), pname) for x in g["x"]]
            good = [e and math.isfinite(k) for e, k in zip(enc, kinv)]
            nominal = [parse_start(s)[1] == 0 for s in g["start"]]
            k_nom = kinv[nominal][0] if any(nominal) else math.nan
            fin = kinv[np.isfinite(kinv)]
            st = g["status"].astype(str).value_counts()
            rows.append({
                "W_p": pname, "solver": solver, "runs": len(g),
                "f* from d0": _num(k_nom, ".4f"),
                "f* min": _num(fin.min() if fin.size else math.nan, ".4f"),
                "f* median": _num(np.median(fin) if fin.size else math.nan, ".4f"),
                "f* max": _num(fin.max() if fin.size else math.nan, ".4f"),
                "enclosed": f"{sum(enc)} of {len(g)}",
                "f* of the enclosed ends": _span([float(k) for k, gd in zip(kinv, good) if gd], ".4f"),
                "enclosed, f* >= exact local min - 0.01": (
                    f"{sum(gd and k >= local - F_TOL for gd, k in zip(good, kinv))} of {len(g)}"
                    if math.isfinite(local) else ""),
                "enclosed, f* >= exact best - 0.01": (
                    f"{sum(gd and k >= best - F_TOL for gd, k in zip(good, kinv))} of {len(g)}"
                    if math.isfinite(best) else ""),
                "exact local min from d0": _num(local, ".4f"),
                "exact best": _num(best, ".4f"),
                "N^fg": _span([float(c) for c in map(count, g["nfg"]) if c is not None], ".0f"),
                "status": ", ".join(f"{k} {v}" for k, v in st.items()),
            })
    return Table(
        name=f"table_{num.replace('.', '_')}s",
        title=f"Table {num}s: {title}; ends from d0 and from starts within {EPS:g} of it",
        frame=pd.DataFrame(rows), flags=None,
        notes=[f"Each row: one solver with suite rpr3's settings (Table {num}) from d0 and from starts that differ "
               f"from it by at most {EPS:g} in every component (seeded uniform; "
               "manipulators.synthesis.rpr3_spread_suite). f* = min kappa^-1 over the prescribed boundary at the "
               "end (the thesis's f, dense and exact).",
               "enclosed: W_p inside the exact workspace(s) at the end (rpr3_suite.exact_enclosure: uncovered area "
               "<= 1e-3 of W_p, the chord sagitta level; D: 201 slices).",
               f"'exact local min from d0' / 'exact best': the exact model's local optimum from d0 and the best "
               "design found (differential evolution and multistart SLSQP; rpr3_exact.exact_optimum, stored in "
               f"reference.json). The two count columns: enclosed ends within {F_TOL} of them or above.",
               "A row whose ends scatter far beyond 0.01 under such changes is a cell no single run can judge: "
               "its spread is the measure. Regenerate: python -m harness run --suite rpr3-spread (about 35 "
               "minutes on 2 cores)."])


def tables(runs: pd.DataFrame, reference: dict | None = None) -> list[Table]:
    """Tables 5.4s and 5.5s; ``reference``: the stored exact-model optima
    (`manipulators.synthesis.rpr3_exact.reference`, ``results/rpr3-spread/reference.json``)."""
    from manipulators.synthesis.rpr3_spread_suite import KINDS as SPREAD_KINDS

    runs = _decoded(runs)
    if "suite" in runs:
        runs = runs[runs["suite"] == "rpr3-spread"]
    optima = dict((reference or {}).get("exact_optimum") or {})
    return [spread_table(runs, kind, optima) for kind in SPREAD_KINDS]
