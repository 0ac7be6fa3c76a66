"""`solve`: the one front door from a problem and a solver to a `Result`."""

from __future__ import annotations

import time
import traceback
from typing import Any

import numpy as np

from problems import BudgetExhausted, Oracle, Problem

from ._base import AbstractSolver, NotApplicable
from ._registry import make_solver
from ._result import Result, SolverOutput, Status

__all__ = ["solve"]

FEASIBILITY_TOL = 1e-6


def solve(
    problem: Problem,
    solver: str | AbstractSolver,
    *,
    max_nfg: int | None = None,
    feas_tol: float = FEASIBILITY_TOL,
    throw: bool = False,
    **options: Any,
) -> Result:
    """Minimize ``problem`` with ``solver`` and measure the cost.

    Parameters
    ----------
    problem : Problem
    solver : str or AbstractSolver
        A registry id (``"sqsd"``, ``"dynamic-q"``, ``"lfopc[mu1=1e4]"``) or an instance.
    max_nfg : int, optional
        Budget of distinct evaluation points; reaching it ends the run with ``max_iter``.
    feas_tol : float
        Largest constraint violation for which a converged run counts as a success.
    throw : bool
        Re-raise exceptions from the solver or the problem instead of returning a
        Result with status ``error``.
    **options
        Solver options (see ``python -m harness list solvers``). Unknown names raise
        ValueError listing the valid ones.

    Raises
    ------
    NotApplicable
        If the solver cannot handle the problem's constraints.
    """
    if not isinstance(problem, Problem):
        raise TypeError(f"solve() needs a problems.Problem, got {type(problem).__name__}")
    inst = make_solver(solver, **options)
    reason = inst.can_solve(problem)
    if reason:
        raise NotApplicable(f"{problem.name}: {reason}")
    oracle = Oracle(problem, max_nfg=max_nfg)
    t0 = time.perf_counter()
    try:
        out = inst.minimize(oracle)
    except BudgetExhausted as exc:
        out = SolverOutput(x=oracle.last_x, status=Status.MAX_ITER, message=str(exc))
    except Exception as exc:  # recorded, never lost: the harness keeps going
        if throw:
            raise
        tb = traceback.extract_tb(exc.__traceback__)
        where = f" (at {tb[-1].filename.rsplit('/', 1)[-1]}:{tb[-1].lineno})" if tb else ""
        out = SolverOutput(x=oracle.last_x, status=Status.ERROR, message=f"{type(exc).__name__}: {exc}{where}")
    wall = time.perf_counter() - t0
    return _finish(problem, inst, oracle, out, wall, feas_tol)


def _finish(problem: Problem, inst: AbstractSolver, oracle: Oracle, out: SolverOutput,
            wall: float, feas_tol: float) -> Result:
    x = np.asarray(out.x, dtype=float).reshape(-1)
    status, message = Status(out.status), out.message or Status(out.status).message
    # f and the violation at the returned point, outside the count (report evaluations)
    try:
        f = float(problem.objective(x)) if x.size == problem.n else float("nan")
        viol = problem.max_violation(x) if x.size == problem.n else float("nan")
    except Exception as exc:  # noqa: BLE001 - a report evaluation must not lose the run
        f, viol = float("nan"), float("nan")
        message = f"{message}; evaluating the final point failed: {exc}"
    if status is not Status.ERROR and not (np.isfinite(f) and np.all(np.isfinite(x)) and np.isfinite(viol)):
        status, message = Status.ERROR, f"non-finite result (f={f}, max_violation={viol}); {message}"
    success = status is Status.CONVERGED and viol <= feas_tol
    c = oracle.counts()
    return Result(
        solver=inst.name, problem=problem.name, x=x, f=f, status=status, message=message,
        nfg=c["nfg"], nf=c["nf"], ng=c["ng"], nc=c["nc"], nj=c["nj"], nh=c["nh"], nit=int(out.nit),
        max_violation=viol, success=bool(success), wall_time=wall, time_in_evals=oracle.time_in_evals,
        options=inst.settings(), history=oracle.complete_history(), extra=dict(out.extra),
    )
