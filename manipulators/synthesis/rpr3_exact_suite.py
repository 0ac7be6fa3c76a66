"""Suite ``rpr3-exact``: 3-RPR SO, MO and D synthesis in exact form, from the suite ``rpr3`` starts.

Suite ``rpr3`` poses the syntheses as the thesis does (5.34-5.40): max min kappa^-1 subject
to g = area of W_p outside the chord workspaces (triangle scheme (4.9)) <= 0, with finite
differences of traced workspaces.  `rpr3_exact` states the same syntheses exactly: W_p lies
inside a constant-orientation workspace iff every leg length over W_p's boundary is within its
limits (and W_p is on the upper branch), so each synthesis is max t subject to
t <= kappa^-1 and the leg limits at ``k`` points of W_p's boundary on every slice
(`rpr3_exact.exact_constraints`): smooth constraints, no chord method.  This suite makes that an
ordinary `Problem` (`exact_problem`) and runs the ``rpr3`` solvers on it from the same starts at
their defaults, so that what a solver reaches from the start in the exact model - the local
optimum, or another - can be read beside Tables 5.3-5.5.  Table plug-in
``harness.tables.rpr3_exact`` (Table 5.3x).
"""

from __future__ import annotations

import numpy as np

from problems import Case, Problem, Suite

from .._checks import is_integer
from .rpr3_exact import CASES, GLOBAL_BOX, _slices, exact_constraints
from .rpr3_suite import PRESCRIBED3, SETTINGS, SOLVERS, design

__all__ = ["SUITE", "K", "FD_STEP", "R_MIN", "exact_problem"]

K = 96  # points of W_p's boundary per slice (as `rpr3_exact.exact_optimum`'s local stage)
FD_STEP = 1e-7  # central differences of the constraints: leg lengths and kappa^-1 are smooth in z
#: lower bound on the platform size r (a platform of size <= 0 is no manipulator; the lower end of
#: `rpr3_exact.GLOBAL_BOX`).  Without it Ipopt steps to r < 0 on MO/D P1-P2 and reports infeasibility.
R_MIN = GLOBAL_BOX[4][0]


def exact_problem(kind: str, prescribed: str = "P1", k: int = K) -> Problem:
    """SO/MO/D synthesis in exact form as a `Problem` in z = [x_C, y_C, x_D, x_E, r, t].

    Minimize -t subject to g(z) = -`exact_constraints` (z) <= 0: every leg-length excess over
    ``k`` points of W_p's boundary on every slice (D: 11 over the range), and t - kappa^-1 at
    the same points on the kappa slices (5.39); bound r >= `R_MIN`.  Starts at suite ``rpr3``'s
    design with t = min kappa^-1 there (so only the leg limits can be violated at the start).  The objective's
    gradient is exact; the constraints' Jacobian is by central differences (step `FD_STEP`).
    """
    kl = str(kind).lower()
    if not (is_integer(k) and k >= 3):
        raise ValueError(f"k (boundary points per slice) must be an integer >= 3, got {k!r}")
    cons = exact_constraints(kl, prescribed, int(k))  # checks kind and prescribed, naming the valid ones
    d0 = np.asarray(SETTINGS[kl]["start"], dtype=float)
    B = PRESCRIBED3[prescribed].points(int(k))
    m0 = design(d0)
    if m0 is None:
        raise ValueError(f"{kl}/{prescribed}: the suite's start {d0.tolist()} is not a valid design")
    t0 = min(float(m0.inverse_condition(B, p).min()) for p in _slices(kl)[1])
    grad = np.r_[np.zeros(5), -1.0]
    return Problem(
        name=f"rpr3-{kl}-exact-{prescribed.lower()}", x0=np.append(d0, t0),
        objective=lambda z: -float(z[5]), gradient=lambda z: grad.copy(),
        ineq=lambda z: -cons(np.asarray(z, dtype=float)), n_ineq=int(cons(np.append(d0, t0)).size),
        lower=np.array([-np.inf] * 4 + [R_MIN, -np.inf]), upper=np.full(6, np.inf),
        fd="central", fd_step=FD_STEP,
        source=f"Hay 2003, Sec. 5.{ {'so': 6, 'mo': 7, 'd': 8}[kl] }, eqs. (5.34)-(5.40) in exact form "
               "(ours: leg limits on dW_p, no chord method)",
        tags=("manipulator", "rpr3", kl.upper(), "exact"), meta={"prescribed": prescribed, "k": int(k), "kind": kl})


def _build() -> list[Case]:
    return [Case(exact_problem(kind, p), f"rpr3-{kind}-exact", start=p, meta={"table": "5.3x", "kind": kind})
            for kind, p in CASES]


SUITE = Suite(
    name="rpr3-exact",
    description="3-RPR SO, MO and D synthesis in exact form (leg limits on W_p's boundary, no chord method) from "
                "suite rpr3's starts, its solvers at their defaults (Table 5.3x)",
    build=_build,
    solvers=SOLVERS,
    tables="harness.tables.rpr3_exact",
)
