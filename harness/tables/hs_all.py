"""Tables of suite ``hs-all`` (every HS problem of S2MPJ): per-solver summary and every run."""

from __future__ import annotations

import pandas as pd

from ._base import Table
from ._campaign import campaign_tables


def tables(runs: pd.DataFrame) -> list[Table]:
    from problems.s2mpj.hs_all_suite import SOLVERS

    return campaign_tables(runs, list(SOLVERS), prefix="hs_all", suite="hs-all")
