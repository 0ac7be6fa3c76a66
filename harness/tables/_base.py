"""The table type that every suite's table plug-in returns.

A plug-in is a module ``harness.tables.<suite_with_underscores>`` with a function
``tables(runs: pandas.DataFrame) -> list[Table]`` building the thesis's tables from the
stored runs (columns of `harness._record.ROW_COLUMNS`), ours beside the thesis's.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import pandas as pd

__all__ = ["Table", "count", "count_cell", "column_flags"]


@dataclasses.dataclass
class Table:
    """One rendered table.

    name : file stem, e.g. ``"table_2_1"``.
    title : caption, e.g. ``"Table 2.1: SQSD and SD on the Appendix A problems"``.
    frame : the cells (ours beside the thesis's); strings or numbers.
    flags : same shape as ``frame`` (or None): True where our cell differs from the
        thesis beyond the tolerance the plug-in states in ``notes``; renderers mark them.
    notes : free text lines printed under the table (tolerances, why a number differs).
    """

    name: str
    title: str
    frame: pd.DataFrame
    flags: pd.DataFrame | None = None
    notes: list[str] = dataclasses.field(default_factory=list)


def count(value: object) -> int | None:
    """A stored count as an int, or None when the run has none (error, time-out, not applicable).

    Rows without counts are failures of that solver on that case: tables show them as such
    and never call ``int()`` on a missing value.
    """
    if value is None or value is pd.NA:
        return None
    try:
        v = float(value)  # type: ignore[arg-type]  # numbers, numpy scalars and numeric strings
    except (TypeError, ValueError):
        return None
    return int(v) if v == v and abs(v) != float("inf") else None


def count_cell(value: object) -> int | str:
    """A count for a table cell: the int, or "" when the run has none (its status says why)."""
    c = count(value)
    return "" if c is None else c


def column_flags(frame: pd.DataFrame, **columns: list[bool]) -> pd.DataFrame | None:
    """A `Table.flags` frame for ``frame``: False everywhere but the named columns, which
    take the given per-row flags (e.g. ``column_flags(frame, reached=[...])``); None if empty."""
    if not len(frame):
        return None
    flags = pd.DataFrame(False, index=frame.index, columns=frame.columns)
    for name, values in columns.items():
        flags[name] = list(values)
    return flags


def run_end(row: Any) -> tuple[np.ndarray, float, float]:
    """A stored run's end: x (empty if none), f and the largest violation (NaN where missing)."""
    x = np.asarray(row["x"], dtype=float) if row["x"] is not None else np.array([])
    f = float(row["f"]) if row["f"] is not None and pd.notna(row["f"]) else math.nan
    viol = float(row["max_violation"]) if pd.notna(row["max_violation"]) else math.nan
    return x, f, viol
