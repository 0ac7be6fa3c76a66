"""A user's problems, checked once at their starting points before any run (suite files).

`Problem` checks what it can without evaluating anything, and the counting oracle refuses a
callable's bad return value (a vector objective, None, a transposed Jacobian) when a solver
first asks for it, so without this check such a mistake shows once per solver, as an error
row. `check_problem` evaluates every callable of a problem once at x0 (outside any run,
uncounted) and raises `ProblemInputError` naming the problem, the callable and the shape it
must have, before anything runs; it returns warnings for what is legal but will likely fail
(NaN or inf at x0) or is probably wrong (a gradient or Jacobian that disagrees with central
differences at x0).  `harness run` and `run --dry-run` call it for every problem of a
``--suite-file`` they are about to run.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

import numpy as np

from problems import Problem, fd_jacobian

from ._plan import HarnessArgumentError

__all__ = ["ProblemInputError", "check_problem", "check_problems", "DERIVATIVE_CHECK_MAX_N", "DERIVATIVE_RTOL"]

#: derivatives are compared with central differences only up to this many variables (2n evaluations)
DERIVATIVE_CHECK_MAX_N = 200
#: a derivative is reported when it differs from central differences by more than this, relative to
#: max(1, its largest entry): far above the differences' own error for smooth functions (~1e-8)
DERIVATIVE_RTOL = 1e-4
#: the interval of those central differences (`problems.fd_jacobian`)
DERIVATIVE_CHECK_STEP = 1e-6


class ProblemInputError(HarnessArgumentError):
    """A problem's callable returns something no solver can use (CLI exit status 2)."""


def _call(problem: Problem, what: str, fun: Callable[[np.ndarray], Any], x: np.ndarray) -> np.ndarray:
    try:
        out = fun(x.copy())
    except Exception as exc:  # noqa: BLE001 - the user's function failed: say which and where
        raise ProblemInputError(f"problem {problem.name!r}: {what}(x0) raised {type(exc).__name__}: {exc}") from None
    try:
        return np.asarray(out, dtype=float)
    except (TypeError, ValueError):
        raise ProblemInputError(f"problem {problem.name!r}: {what}(x0) returned {type(out).__name__} {out!r:.80}, "
                                "not numbers") from None


def _compare(problem: Problem, what: str, given: np.ndarray, fd: np.ndarray) -> str | None:
    scale = max(1.0, float(np.max(np.abs(given), initial=0.0)))
    err = np.abs(given - fd)
    if not np.all(np.isfinite(fd)) or float(np.max(err, initial=0.0)) <= DERIVATIVE_RTOL * scale:
        return None
    i = np.unravel_index(int(np.argmax(err)), err.shape)
    where = f"[{', '.join(map(str, i[1:] if what == 'gradient' else i))}]"  # a gradient is one row of fd
    return (f"problem {problem.name!r}: {what} at x0 differs from central differences by {float(err[i]):.3g} "
            f"at {where} (given {float(given[i]):.6g}, differences {float(fd[i]):.6g}): check the derivative")


def check_problem(problem: Problem, derivatives: bool = True) -> list[str]:
    """Evaluate each of ``problem``'s callables once at x0; raise `ProblemInputError` if one returns
    the wrong shape or raises, and return warnings: non-finite values at x0 and, with
    ``derivatives`` (n <= `DERIVATIVE_CHECK_MAX_N`), supplied gradients or Jacobians that
    disagree with central differences.  Shapes: the objective one number, the gradient (n,),
    ``ineq``/``eq`` (m,), their Jacobians (m, n) (also (n,) for one constraint)."""
    if not isinstance(problem, Problem):
        raise TypeError(f"check_problem needs a problems.Problem, got {type(problem).__name__} {problem!r:.80}")
    x0, n = np.array(problem.x0, dtype=float), problem.n
    notes: list[str] = []
    raw: list[Any] = []  # the objective's own return value, besides its conversion to an array

    def objective(x: np.ndarray) -> Any:
        raw.append(problem.objective(x))
        return raw[-1]

    f = _call(problem, "objective", objective, x0)
    if f.size != 1:
        raise ProblemInputError(f"problem {problem.name!r}: objective(x0) returned an array of shape {f.shape}; it "
                                "must return one number")
    try:
        if isinstance(raw[0], (bool, np.bool_)):  # the counting oracle refuses a bool, as not a number
            raise TypeError
        float(raw[0])  # what the counting oracle does with it: NumPy >= 2 refuses an array of shape (1,)
    except (TypeError, ValueError):
        what = ("None (a missing return?)" if raw[0] is None else
                f"{type(raw[0]).__name__} of shape {f.shape}")
        raise ProblemInputError(f"problem {problem.name!r}: objective(x0) returned {what}; it must return one "
                                "number (a float)") from None
    values: dict[str, np.ndarray] = {"objective": f.reshape(-1)}
    if problem.gradient is not None:
        g = _call(problem, "gradient", problem.gradient, x0)
        if g.size != n or g.ndim > 2 or (g.ndim == 2 and 1 not in g.shape):
            raise ProblemInputError(f"problem {problem.name!r}: gradient(x0) has shape {g.shape}; expected ({n},), "
                                    "one entry per variable")
        values["gradient"] = g.reshape(-1)
    for which, jac_name, m in (("ineq", "ineq_jacobian", problem.n_ineq), ("eq", "eq_jacobian", problem.n_eq)):
        fun, jac = getattr(problem, which), getattr(problem, jac_name)
        if fun is None:
            continue
        c = _call(problem, which, fun, x0)
        if c.size != m or c.ndim > 1:
            raise ProblemInputError(f"problem {problem.name!r}: {which}(x0) has shape {c.shape}; expected ({m},) "
                                    f"(n_{which} = {m})")
        values[which] = c.reshape(-1)
        if jac is not None:
            J = _call(problem, jac_name, jac, x0)
            if J.shape != (m, n) and not (m == 1 and J.shape == (n,)):
                hint = " (the transpose: one row per constraint, one column per variable)" if J.shape == (n, m) else ""
                raise ProblemInputError(f"problem {problem.name!r}: {jac_name}(x0) has shape {J.shape}; expected "
                                        f"({m}, {n}) = (n_{which}, n){hint}")
            values[jac_name] = J.reshape(m, n)
    bad = [k for k, v in values.items() if not np.all(np.isfinite(v))]
    if bad:
        notes.append(f"problem {problem.name!r}: {', '.join(bad)} not finite at x0 (NaN or inf): solvers will likely "
                     "fail at the start")
    if derivatives and n <= DERIVATIVE_CHECK_MAX_N and not bad:
        pairs: list[tuple[str, Callable[[np.ndarray], Any] | None]] = [
            ("gradient", problem.objective), ("ineq_jacobian", problem.ineq), ("eq_jacobian", problem.eq)]
        for name, fun in pairs:
            if name in values and fun is not None:
                try:
                    fd = fd_jacobian(fun, x0, None, DERIVATIVE_CHECK_STEP, "central")[0]
                except Exception:  # noqa: BLE001 - a function undefined next to x0: no comparison
                    continue
                note = _compare(problem, name, values[name].reshape(fd.shape), fd)
                if note:
                    notes.append(note)
    return notes


def check_problems(problems: Iterable[Problem], derivatives: bool = True) -> list[str]:
    """`check_problem` of each problem (each name once); the first bad one raises."""
    notes, seen = [], set()
    for p in problems:
        if p.name not in seen:
            seen.add(p.name)
            notes += check_problem(p, derivatives)
    return notes
