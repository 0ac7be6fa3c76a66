"""Suite ``rpr2-spread``: how far the 2-RPR synthesis ends move under tiny changes of the start.

Table 4.7 (E synthesis) is not reproduced from SP1, SP3, SP4, while Tables 4.3-4.6
(O synthesis) are.  Section 4.6.2 calls the E runs "slow and erratic"; this suite
measures how erratic: Dynamic-Q, Dynamic-Q+ and SciPy's SLSQP, with exactly the settings of
suite ``rpr2`` (`rpr2_suite._caps`), run O and E synthesis from each thesis start SP1-SP4 and
from ``N_PERTURBED`` starts that differ from it by at most ``EPS`` in every component
(`_spread.perturbed`; the thesis prints its starts to three decimals at most).  A cell
whose ends spread far beyond its tolerance under such changes cannot be pinned by any
implementation; a cell whose ends stay together can.

Cases are ordinary `Case`s of the same problems (`rpr2_suite.o_problem`,
`rpr2_suite.e_problem`) with start labels ``SP1``, ``SP1~1`` ... ``SP1~10``; the table
plug-in ``harness.tables.rpr2_spread`` summarizes them.  About 12 minutes on 2 cores.
"""

from __future__ import annotations

import numpy as np

from problems import Case, Suite

from ._spread import parse_start, perturbed, start_label
from .rpr2_suite import STARTS, _caps, e_problem, o_problem

__all__ = ["SUITE", "EPS", "N_PERTURBED", "perturbed_start", "parse_start"]

EPS = 1e-6  # largest change of any start component
N_PERTURBED = 10  # perturbed starts per thesis start (besides the thesis start itself)
KINDS = {"o": ("rpr2-o", o_problem), "e": ("rpr2-e", e_problem)}


def perturbed_start(start: str, k: int, eps: float = EPS) -> np.ndarray:
    """Start ``k`` about thesis start ``start`` (k = 0: the start itself).

    Components move by eps * U(-1, 1), seeded by (the start's index in SP1-SP4, k): the
    same starts on every machine and run (`_spread.perturbed`).
    """
    if start not in STARTS:
        raise ValueError(f"unknown start {start!r}; valid: {', '.join(STARTS)}")
    return perturbed(STARTS[start], (list(STARTS).index(start),), k, eps)


def _build() -> list[Case]:
    cases: list[Case] = []
    for kind, (pid, make) in KINDS.items():
        opts = _caps(kind)
        for sp in STARTS:
            problem = make(sp)
            for k in range(N_PERTURBED + 1):
                label = start_label(sp, k)
                cases.append(Case(problem.with_start(perturbed_start(sp, k), name=problem.name + label[len(sp):]),
                                  pid, start=label, options=opts,
                                  meta={"table": "4.7s", "thesis_start": sp, "k": k, "eps": EPS}))
    return cases


SUITE = Suite(
    name="rpr2-spread",
    description=(f"2-RPR O and E synthesis by Dynamic-Q, Dynamic-Q+ and SLSQP from SP1-SP4 and {N_PERTURBED} starts "
                 f"within {EPS:g} of each: how much the thesis's cells depend on the start (Tables 4.3-4.7)"),
    build=_build,
    solvers=("dynamic-q", "dynamic-q-plus", "scipy-slsqp"),
    tables="harness.tables.rpr2_spread",
    figures="harness.figures.rpr2_spread",
)
