"""Suite ``rpr2-exact``: 2-RPR E synthesis (4.14) from SP1-SP4 and P synthesis (4.21) for P1-P3,
in exact, smooth form.

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

P synthesis likewise (Table 4.9's cases; `p_exact_problem`): suite ``rpr2`` maximizes min
kappa^-1 over P's boundary subject to g(d) <= 0 (4.16) on chord workspaces, whose sagitta
lets slivers of P fall outside the exact workspace at an end on g = 0 (Table 4.9's
'enclosed' column).  `rpr2_exact.exact_p_problem` states it exactly, in epigraph form: max t
subject to kappa^-1 >= t at the suite's 2048 boundary points and the leg limits [4, 7] at
``EXACT_K`` of them (Table 4.9x).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from problems import Case, Problem, Suite

from .._checks import is_integer
from ..prescribed import PRESCRIBED
from ._design_cache import DesignCache
from .rpr2_exact import EXACT_K, _jsonable, exact_e_problem, exact_optimum, exact_p_problem, p_start
from .rpr2_suite import STARTS

__all__ = ["SUITE", "SOLVERS", "L_MIN_LOWER", "P_CASES", "e_exact_problem", "p_exact_problem", "reference"]

#: the prescribed workspaces of Table 4.9 (Section 4.7.3)
P_CASES = ("P1", "P2", "P3")

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
    if not (is_integer(k) and k >= 3):
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


def p_exact_problem(prescribed: str = "P1", k: int = EXACT_K) -> Problem:
    """P synthesis (4.21) for Table 4.9's ``prescribed`` workspace in exact form as a `Problem`.

    Variables z = [xA, yA, xB, t] (l in [4, 7], Section 4.7.3), objective -t (max t), started at
    Section 4.7.3's d0 lifted by t = min kappa^-1 there (`rpr2_exact.p_start`); inequalities
    g(z) <= 0: kappa^-1 >= t at the 2048 boundary points of suite rpr2's objective, the leg
    limits at ``k`` boundary points (4k rows) and P above the base line (one row), all with
    analytic derivatives (`rpr2_exact.exact_p_problem`).  No bounds.
    """
    if prescribed not in P_CASES:
        raise ValueError(f"unknown prescribed workspace {prescribed!r}; valid: {', '.join(P_CASES)}")
    if not (is_integer(k) and k >= 3):
        raise ValueError(f"k (boundary points) must be an integer >= 3, got {k!r}")
    cons = exact_p_problem(prescribed, int(k))
    c_memo: DesignCache[tuple[np.ndarray, np.ndarray]] = DesignCache(4)
    x0 = p_start(prescribed)
    return Problem(
        name=f"rpr2-p{prescribed[-1]}-exact", x0=x0,
        objective=lambda z: -float(z[3]), gradient=lambda z: np.array([0.0, 0.0, 0.0, -1.0]),
        ineq=lambda z: -c_memo.get(z, cons)[0], ineq_jacobian=lambda z: -c_memo.get(z, cons)[1],
        n_ineq=cons(x0)[0].size,
        source="Hay 2003, Sec. 4.7, eq. (4.21) in exact epigraph form (ours: leg limits on dP, no chord method)",
        tags=("manipulator", "rpr2", "P", "exact"), meta={"prescribed": prescribed, "k": int(k), "kind": "p-exact"})


def _build() -> list[Case]:
    cases = [Case(e_exact_problem(sp), "rpr2-e-exact", start=sp, meta={"table": "4.7x"}) for sp in STARTS]
    cases += [Case(p_exact_problem(p), f"rpr2-p{p[-1]}-exact", start="d0", meta={"table": "4.9x", "prescribed": p})
              for p in P_CASES]
    return cases


def reference(runs=None, stored: dict[str, Any] | None = None) -> dict[str, Any]:
    """The exact E problem's local minima and the exact P problems' best designs
    (`rpr2_exact.exact_optimum`: multistart SLSQP), for Tables 4.7x and 4.9x to name the
    minimum each end reached; computed once and kept."""
    stored = dict(stored or {})
    p_opt = dict(stored.get("exact_p_optimum") or {})
    for p in P_CASES:
        p_opt[p] = p_opt.get(p) or _jsonable(exact_optimum("p", p))
    return {"exact_optimum": stored.get("exact_optimum") or _jsonable(exact_optimum("e")), "exact_p_optimum": p_opt}


SUITE = Suite(
    name="rpr2-exact",
    description="2-RPR E synthesis (4.14) from SP1-SP4 and P synthesis (4.21) for P1-P3 in exact smooth form (no "
                "chord method), every constrained solver at its defaults (Tables 4.7x, 4.9x)",
    build=_build,
    solvers=SOLVERS,
    tables="harness.tables.rpr2_exact",
)
