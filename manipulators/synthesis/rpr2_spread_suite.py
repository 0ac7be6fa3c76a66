"""Suite ``rpr2-spread``: how far Dynamic-Q's 2-RPR synthesis ends move under tiny changes of the start.

Table 4.7 (E synthesis) is not reproduced from SP1, SP3, SP4, while Tables 4.3-4.6
(O synthesis) are.  Section 4.6.2 calls the E runs "slow and erratic"; this suite
measures how erratic: Dynamic-Q, with exactly the settings of suite ``rpr2``
(`rpr2_suite._caps`), runs O and E synthesis from each thesis start SP1-SP4 and from
``N_PERTURBED`` starts that differ from it by at most ``EPS`` in every component
(uniform, seeded; the thesis prints its starts to three decimals at most).  A cell whose
ends spread far beyond its tolerance under such changes cannot be pinned by any
implementation; a cell whose ends stay together can.

Cases are ordinary `Case`s of the same problems (`rpr2_suite.o_problem`,
`rpr2_suite.e_problem`) with start labels ``SP1``, ``SP1~1`` ... ``SP1~10``; the table
plug-in ``harness.tables.rpr2_spread`` summarizes them.  About 7 minutes on 2 cores.
"""

from __future__ import annotations

import numpy as np

from problems import Case, Suite

from .rpr2_suite import STARTS, _caps, e_problem, o_problem

__all__ = ["SUITE", "EPS", "N_PERTURBED", "perturbed_start", "parse_start"]

EPS = 1e-6  # largest change of any start component
N_PERTURBED = 10  # perturbed starts per thesis start (besides the thesis start itself)
KINDS = {"o": ("rpr2-o", o_problem), "e": ("rpr2-e", e_problem)}


def perturbed_start(start: str, k: int, eps: float = EPS) -> np.ndarray:
    """Start ``k`` about thesis start ``start`` (k = 0: the start itself).

    Components move by eps * U(-1, 1), seeded by (start, k): the same starts on every
    machine and run.
    """
    if start not in STARTS:
        raise ValueError(f"unknown start {start!r}; valid: {', '.join(STARTS)}")
    if not (isinstance(k, (int, np.integer)) and k >= 0):
        raise ValueError(f"k must be an integer >= 0, got {k!r}")
    x0 = np.asarray(STARTS[start], dtype=float)
    if k == 0:
        return x0
    rng = np.random.default_rng([list(STARTS).index(start), int(k)])
    return x0 + eps * rng.uniform(-1.0, 1.0, x0.size)


def parse_start(label: str) -> tuple[str, int]:
    """``"SP3~7"`` -> ("SP3", 7); ``"SP3"`` -> ("SP3", 0)."""
    base, _, k = label.partition("~")
    return base, int(k) if k else 0


def _build() -> list[Case]:
    cases: list[Case] = []
    for kind, (pid, make) in KINDS.items():
        opts = _caps(kind)
        for sp in STARTS:
            problem = make(sp)
            for k in range(N_PERTURBED + 1):
                label = sp if k == 0 else f"{sp}~{k}"
                cases.append(Case(problem.with_start(perturbed_start(sp, k), name=problem.name + label[len(sp):]),
                                  pid, start=label, options=opts,
                                  meta={"table": "4.7s", "thesis_start": sp, "k": k, "eps": EPS}))
    return cases


SUITE = Suite(
    name="rpr2-spread",
    description=(f"2-RPR O and E synthesis by Dynamic-Q from SP1-SP4 and {N_PERTURBED} starts within {EPS:g} "
                 "of each: how much the thesis's cells depend on the start (Tables 4.3-4.7)"),
    build=_build,
    solvers=("dynamic-q",),
    tables="harness.tables.rpr2_spread",
    figures="harness.figures.rpr2_spread",
)
