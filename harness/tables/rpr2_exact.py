"""Table 4.7x (suite ``rpr2-exact``): E synthesis (4.14) in exact smooth form, every solver from SP1-SP4.

One row per (start, solver): the end's f* (= dW_c when W_p is enclosed), its constraint
violation as the harness measured it, the local minimum of the exact problem it reached
(from the stored multistart, `rpr2_exact_suite.reference`), the end's exact dW_p and, for
comparison with Table 4.7, the thesis formulation's f and h (chord method, triangle scheme)
at the same design.  Flagged: an end that is not one of the exact problem's local minima.
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
    from manipulators.synthesis.rpr2_exact_suite import SOLVERS

    runs = _decoded(runs)
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
        order = {s: k for k, s in enumerate(SOLVERS)}
        runs = runs.assign(_o=[order.get(s, len(order)) for s in runs["solver"]]).sort_values(["start", "_o"])
        for _, r in runs.iterrows():
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
    return [Table(
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
               "Regenerate: python -m harness run --suite rpr2-exact."])]
