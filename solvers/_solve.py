"""`solve`: the one front door from a problem and a solver to a `Result`."""

from __future__ import annotations

import dataclasses
import time
import traceback
from typing import Any

import numpy as np

from problems import BudgetExhausted, Oracle, Problem
from problems._numbers import is_finite_number, is_integer

from ._base import AbstractSolver, NotApplicable
from ._registry import make_solver, parse_spec
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
        Largest constraint violation for which a converged run counts as a success. A solver
        with its own ``feas_tol`` option (multistart) left at its default runs with this one.
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
    ValueError
        If ``max_nfg``, ``feas_tol`` or a solver option is invalid.
    """
    if not isinstance(problem, Problem):
        raise TypeError(f"solve() needs a problems.Problem, got {type(problem).__name__}")
    if not (max_nfg is None or (is_integer(max_nfg) and max_nfg >= 1)):
        raise ValueError(f"solve(): max_nfg={max_nfg!r} is invalid; valid: None or an integer >= 1")
    if not (is_finite_number(feas_tol) and feas_tol >= 0):
        raise ValueError(f"solve(): feas_tol={feas_tol!r} is invalid; valid: a finite number >= 0")
    inst = make_solver(solver, **options)
    if _takes_solve_feas_tol(inst, solver, options) and inst.feas_tol != feas_tol:  # type: ignore[attr-defined]
        inst = dataclasses.replace(inst, feas_tol=float(feas_tol))  # type: ignore[type-var]  # a dataclass
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


def _at_default(inst: AbstractSolver, name: str) -> bool:
    """Whether option ``name`` of ``inst`` holds its field's default."""
    for f in dataclasses.fields(inst):  # type: ignore[arg-type]  # concrete solvers are dataclasses
        if f.name == name:
            return f.default is not dataclasses.MISSING and bool(getattr(inst, name) == f.default)
    return False


def _takes_solve_feas_tol(inst: AbstractSolver, solver: str | AbstractSolver, options: dict[str, Any]) -> bool:
    """Whether the solver has a ``feas_tol`` option that nobody set (not in the spec, the keywords or the instance)."""
    if "feas_tol" in options or not _at_default(inst, "feas_tol"):
        return False
    return not (isinstance(solver, str) and "feas_tol" in parse_spec(solver)[1])


def _checked_output(problem: Problem, inst: AbstractSolver, oracle: Oracle,
                    out: Any) -> tuple[np.ndarray, Status, str, int, dict[str, Any]]:
    """x, status, message, nit and extra of a solver's output; a malformed output is status error."""
    if not isinstance(out, SolverOutput):
        return (oracle.last_x, Status.ERROR, f"{inst.name}: minimize returned {type(out).__name__}, "
                f"not a SolverOutput", 0, {})
    try:
        x = np.asarray(out.x, dtype=float).reshape(-1)
        status = Status(out.status)
        nit, extra = int(out.nit), dict(out.extra)
    except Exception as exc:  # noqa: BLE001 - a malformed output must not lose the run
        return oracle.last_x, Status.ERROR, f"{inst.name}: minimize returned a malformed SolverOutput: {exc}", 0, {}
    message = out.message or status.message
    if x.size != problem.n:
        return (x, Status.ERROR, f"{inst.name}: minimize returned x of length {x.size}, the problem has "
                f"n = {problem.n}; {message}", nit, extra)
    return x, status, message, nit, extra


def _finish(problem: Problem, inst: AbstractSolver, oracle: Oracle, out: SolverOutput,
            wall: float, feas_tol: float) -> Result:
    x, status, message, nit, extra = _checked_output(problem, inst, oracle, out)
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
        nfg=c["nfg"], nf=c["nf"], ng=c["ng"], nc=c["nc"], nj=c["nj"], nh=c["nh"], nit=nit,
        max_violation=viol, success=bool(success), wall_time=wall, time_in_evals=oracle.time_in_evals,
        options=inst.settings(), history=oracle.complete_history(), extra=extra,
    )
