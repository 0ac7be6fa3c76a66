"""A SciPy-compatible facade: use any registered solver through `scipy.optimize.minimize`.

>>> from scipy.optimize import minimize
>>> from solvers.scipy_compat import method
>>> res = minimize(rosen, x0, jac=rosen_der, method=method("sqsd"), options={"rho": 0.3})

The thesis optimizers then interoperate with SciPy-based tools. Constraints are given as
SciPy dicts (``{"type": "ineq", "fun": c}`` meaning c(x) >= 0, or ``"eq"``); they are
converted to this project's g(x) <= 0 convention by negation in `_to_problem`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from scipy.optimize import OptimizeResult

from problems import Problem

from ._solve import solve

__all__ = ["method"]


def _stack(funcs: Sequence[Callable], args: tuple, sign: float) -> Callable[[np.ndarray], np.ndarray]:
    return lambda x: sign * np.concatenate([np.atleast_1d(np.asarray(f(x, *args), dtype=float)) for f in funcs])


def _stack_jac(funcs: Sequence[Callable | None], args: tuple, sign: float) -> Callable | None:
    if any(f is None for f in funcs):
        return None
    return lambda x: sign * np.vstack([np.atleast_2d(np.asarray(f(x, *args), dtype=float)) for f in funcs])


def _to_problem(fun, x0, args=(), jac=None, bounds=None, constraints=()) -> Problem:
    """SciPy's minimize arguments -> Problem (HS/SciPy c(x) >= 0 becomes g = -c <= 0)."""
    if callable(jac):
        gradient = lambda x: np.asarray(jac(x, *args), dtype=float)
        objective = lambda x: float(fun(x, *args))
    elif jac is True:
        objective = lambda x: float(fun(x, *args)[0])
        gradient = lambda x: np.asarray(fun(x, *args)[1], dtype=float)
    else:
        objective, gradient = (lambda x: float(fun(x, *args))), None
    if isinstance(constraints, dict):
        constraints = [constraints]
    ineq = [c for c in constraints if c["type"] == "ineq"]
    eq = [c for c in constraints if c["type"] == "eq"]
    bad = [c["type"] for c in constraints if c["type"] not in ("ineq", "eq")]
    if bad:
        raise ValueError(f"constraint type must be 'ineq' or 'eq', got {bad}")
    kw: dict[str, Any] = {}
    if ineq:
        kw["ineq"] = _stack([c["fun"] for c in ineq], tuple(ineq[0].get("args", ())), -1.0)
        kw["ineq_jacobian"] = _stack_jac([c.get("jac") for c in ineq], tuple(ineq[0].get("args", ())), -1.0)
    if eq:
        kw["eq"] = _stack([c["fun"] for c in eq], tuple(eq[0].get("args", ())), 1.0)
        kw["eq_jacobian"] = _stack_jac([c.get("jac") for c in eq], tuple(eq[0].get("args", ())), 1.0)
    if bounds is not None:
        lb = getattr(bounds, "lb", None)
        if lb is not None:
            kw["lower"], kw["upper"] = bounds.lb, bounds.ub
        else:
            arr = np.array([[(-np.inf if lo is None else lo), (np.inf if hi is None else hi)] for lo, hi in bounds])
            kw["lower"], kw["upper"] = arr[:, 0], arr[:, 1]
    return Problem(name=getattr(fun, "__name__", "scipy-problem"), x0=x0, objective=objective,
                   gradient=gradient, **kw)


def method(name: str, **fixed: Any) -> Callable[..., OptimizeResult]:
    """A callable for ``scipy.optimize.minimize(..., method=method(name))``.

    ``options`` passed to minimize become solver options; ``fixed`` are applied first.
    The result's ``nfev``/``njev`` are the counting oracle's ``nf``/``ng`` and ``nfg``
    is added as an extra field.
    """

    def _minimize(fun, x0, args=(), jac=None, hess=None, hessp=None, bounds=None, constraints=(),
                  tol=None, callback=None, **options: Any) -> OptimizeResult:
        problem = _to_problem(fun, x0, args, jac, bounds, constraints)
        r = solve(problem, name, **{**fixed, **options})
        return OptimizeResult(x=r.x, fun=r.f, success=r.success, status=0 if r.success else 1,
                              message=r.message, nit=r.nit, nfev=r.nf, njev=r.ng, nfg=r.nfg,
                              maxcv=r.max_violation, solver_status=r.status.value)

    _minimize.__name__ = f"haybench_{name.replace('-', '_')}"
    return _minimize
