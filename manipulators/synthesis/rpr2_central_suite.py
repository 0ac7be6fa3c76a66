"""Suite ``rpr2-central``: 2-RPR E synthesis (4.14) with central instead of forward differences.

Section 4.6.2 gives E synthesis's finite-difference interval (Gamma = 1e-3) but not its scheme;
suite ``rpr2`` takes forward differences, as Section 4.5.2 states for the same manipulator, and
so reproduces the thesis's experiment.  Its equality h = dW_p is >= 0 and, near an enclosing
design, a parabola in the design (h ~ 2.5 t^2 at Dynamic-Q+'s ends), so forward differences
err by about h'' Gamma / 2 ~ 2.5e-3 in its slope, as much as the slope itself near h = 0
(docs/dynamic_q_plus_targets.md).  Central differences of the same interval, the scheme the
thesis states for its later syntheses (Sections 5.8.2, 6.6.2), are exact for a parabola.

This suite runs E synthesis with ``fd="central"`` and suite ``rpr2``'s settings otherwise
(`rpr2_suite._caps`), from SP1-SP4 and from the perturbed starts of suite ``rpr2-spread``
(`rpr2_spread_suite.perturbed_start`: the same 10 starts within 1e-6 of each): Dynamic-Q+ and
SciPy's SLSQP from all 44, the literal Dynamic-Q (whose runs take minutes each) from the four
thesis starts.  A sensitivity study of our [OWN] choice, beside Tables 4.7 and 4.7s, not a
replacement of either.  Table plug-in ``harness.tables.rpr2_central`` (Table 4.7c).
"""

from __future__ import annotations

from problems import Case, Suite

from ._spread import start_label
from .rpr2_spread_suite import EPS, N_PERTURBED, perturbed_start
from .rpr2_suite import STARTS, _caps, e_problem

__all__ = ["SUITE", "SOLVERS", "FD_SCHEME"]

FD_SCHEME = "central"
SOLVERS = ("dynamic-q", "dynamic-q-plus", "scipy-slsqp")
#: the solvers of the perturbed starts (the literal Dynamic-Q runs from the thesis starts only)
SPREAD_SOLVERS = ("dynamic-q-plus", "scipy-slsqp")


def _build() -> list[Case]:
    cases: list[Case] = []
    opts = _caps("e")
    for sp in STARTS:
        problem = e_problem(sp).replace(fd=FD_SCHEME)
        for k in range(N_PERTURBED + 1):
            label = start_label(sp, k)
            meta = {"table": "4.7c", "thesis_start": sp, "k": k, "eps": EPS, "fd": FD_SCHEME}
            if k:
                meta["solvers"] = SPREAD_SOLVERS
            cases.append(Case(problem.with_start(perturbed_start(sp, k), name=problem.name + label[len(sp):]),
                              "rpr2-e", start=label, options=opts, meta=meta))
    return cases


SUITE = Suite(
    name="rpr2-central",
    description=(f"2-RPR E synthesis with central differences (Section 4.6.2 names no scheme) and suite rpr2's "
                 f"settings otherwise, from SP1-SP4 and {N_PERTURBED} starts within {EPS:g} of each (Table 4.7c)"),
    build=_build,
    solvers=SOLVERS,
    tables="harness.tables.rpr2_central",
)
