"""Adapters to established convex solvers (LP and QP) for small, repeated problems.

Not part of the registry of general NLP solvers: these solve the cable-tension
subproblems of thesis Section 6.3 (the constrained l1 LP (6.19) and l2 QP (6.17)) with
well-kept libraries, to compare with the in-house LfopC and the closed forms.

Problems have the form

    minimize   c^T x            (LP)      or   ||x||_2^2 + q^T x   (QP)
    subject to A x = b,  lb <= x <= ub

Backends: ``"highs"``, ``"clarabel"``, ``"osqp"`` through cvxpy (one compiled,
parametrized problem per shape and backend, so repeated solves skip cvxpy's compilation),
and ``"linprog"`` (``scipy.optimize.linprog(method="highs")``, LP only).

Each backend has a status map (cvxpy-style ``STATUS_MAP``) from the solver's reported
status to our `Status` and a feasibility verdict (True, False or None = undetermined).
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from ._result import Status

__all__ = ["ConvexResult", "STATUS_MAPS", "LINPROG_STATUS_MAP", "LP_BACKENDS", "QP_BACKENDS",
           "map_status", "solve_lp", "solve_qp"]

LP_BACKENDS = ("highs", "clarabel", "osqp", "linprog")
QP_BACKENDS = ("osqp", "clarabel")

_CVXPY_NAME = {"highs": "HIGHS", "clarabel": "CLARABEL", "osqp": "OSQP"}

# cvxpy normalizes each solver's status to these strings (cvxpy.settings). Per backend:
# an "inaccurate" answer from the first-order OSQP usually means its iteration limit was
# reached with a usable point (MAX_ITER); from the interior-point Clarabel it means
# "AlmostSolved" short of full accuracy (FAILED, point kept). An infeasibility
# certificate is a converged answer whose verdict is "infeasible".
_COMMON = {
    "optimal": (Status.CONVERGED, True),
    "infeasible": (Status.CONVERGED, False),
    "unbounded": (Status.CONVERGED, True),
    "solver_error": (Status.ERROR, None),
    "user_limit": (Status.MAX_ITER, None),
}
STATUS_MAPS: dict[str, dict[str, tuple[Status, bool | None]]] = {
    "osqp": {**_COMMON,
             "optimal_inaccurate": (Status.MAX_ITER, True),
             "infeasible_inaccurate": (Status.MAX_ITER, False),
             "unbounded_inaccurate": (Status.MAX_ITER, None)},
    "clarabel": {**_COMMON,
                 "optimal_inaccurate": (Status.FAILED, True),
                 "infeasible_inaccurate": (Status.FAILED, False),
                 "unbounded_inaccurate": (Status.FAILED, None)},
    "highs": {**_COMMON,
              "optimal_inaccurate": (Status.FAILED, True),
              "infeasible_inaccurate": (Status.FAILED, False),
              "unbounded_inaccurate": (Status.FAILED, None),
              # HiGHS cannot always tell infeasible from unbounded after presolve
              "infeasible_or_unbounded": (Status.FAILED, None)},
}

#: scipy.optimize.linprog ``status`` codes (SciPy documentation of OptimizeResult).
LINPROG_STATUS_MAP: dict[int, tuple[Status, bool | None]] = {
    0: (Status.CONVERGED, True),   # optimization terminated successfully
    1: (Status.MAX_ITER, None),    # iteration limit reached
    2: (Status.CONVERGED, False),  # problem appears to be infeasible
    3: (Status.CONVERGED, True),   # problem appears to be unbounded
    4: (Status.FAILED, None),      # numerical difficulties encountered
}


@dataclasses.dataclass(frozen=True)
class ConvexResult:
    """Outcome of one convex solve: x (None unless a point was returned), our status,
    the feasibility verdict (None = undetermined), the backend's own status, the backend."""

    x: np.ndarray | None
    status: Status
    feasible: bool | None
    raw_status: str
    backend: str


def map_status(backend: str, raw: str | int) -> tuple[Status, bool | None]:
    """Our (Status, feasible) for a backend's status; unknown statuses are errors."""
    table = LINPROG_STATUS_MAP if backend == "linprog" else STATUS_MAPS.get(backend)
    if table is None:
        raise ValueError(f"unknown convex backend {backend!r}; valid: {', '.join(LP_BACKENDS)}")
    return table.get(raw, (Status.ERROR, None))  # type: ignore[arg-type]  # str or int keys by backend


def _check(name: str, A, b, lb, ub, vec):
    A = np.atleast_2d(np.asarray(A, dtype=float))
    m, n = A.shape
    b = np.asarray(b, dtype=float).reshape(m)
    v = np.asarray(vec, dtype=float).reshape(n)
    lb = np.broadcast_to(np.asarray(lb, dtype=float), (n,))
    ub = np.broadcast_to(np.asarray(ub, dtype=float), (n,))
    for label, arr in (("A", A), ("b", b), (name, v)):
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"{label} contains NaN or inf")
    if np.any(lb > ub):
        raise ValueError(f"lower bounds exceed upper bounds at {np.flatnonzero(lb > ub).tolist()}")
    return A, b, lb, ub, v


