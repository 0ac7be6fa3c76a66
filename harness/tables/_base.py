"""The table type that every suite's table plug-in returns.

A plug-in is a module ``harness.tables.<suite_with_underscores>`` with a function
``tables(runs: pandas.DataFrame) -> list[Table]`` building the thesis's tables from the
stored runs (columns of `harness._record.ROW_COLUMNS`), ours beside the thesis's.
"""

from __future__ import annotations

import dataclasses

import pandas as pd

__all__ = ["Table"]


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
