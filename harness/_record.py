"""One stored run: the flat row written to runs.parquet for each (case, solver).

Columns (identity, settings, metrics, provenance):
suite, problem, n, start, variant, case_id, solver, settings (JSON), settings_hash,
nfg, nf, ng, nc, nj, nh, nit, f, f_ref, rel_error (E^r, eq. 2.34 / 3.12), inf_error
(||x* - x^c||_inf where x* is known), max_violation, success, status, message,
wall_time_s, time_in_evals_s, x (list of floats), history (JSON [[nfg, f, viol], ...]),
extra (JSON).
"""

from __future__ import annotations

import hashlib
import json
import math
from typing import Any

import numpy as np

from problems import Case
from solvers import Result

__all__ = ["relative_error", "result_to_row", "settings_hash", "ROW_COLUMNS"]

ROW_COLUMNS = [
    "suite", "problem", "n", "start", "variant", "case_id", "solver", "settings", "settings_hash",
    "nfg", "nf", "ng", "nc", "nj", "nh", "nit", "f", "f_ref", "rel_error", "inf_error",
    "max_violation", "success", "status", "message", "wall_time_s", "time_in_evals_s",
    "x", "history", "extra",
]


def relative_error(f_ref: float | None, f: float) -> float:
    """E^r = |f(x*) - f(x^c)| / (1 + |f(x*)|)  (thesis eq. 2.34, eq. 3.12)."""
    if f_ref is None or not math.isfinite(f_ref) or not math.isfinite(f):
        return float("nan")
    return abs(f_ref - f) / (1.0 + abs(f_ref))


def _jsonable(v: Any) -> Any:
    if isinstance(v, dict):
        return {str(k): _jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    if isinstance(v, np.ndarray):
        return _jsonable(v.tolist())
    if isinstance(v, (np.floating, float)):
        v = float(v)
        return v if math.isfinite(v) else str(v)
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (str, int, bool)) or v is None:
        return v
    return str(v)


def settings_hash(settings: dict[str, Any]) -> str:
    """Stable short hash of a settings dict (part of a run's key)."""
    blob = json.dumps(_jsonable(settings), sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:12]


def result_to_row(suite: str, case: Case, result: Result) -> dict[str, Any]:
    """Flatten a Result into one row of scalars and JSON strings (no pickles)."""
    p = case.problem
    x_ref = p.x_ref
    inf_err = float(np.max(np.abs(result.x - x_ref))) if x_ref is not None and result.x.size == p.n else float("nan")
    settings = _jsonable(result.options)
    return {
        "suite": suite,
        "problem": case.problem_id,
        "n": int(p.n),
        "start": case.start,
        "variant": case.variant,
        "case_id": case.case_id,
        "solver": result.solver,
        "settings": json.dumps(settings, sort_keys=True),
        "settings_hash": settings_hash(settings),
        "nfg": result.nfg, "nf": result.nf, "ng": result.ng, "nc": result.nc, "nj": result.nj, "nh": result.nh,
        "nit": result.nit,
        "f": result.f,
        "f_ref": float("nan") if p.f_ref is None else p.f_ref,
        "rel_error": relative_error(p.f_ref, result.f),
        "inf_error": inf_err,
        "max_violation": result.max_violation,
        "success": result.success,
        "status": result.status.value,
        "message": result.message,
        "wall_time_s": result.wall_time,
        "time_in_evals_s": result.time_in_evals,
        "x": [float(v) for v in result.x] if result.x.size <= 1000 else [],
        "history": json.dumps(_jsonable(result.history)),
        "extra": json.dumps(_jsonable(result.extra)),
    }
