"""Suite ``rpr2-exact``: 2-RPR E synthesis (4.14) in exact, smooth form, from SP1-SP4.

Table 4.7 poses E synthesis as the thesis does: min dW_c subject to the equality
h = dW_p = 0, both areas from the chord method (Appendix C, chord 0.1) and the triangle
scheme (4.9), gradients by forward differences.  That h is >= 0 everywhere and zero on the
whole enclosing region, so its gradient vanishes where it is met (a degenerate constraint),
and the chord discretization makes it piecewise: every solver of suite ``rpr2`` that
insists on feasibility stalls (docs/manipulators.md, "E synthesis in exact form").

`rpr2_exact.exact_e_problem` states the same synthesis exactly: W_p lies inside W_c iff it
lies above the base line and every leg length over its boundary is within
[l_min, 1.5 l_min], so (4.14) is min area(W_c) - area(W_p) subject to smooth inequalities
at ``EXACT_K`` boundary points, with analytic derivatives.  This suite makes that an
ordinary `Problem` (`e_exact_problem`) and runs every constrained solver on it from the
thesis's starts, at its defaults: what each solver reaches once the formulation, not the
solver, is the difficulty.  Table plug-in ``harness.tables.rpr2_exact`` (Table 4.7x).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from problems import Case, Problem, Suite

from ..prescribed import PRESCRIBED
from ._design_cache import DesignCache
from .rpr2_exact import EXACT_K, _jsonable, exact_e_problem, exact_optimum
from .rpr2_suite import STARTS

__all__ = ["SUITE", "SOLVERS", "L_MIN_LOWER", "e_exact_problem", "reference"]

#: the constrained solvers of suite ``rpr2`` (SQSD is unconstrained)
SOLVERS = ("lfopc", "etopc", "dynamic-q", "dynamic-q-plus", "scipy-slsqp", "ipopt", "nlopt-mma", "scipy-cobyla")
#: lower bound on l_1^min, l_2^min (a leg of length <= 0 is no design; as `rpr2_exact`'s SLSQP)
L_MIN_LOWER = 0.05


def e_exact_problem(start: str = "SP1", prescribed: str = "P1", k: int = EXACT_K) -> Problem:
    """E synthesis (4.14) in exact form as a `Problem`, started at Table 4.2's ``start``.

    Variables d = [xA, yA, xB, l1min, l2min] (l_max = 1.5 l_min, Section 4.5.2).  Objective
    area(W_c) - area(W_p) (= dW_c when W_p is enclosed), inequalities g(d) <= 0: the leg
    limits at ``k`` points of W_p's boundary (4k rows) and W_p above the base line (one row),
    all with analytic derivatives (`rpr2_exact.exact_e_problem`).  Bounds l_min >= 0.05.
    """
    if start not in STARTS:
        raise ValueError(f"unknown start {start!r}; valid: {', '.join(STARTS)}")
    if prescribed not in PRESCRIBED:
        raise ValueError(f"unknown prescribed workspace {prescribed!r}; valid: {', '.join(PRESCRIBED)}")
    if not (isinstance(k, (int, np.integer)) and k >= 3):
        raise ValueError(f"k (boundary points) must be an integer >= 3, got {k!r}")
    f, cons = exact_e_problem(prescribed, int(k))
    # the oracle asks for value and derivative at one point separately; each pair is one computation
    f_memo: DesignCache[tuple[float, np.ndarray]] = DesignCache(4)
    c_memo: DesignCache[tuple[np.ndarray, np.ndarray]] = DesignCache(4)
    inf = np.inf
    return Problem(
        name=f"rpr2-e-exact-{start}", x0=np.asarray(STARTS[start], dtype=float),
        objective=lambda d: f_memo.get(d, f)[0], gradient=lambda d: f_memo.get(d, f)[1],
        ineq=lambda d: -c_memo.get(d, cons)[0], ineq_jacobian=lambda d: -c_memo.get(d, cons)[1],
        n_ineq=4 * int(k) + 1,
        lower=np.array([-inf, -inf, -inf, L_MIN_LOWER, L_MIN_LOWER]), upper=np.full(5, inf),
        source="Hay 2003, Sec. 4.6, eq. (4.14) in exact form (ours: leg limits on dW_p, no chord method)",
        tags=("manipulator", "rpr2", "E", "exact"), meta={"prescribed": prescribed, "k": int(k), "kind": "e-exact"})


def _build() -> list[Case]:
    return [Case(e_exact_problem(sp), "rpr2-e-exact", start=sp, meta={"table": "4.7x"}) for sp in STARTS]


def reference(runs=None, stored: dict[str, Any] | None = None) -> dict[str, Any]:
    """The exact E problem's local minima (`rpr2_exact.exact_optimum`: multistart SLSQP), for
    Table 4.7x to name the minimum each end reached; computed once and kept."""
    stored = dict(stored or {})
    return {"exact_optimum": stored.get("exact_optimum") or _jsonable(exact_optimum("e"))}


SUITE = Suite(
    name="rpr2-exact",
    description="2-RPR E synthesis (4.14) in exact smooth form (no chord method) from SP1-SP4, every constrained "
                "solver at its defaults (Table 4.7x)",
    build=_build,
    solvers=SOLVERS,
    tables="harness.tables.rpr2_exact",
)
