"""Tables of suite ``cutest`` (S2MPJ problems): per-solver summary and every run."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import pandas as pd

from .._best_known import best_known_values
from ._base import Table
from ._campaign import campaign_tables


def tables(runs: pd.DataFrame, reference: Mapping[str, Any] | None = None) -> list[Table]:
    """``reference``: the suite's stored best-known points (`harness._best_known`)."""
    from problems.s2mpj.cutest_suite import SOLVERS

    return campaign_tables(runs, list(SOLVERS), prefix="cutest", suite="cutest",
                           best_known=best_known_values(dict(reference or {})))
