"""Tables of the ``spatial`` suite (docs/spatial.md, "Synthesis"): every run's end, checked
independently of the formulation, and each solver's result as the number of design
variables grows.

Checks (analysis, no optimization): a cable design's dextrous wrench-feasible volume on a
20^3 grid of the frame's box (every load and orientation; the grid counts every dextrous
cell, including any the rays from the centre miss); a hexapod's leg limits and
kappa^-1 on a 9^3 grid of the prescribed box at every orientation (the formulation
imposes them at 27 points).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pandas as pd

from ._base import Table, count_cell

__all__ = ["tables", "check_design", "GRID_CABLE", "GRID_GS"]

GRID_CABLE = 20
GRID_GS = 9


def _cable_check(x: np.ndarray) -> dict[str, Any]:
    from manipulators.synthesis.spatial_suite import CABLE, cable_design

    m = cable_design(x)
    if m is None:
        return {"check": "degenerate design", "grid": math.nan}
    frame = m.frame_points
    box = np.array([frame.min(axis=0), frame.max(axis=0)])
    wss = [m.dextrous_workspace(CABLE["orientations"], w, box, resolution=GRID_CABLE) for w in CABLE["loads"]]
    ws = wss[0]
    mask = np.logical_and.reduce([w.mask for w in wss])
    vol = float(mask.sum()) * ws.cell_volume
    return {"check": f"grid volume {vol:.3f} m^3", "grid": vol}


def _gs_check(x: np.ndarray) -> dict[str, Any]:
    from manipulators.synthesis.spatial_suite import GS, gs_design

    m = gs_design(x)
    if m is None:
        return {"check": "degenerate design", "grid": math.nan}
    zc = float(x[16] if x.size == 18 else x[7])
    g = np.linspace(-1.0, 1.0, GRID_GS)
    X, Y, Z = np.meshgrid(g, g, g, indexing="ij")
    P = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()]) * np.asarray(GS["half"]) + np.array([0.0, 0.0, zc])
    inside = all(bool(m.feasible(P, rot).all()) for rot in GS["orientations"])
    kinv = min(float(m.inverse_condition(P, rot).min()) for rot in GS["orientations"])
    return {"check": f"box {'enclosed' if inside else 'NOT enclosed'}, min kappa^-1 {kinv:.4f} on {GRID_GS}^3",
            "grid": kinv, "enclosed": inside}


def check_design(kind: str, x: Any) -> dict[str, Any]:
    """The independent check of a design of the ``kind`` ("cable" or "gs") synthesis."""
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        return {"check": "no design", "grid": math.nan}
    return _cable_check(x) if kind == "cable" else _gs_check(x)


def _value(kind: str, f: float) -> float:
    """The synthesis's own measure from f: V (m^3) for the cable robot, t = min kappa^-1 for GS."""
    return -float(f) if np.isfinite(f) else math.nan


def _runs_table(runs: pd.DataFrame) -> Table:
    rows, flags = [], []
    for _, sub in runs.groupby("case_id", sort=False):
        kind = "cable" if "cable" in str(sub["problem"].iloc[0]) else "gs"
        for _, r in sub.iterrows():
            chk = check_design(kind, r["x"]) if r["status"] not in ("timeout", "not_applicable") else {"check": ""}
            viol = float(r["max_violation"]) if r["max_violation"] is not None else math.nan
            rows.append({"problem": r["problem"], "n": int(r["n"]), "solver": r["solver"], "status": r["status"],
                         "N^fg": count_cell(r["nfg"]),
                         "V [m^3] / min kappa^-1": round(_value(kind, r["f"]), 4),
                         "max violation": float(f"{viol:.2g}") if np.isfinite(viol) else math.nan,
                         "independent check": chk["check"], "wall [s]": round(float(r["wall_time_s"]), 1)})
            flags.append({k: False for k in rows[-1]} | {
                "independent check": bool(chk.get("enclosed") is False),
                "max violation": bool(np.isfinite(viol) and viol > 1e-6)})
    frame = pd.DataFrame(rows)
    return Table("spatial_runs", "Spatial synthesis: every run's end, with an independent check", frame,
                 flags=pd.DataFrame(flags) if flags else None,
                 notes=["V: dextrous wrench-feasible volume by 32 rays from (0, 0, 1.5) (the objective); "
                        f"grid volume: the same set counted on a {GRID_CABLE}^3 grid of the frame's box, every load "
                        "and orientation. GS: t = worst kappa^-1 at the 27 box points (the objective); the check "
                        f"re-tests the leg limits and kappa^-1 on a {GRID_GS}^3 grid of the box at every orientation.",
                        "Flagged: a violation above 1e-6, or a box the legs do not reach on the finer grid.",
                        "Every solver ran with the suite's evaluation budget (manipulators/synthesis/"
                        "spatial_suite.py, _options); derivatives by counted forward differences."])


def _growth_table(runs: pd.DataFrame) -> Table:
    """Per solver, the result and N^fg of each formulation at each size."""
    cols: dict[str, dict[str, Any]] = {}
    for _, r in runs.iterrows():
        kind = "cable" if "cable" in str(r["problem"]) else "gs"
        key = f"{kind} n={int(r['n'])}"
        ok = r["status"] not in ("timeout", "error", "not_applicable") and float(r["max_violation"] or 0) <= 1e-6
        row = cols.setdefault(r["solver"], {"solver": r["solver"]})
        row[f"{key}: value"] = round(_value(kind, r["f"]), 4) if ok else "infeasible/failed"
        row[f"{key}: N^fg"] = count_cell(r["nfg"])
    frame = pd.DataFrame(list(cols.values()))
    return Table("spatial_growth", "Spatial synthesis: result and cost as the number of design variables grows",
                 frame, notes=["value: V [m^3] (cable, larger is better) or worst kappa^-1 (gs, larger is better) "
                               "at a feasible end (violation <= 1e-6)."])


def tables(runs: pd.DataFrame) -> list[Table]:
    from manipulators.synthesis.spatial_suite import SOLVERS

    runs = runs[runs["suite"] == "spatial"] if "suite" in runs else runs
    # rows in the suite's case and solver order, not in the order the runs finished
    order = {s: i for i, s in enumerate(SOLVERS)}
    runs = runs.assign(_c=runs["problem"].map({"spatial-cable-9": 0, "spatial-cable-13": 1, "spatial-gs-9": 2,
                                                "spatial-gs-18": 3}).fillna(9),
                       _s=runs["solver"].map(order).fillna(len(order)))
    runs = runs.sort_values(["_c", "_s", "solver"], kind="stable").drop(columns=["_c", "_s"])
    return [_runs_table(runs), _growth_table(runs)]