@functools.lru_cache(maxsize=64)
def _compiled(kind: str, m: int, n: int, backend: str):
    """A parametrized cvxpy problem (DPP) for one shape: compiled once, re-solved fast."""
    from problems._registry import require

    cp = require("cvxpy", f"backend {backend!r} of solvers.convex")

    x = cp.Variable(n)
    A, b = cp.Parameter((m, n)), cp.Parameter(m)
    lb, ub, c = cp.Parameter(n), cp.Parameter(n), cp.Parameter(n)
    obj = c @ x if kind == "lp" else cp.sum_squares(x) + c @ x
    prob = cp.Problem(cp.Minimize(obj), [A @ x == b, x >= lb, x <= ub])
    return prob, x, (A, b, lb, ub, c)


_SOLVER_OPTS = {
    # tight tolerances: the cable tensions are compared across backends to 1e-4 and better
    "osqp": dict(eps_abs=1e-10, eps_rel=1e-10, max_iter=200000, polishing=True),
    "clarabel": dict(tol_gap_abs=1e-10, tol_gap_rel=1e-10, tol_feas=1e-10),
    "highs": {},
}


@functools.cache
def _swallow_highs_banner() -> None:
    """Build the process's first HiGHS object with the C stdout sent to /dev/null, once.

    HiGHS prints its banner ("Running HiGHS ... Copyright ...") to the C-level stdout when the
    first ``Highs`` object of a process is made, before any option (cvxpy's ``verbose``, HiGHS's
    ``output_flag``) can silence it, so a user's tension query printed it into their output.
    Later objects print nothing.
    """
    try:
        import highspy
    except ImportError:  # cvxpy then reports the missing solver itself
        return
    import ctypes
    import os
    import sys

    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
            highspy.Highs()
            try:  # C stdio buffers (a pipe is block-buffered) go to /dev/null too
                ctypes.CDLL(None).fflush(None)
            except (OSError, AttributeError, TypeError):  # no C library handle (Windows): banner may show
                pass
    finally:
        os.dup2(saved, 1)
        os.close(saved)


def _cvxpy_solve(kind, A, b, lb, ub, c, backend) -> ConvexResult:
    from problems._registry import require

    cp = require("cvxpy", f"backend {backend!r} of solvers.convex")
    if backend == "highs":
        _swallow_highs_banner()

    prob, x, params = _compiled(kind, A.shape[0], A.shape[1], backend)
    for p, v in zip(params, (A, b, lb, ub, c)):
        p.value = v
    try:
        prob.solve(solver=_CVXPY_NAME[backend], **_SOLVER_OPTS[backend])
    except cp.error.SolverError as exc:
        return ConvexResult(None, Status.ERROR, None, f"solver_error: {exc}", backend)
    status, feasible = map_status(backend, prob.status)
    xv = None if x.value is None or feasible is False else np.array(x.value, dtype=float)
    return ConvexResult(xv, status, feasible, str(prob.status), backend)


def solve_lp(c, A, b, lb, ub, backend: str = "highs") -> ConvexResult:
    """minimize c^T x subject to A x = b, lb <= x <= ub, with ``backend`` (`LP_BACKENDS`)."""
    if backend not in LP_BACKENDS:
        raise ValueError(f"unknown LP backend {backend!r}; valid: {', '.join(LP_BACKENDS)}")
    A, b, lb, ub, c = _check("c", A, b, lb, ub, c)
    if backend == "linprog":
        from scipy.optimize import linprog

        res = linprog(c, A_eq=A, b_eq=b, bounds=np.column_stack([lb, ub]), method="highs")
        status, feasible = map_status("linprog", int(res.status))
        x = np.asarray(res.x, dtype=float) if res.x is not None and feasible else None
        return ConvexResult(x, status, feasible, f"{res.status}: {res.message}", backend)
    return _cvxpy_solve("lp", A, b, lb, ub, c, backend)


def solve_qp(A, b, lb, ub, q=None, backend: str = "clarabel") -> ConvexResult:
    """minimize ||x||^2 + q^T x subject to A x = b, lb <= x <= ub (`QP_BACKENDS`)."""
    if backend not in QP_BACKENDS:
        raise ValueError(f"unknown QP backend {backend!r}; valid: {', '.join(QP_BACKENDS)}")
    n = np.atleast_2d(np.asarray(A)).shape[1]
    A, b, lb, ub, q = _check("q", A, b, lb, ub, np.zeros(n) if q is None else q)
    return _cvxpy_solve("qp", A, b, lb, ub, q, backend)
