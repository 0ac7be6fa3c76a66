"""What a listing shows of a case, read without building its problem.

A suite of a large library (``cutest``: 2,397 S2MPJ instances, some of whose set-up takes
minutes) can describe its cases from the library's catalogue instead: the suite registry
(`problems._catalog.case_summaries`) names the function that does so.  Every field is the
one the built case would give (``tests/problems/test_case_summaries.py`` checks them against
built cases), so ``harness list`` prints the same lines either way, at once.
"""

from __future__ import annotations

import dataclasses

__all__ = ["CaseSummary"]


@dataclasses.dataclass(frozen=True)
class CaseSummary:
    """`problems.Case`'s listed fields: ``case_id``, ``problem_id``, ``n``, ``form`` (as
    `problems.Problem.form`), ``f_ref`` (a known optimum, or None) and ``source``."""

    case_id: str
    problem_id: str
    n: int
    form: frozenset[str]
    f_ref: float | None
    source: str
