"""What a worker does for one run: rebuild the case, solve, flatten to a row.

Nothing here raises: an exception anywhere (building the problem, the solver, the
row) becomes a row with status ``error`` and the message, so a suite always goes on
(docs/harness.md, "Fault isolation").  Rows for runs that never produced a result (time-outs, dead
workers, not-applicable pairs) are built from the `RunSpec` alone by `spec_row`.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import traceback
from typing import Any

from problems import Case
from solvers import NotApplicable, solve

from ._plan import RunSpec
from ._record import ROW_COLUMNS, result_to_row
from ._suites import import_modules, load_suite

__all__ = ["execute", "spec_row", "EXTRA_COLUMNS", "COUNT_COLUMNS"]

#: columns the harness adds to `harness._record.ROW_COLUMNS`
EXTRA_COLUMNS = ["overrides", "run_key", "code_version", "finished_at"]
COUNT_COLUMNS = ["nfg", "nf", "ng", "nc", "nj", "nh", "nit"]
NOT_APPLICABLE = "not_applicable"

_IMPORTED: set[tuple[str, ...]] = set()


def _now() -> str:
    return _dt.datetime.now(_dt.UTC).isoformat(timespec="microseconds")


def compact_history(history_json: str) -> str:
    """Re-serialise the history [[nfg, f, viol], ...] without spaces, nfg as integers."""
    rows = json.loads(history_json)
    out = [[int(r[0]) if isinstance(r[0], float) and r[0].is_integer() else r[0], *r[1:]] for r in rows]
    return json.dumps(out, separators=(",", ":"))


def spec_row(spec: RunSpec, status: str, message: str, wall_time: float = float("nan")) -> dict[str, Any]:
    """A row for a run without a solver result (counts unknown: stored as null)."""
    nan = float("nan")
    row: dict[str, Any] = {c: None for c in ROW_COLUMNS}
    row.update(
        suite=spec.suite_ref.name, problem=spec.problem, n=spec.n, start=spec.start, variant=spec.variant,
        case_id=spec.case_id, solver=spec.solver, settings=spec.settings, settings_hash=spec.settings_hash,
        f=nan, f_ref=spec.f_ref, rel_error=nan, inf_error=nan, max_violation=nan, success=False,
        status=status, message=message, wall_time_s=wall_time, time_in_evals_s=nan, x=[], history="[]",
        extra="{}",
    )
    if status == NOT_APPLICABLE:
        for c in COUNT_COLUMNS:
            row[c] = 0
    row.update(overrides=spec.overrides, run_key=spec.run_key, code_version=spec.code_version, finished_at=_now())
    return row


def execute(spec: RunSpec) -> dict[str, Any]:
    """Perform one run and return its row (never raises)."""
    if spec.not_applicable:
        return spec_row(spec, NOT_APPLICABLE, spec.not_applicable, 0.0)
    if spec.plan_error:
        return spec_row(spec, "error", spec.plan_error)
    try:
        if spec.modules and spec.modules not in _IMPORTED:
            import_modules(spec.modules)
            _IMPORTED.add(spec.modules)
        suite = load_suite(spec.suite_ref)
        case: Case = suite.case(spec.case_id)
        try:
            result = solve(case.problem, spec.solver, **spec.options)
        except NotApplicable as exc:
            return spec_row(spec, NOT_APPLICABLE, str(exc), 0.0)
        row = result_to_row(spec.suite_ref.name, case, result)
        row["history"] = compact_history(row["history"])
        if not math.isfinite(row["f"]) and row["status"] != "error":  # solve() flags these; belt and braces
            row["status"], row["success"] = "error", False
    except BaseException as exc:
        if isinstance(exc, (KeyboardInterrupt, SystemExit)):
            raise
        tb = traceback.extract_tb(exc.__traceback__)
        where = f" (at {tb[-1].filename.rsplit('/', 1)[-1]}:{tb[-1].lineno})" if tb else ""
        return spec_row(spec, "error", f"{type(exc).__name__}: {exc}{where}")
    row.update(overrides=spec.overrides, run_key=spec.run_key, code_version=spec.code_version, finished_at=_now())
    return row
