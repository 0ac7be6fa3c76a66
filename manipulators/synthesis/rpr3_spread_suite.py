"""Suite ``rpr3-spread``: how far the 3-RPR MO and D synthesis ends move under tiny changes of the start.

Suite ``rpr3`` runs each of MO and D synthesis (Tables 5.4, 5.5) on P1-P3 from one start,
d0 = [-0.75, 0, 0.75, 1.5, 0.75].  Those objectives are minima of kappa^-1 over the
prescribed boundary and their constraints areas of traced workspaces, differentiated by
finite differences: an end can hang on the last digits of the path (docs/rpr3.md).  This
suite measures how much: Dynamic-Q, Dynamic-Q+ and SciPy's SLSQP, with exactly suite
``rpr3``'s settings (`rpr3_suite._options`), run every MO and D case from d0 and from
``N_PERTURBED`` starts that differ from it by at most ``EPS`` in every component
(`_spread.perturbed`).  A cell whose ends stay together under such changes can be judged
by one run; one whose ends scatter can only be judged by their spread.

Cases are ordinary `Case`s of the same problems (`rpr3_suite.synthesis_problem`) with
start labels ``d0``, ``d0~1`` ... ``d0~5``; the table plug-in ``harness.tables.rpr3_spread``
summarizes them against the exact model's optima (`rpr3_exact.reference`, stored in
``reference.json`` as for suite ``rpr3``).  About 35 minutes on 2 cores.
"""

from __future__ import annotations

from problems import Case, Suite

from ._spread import perturbed, start_label
from .rpr3_suite import SETTINGS, _options, synthesis_problem

__all__ = ["SUITE", "EPS", "N_PERTURBED", "KINDS", "PRESCRIBED"]

EPS = 1e-6  # largest change of any start component (as suite rpr2-spread)
N_PERTURBED = 5  # perturbed starts per case, besides d0 (each D run takes 1-4 minutes)
KINDS = ("mo", "d")  # the syntheses whose ends move (SO's stay within 0.001 of the exact optima)
PRESCRIBED = ("P1", "P2", "P3")
SOLVERS = ("dynamic-q", "dynamic-q-plus", "scipy-slsqp")


def _build() -> list[Case]:
    cases: list[Case] = []
    for i, kind in enumerate(KINDS):
        for j, pname in enumerate(PRESCRIBED):
            problem = synthesis_problem(kind, pname)
            for k in range(N_PERTURBED + 1):
                label = start_label("d0", k)
                cases.append(Case(problem.with_start(perturbed(problem.x0, (i, j), k, EPS),
                                                     name=problem.name + label[2:]),
                                  problem.name, start=label, options=_options(kind),
                                  meta={"table": SETTINGS[kind]["table"] + "s", "kind": kind, "prescribed": pname,
                                        "k": k, "eps": EPS}))
    return cases


SUITE = Suite(
    name="rpr3-spread",
    description=(f"3-RPR MO and D synthesis from d0 and {N_PERTURBED} starts within {EPS:g} of it: how much the "
                 "ends of Tables 5.4-5.5 depend on the start"),
    build=_build,
    solvers=SOLVERS,
    tables="harness.tables.rpr3_spread",
    figures="harness.figures.rpr3_spread",
)
