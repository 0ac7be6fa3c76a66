"""Tables of suite ``cutest`` (S2MPJ problems): per-solver summary and every run."""

from __future__ import annotations

import pandas as pd

from ._base import Table
from ._campaign import campaign_tables


def tables(runs: pd.DataFrame) -> list[Table]:
    from problems.s2mpj.cutest_suite import SOLVERS

    return campaign_tables(runs, list(SOLVERS), prefix="cutest", suite="cutest")
