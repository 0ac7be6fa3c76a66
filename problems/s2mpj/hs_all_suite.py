"""Suite ``hs-all``: every Hock–Schittkowski problem of S2MPJ (HS1–HS119 and the variants
S2MPJ carries, 127 instances), through the same adapter as ``cutest``.

Reference optima: the 40 problems of thesis Table 3.1 have the verified optima of the
project's ``hs`` suite (problems/hs/hock_schittkowski.json); E^r is against them.  For the
others the tables measure E^r against the best feasible f any stored run reached, and
say so (docs/cutest.md).  ``tests/problems/test_s2mpj.py`` checks that the 40 agree with
the ``hs`` suite at x0 and at x*.
"""

from __future__ import annotations

import functools
import re

from .._suite import Case, Suite
from ._cases import case_for, instance_of
from ._select import select

__all__ = ["SUITE", "INSTANCES", "hs_reference"]

SELECTION = r"name~^HS\d+[A-Z]*$"
SOLVERS = ("dynamic-q", "dynamic-q-plus", "lfopc", "etopc", "scipy-slsqp",
           "scipy-trust-constr", "ipopt", "nlopt-mma", "nlopt-slsqp",
           "sqsd", "scipy-lbfgsb")


@functools.lru_cache(maxsize=1)
def _hs_data() -> dict[str, dict]:
    from problems.hs import load_data  # the verified optima of the Table 3.1 problems

    return load_data()


def hs_reference(instance: str) -> tuple[float | None, object]:
    """(f_ref, x_ref) of an S2MPJ HS instance that is one of Table 3.1's problems, else (None, None)."""
    m = re.fullmatch(r"HS(\d+)", instance)
    if not m:
        return None, None
    key = f"hs{int(m.group(1)):03d}"
    if key not in _hs_data():
        return None, None
    from problems.hs import problem

    p = problem(key)
    return p.f_ref, p.x_ref


def INSTANCES() -> list[str]:
    return list(select(SELECTION)["instance"])


def _build() -> list[Case]:
    return [case_for(i, hs_reference) for i in INSTANCES()]


def _selector(expression: str) -> list[Case]:
    chosen = set(select(expression + "," + SELECTION if expression else SELECTION)["instance"])
    return [case_for(i, hs_reference) for i in INSTANCES() if i in chosen]


SUITE = Suite(
    name="hs-all",
    description="every Hock-Schittkowski problem of S2MPJ (CUTEst), 127 instances; the 40 of Table 3.1 with "
                "verified optima",
    build=_build, solvers=SOLVERS,
    build_case=lambda case_id: case_for(instance_of(case_id), hs_reference),
    selector=_selector,
    tables="harness.tables.hs_all",
)
