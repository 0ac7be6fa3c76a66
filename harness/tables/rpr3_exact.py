"""Table 5.3x (suite ``rpr3-exact``): 3-RPR SO, MO and D synthesis in exact form, the rpr3 solvers from its starts.

One row per (synthesis, prescribed workspace, solver): the end's t* = min kappa^-1 it
certifies, its largest constraint violation (a leg-length excess on W_p's boundary or
t - kappa^-1) as the harness measured it, and which optimum of the exact model it reached:
the best design the stored multistart knows, or the local optimum SLSQP reaches from the
suite's start (`rpr3_exact.exact_optimum`, stored in reference.json).  Flagged: neither.
"""

from __future__ import annotations

import math
from typing import Any

import pandas as pd

from ._base import Table, column_flags, count_cell, run_end
from .rpr2 import _decoded, _fmt_d, _num, _status

__all__ = ["tables", "AT_OPTIMUM_REL", "FEAS_TOL"]

AT_OPTIMUM_REL = 1e-4  # |t* - t_ref| / (1 + |t_ref|): the constraints' Jacobian is by central differences
FEAS_TOL = 1e-6  # largest constraint violation of an end counted as feasible (solvers.solve's default)
NAMES = {"so": "SO (5.34)", "mo": "MO (5.37)", "d": "D (5.39)"}


def _reached(t: float, viol: float, opt: dict) -> tuple[str, bool]:
    """Which reference optimum t is at: 'best found', 'local min from d0', both, or none."""
    if not (math.isfinite(t) and math.isfinite(viol)):
        return "none", False
    if viol > FEAS_TOL:
        return "none (infeasible)", False
    hits = [name for name, key in (("best found", "kinv"), ("local min from d0", "local_kinv"))
            if opt.get(key) is not None and math.isfinite(float(opt[key]))
            and abs(t - float(opt[key])) <= AT_OPTIMUM_REL * (1.0 + abs(float(opt[key])))]
    return (" = ".join(hits), True) if hits else ("none", False)


def tables(runs: pd.DataFrame, reference: dict | None = None) -> list[Table]:
    from manipulators.synthesis.rpr3_exact import CASES
    from manipulators.synthesis.rpr3_suite import SOLVERS

    runs = _decoded(runs)
    optima = dict((reference or {}).get("exact_optimum") or {})
    rows: list[dict[str, Any]] = []
    flags: list[bool] = []
    order = {s: k for k, s in enumerate(SOLVERS)}
    for kind, pname in CASES:
        opt = optima.get(f"{kind}/{pname}") or {}
        for label, key, dkey in (("(exact-model optimum)", "kinv", "d"), ("(exact local min from d0)", "local_kinv",
                                                                          "local_d")):
            if opt.get(key) is not None:
                rows.append({"synthesis": NAMES[kind], "P": pname, "solver": label, "status": "", "N^fg": "",
                             "t* = min kappa^-1": _num(opt[key], ".4f"), "violation": "", "reached": "",
                             "d*": _fmt_d(opt.get(dkey) or []), "time_s": ""})
                flags.append(False)
        if runs.empty:
            continue
        ours = runs[(runs["problem"] == f"rpr3-{kind}-exact") & (runs["start"] == pname)]
        ours = ours.assign(_o=[order.get(s, len(order)) for s in ours["solver"]]).sort_values("_o")
        for _, r in ours.iterrows():
            x, f, viol = run_end(r)
            t = -f
            at, ok = _reached(t, viol, opt)
            rows.append({"synthesis": NAMES[kind], "P": pname, "solver": r["solver"], "status": _status(r),
                         "N^fg": count_cell(r["nfg"]), "t* = min kappa^-1": _num(t, ".4f"),
                         "violation": _num(viol, ".1e"), "reached": at, "d*": _fmt_d(x[:5]) if x.size else "",
                         "time_s": _num(r.get("wall_time_s"), ".3g")})
            flags.append(not ok and r["status"] != "not_applicable")
    frame = pd.DataFrame(rows)
    flag_frame = column_flags(frame, reached=flags)
    return [Table(
        name="table_5_3x",
        title="Table 5.3x: 3-RPR SO, MO and D synthesis in exact form (no chord method), from suite rpr3's starts, "
              "every solver at its defaults",
        frame=frame, flags=flag_frame,
        notes=["Problem (manipulators.synthesis.rpr3_exact_suite.exact_problem): max t over z = [x_C, y_C, x_D, x_E, "
               "r, t] subject to every leg length within its limits at 96 points of W_p's boundary on every slice "
               "(SO: phi = 0; MO: -5, 0, +5 degrees; D: 11 slices over [-5, +5]) and t <= kappa^-1 at those points "
               "on the kappa slices (5.39) - exactly W_p inside the required workspaces, no chord method, no "
               "triangle scheme; bound r >= 0.05 (a platform of size <= 0 is no design). Start: suite rpr3's "
               "design with t = min kappa^-1 there. Constraint Jacobian by central differences (step 1e-7).",
               "violation: the largest constraint violation at the end, measured by the harness's oracle. "
               "'reached': the end's t* within 1e-4 (1 + |t|) of the exact model's best design found "
               "(differential evolution and multistart SLSQP) or of its local optimum from the suite's start "
               "(rpr3_exact.exact_optimum, stored in reference.json; the '(exact ...)' rows); flagged when "
               "neither, or when the end is infeasible (violation > 1e-6).",
               "No thesis numbers: this formulation is ours (docs/rpr3.md, 'Exact form: suite rpr3-exact'). "
               "Regenerate: python -m harness run --suite rpr3-exact."])]
