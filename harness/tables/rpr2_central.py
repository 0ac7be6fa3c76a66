"""Table 4.7c (suite ``rpr2-central``): E synthesis with central differences, from SP1-SP4 and from
starts within 1e-6 of them.

The rows of Table 4.7s (`rpr2_spread.spread_rows`: per thesis start and solver, the ends' spread,
the thesis's value, Table 4.7's tolerance and Dynamic-Q+'s target) for the runs of suite
``rpr2-central``, whose only change from suite ``rpr2`` is the finite-difference scheme.
Diagnostic only: nothing is flagged.
"""

from __future__ import annotations

import pandas as pd

from ._base import Table
from .rpr2_spread import TOLERANCE_NOTES, spread_rows

__all__ = ["tables"]


def tables(runs: pd.DataFrame) -> list[Table]:
    from manipulators.synthesis.rpr2_central_suite import FD_SCHEME
    from manipulators.synthesis.rpr2_spread_suite import EPS

    return [Table(
        name="table_4_7c",
        title=f"Table 4.7c: E synthesis with {FD_SCHEME} differences, from SP1-SP4 and from starts within {EPS:g} "
              "of them",
        frame=pd.DataFrame(spread_rows(runs)), flags=None,
        notes=[f"Each row: one solver with suite rpr2's settings for Table 4.7 (chord 0.1, Gamma = 1e-3, the "
               f"iteration caps) but {FD_SCHEME} instead of forward differences, from the thesis start and from "
               f"the starts of Table 4.7s that differ from it by at most {EPS:g} in every component "
               "(manipulators.synthesis.rpr2_central_suite; the literal Dynamic-Q from the thesis starts only). "
               "Section 4.6.2 gives the interval but not the scheme; the thesis states central differences for "
               "its D and cable syntheses (Sections 5.8.2, 6.6.2). 'thesis f*' is the thesis's Dynamic-Q value.",
               *TOLERANCE_NOTES,
               "Compare with Table 4.7s (the same starts, forward differences): h = dW_p is a parabola in the "
               "design near an enclosing one, whose forward-difference slope errs by about h'' Gamma / 2, as much "
               "as the slope itself near h = 0 (docs/dynamic_q_plus_targets.md).",
               "Regenerate: python -m harness run --suite rpr2-central."])]
