"""A SciPy-compatible facade: use any registered solver through `scipy.optimize.minimize`.

>>> from scipy.optimize import minimize
>>> from solvers.scipy_compat import method
>>> res = minimize(rosen, x0, jac=rosen_der, method=method("sqsd"), options={"rho": 0.3})

The thesis optimizers then interoperate with SciPy-based tools. Constraints are given as
SciPy dicts (``{"type": "ineq", "fun": c}`` meaning c(x) >= 0, or ``"eq"``; each with its
own ``jac`` and ``args``) or as `scipy.optimize.NonlinearConstraint` /
`scipy.optimize.LinearConstraint` (lb <= c(x) <= ub); they are converted to this project's
g(x) <= 0, h(x) = 0 convention in `_to_problem`.  ``tol`` and ``callback`` have no
counterpart here and are refused with the solver's own tolerance options named; ``hess``
and ``hessp`` are not used (the solvers build their own curvature models), with a warning,
as SciPy warns for its methods that do not use them.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from scipy.optimize import LinearConstraint, NonlinearConstraint, OptimizeResult

from problems import Problem

from ._registry import get_solver_class
from ._solve import solve

__all__ = ["method"]

#: one constraint block in SciPy's sign (c >= 0 or c = 0): its function and Jacobian (None:
#: finite differences), each taking x alone (the block's own ``args`` already bound)
_Block = tuple[Callable[[np.ndarray], np.ndarray], Callable[[np.ndarray], np.ndarray] | None]


def _bound(f: Callable, args: tuple) -> Callable[[np.ndarray], Any]:
    return lambda x: f(x, *args)


def _stack(funcs: Sequence[Callable], sign: float) -> Callable[[np.ndarray], np.ndarray]:
    return lambda x: sign * np.concatenate([np.atleast_1d(np.asarray(f(x), dtype=float)) for f in funcs])


def _stack_jac(funcs: Sequence[Callable | None], sign: float) -> Callable | None:
    if any(f is None for f in funcs):
        return None
    return lambda x: sign * np.vstack([np.atleast_2d(np.asarray(f(x), dtype=float)) for f in funcs])


def _from_dict(c: dict) -> tuple[str, _Block]:
    """A SciPy constraint dict -> (type, block), with its own ``args``."""
    if not isinstance(c, dict) or "type" not in c or "fun" not in c:
        raise TypeError("each constraint must be a dict {'type': 'ineq' | 'eq', 'fun': c[, 'jac', 'args']} or a "
                        f"scipy.optimize.NonlinearConstraint / LinearConstraint, got {c!r}")
    if c["type"] not in ("ineq", "eq"):
        raise ValueError(f"constraint type must be 'ineq' or 'eq', got {c['type']!r}")
    args = tuple(c.get("args", ()))
    jac = c.get("jac")
    return c["type"], (_bound(c["fun"], args), _bound(jac, args) if callable(jac) else None)


def _from_bounds_form(fun: Callable, jac: Callable | None, lb, ub, x0: np.ndarray) -> list[tuple[str, _Block]]:
    """lb <= fun(x) <= ub (SciPy's new-style constraints) -> an 'eq' block fun - lb = 0 on the
    rows where lb == ub, and one 'ineq' block [fun - lb; ub - fun] >= 0 on the rows whose lower
    / upper bound is finite (one evaluation of fun per block, however many sides it has)."""
    m = np.atleast_1d(np.asarray(fun(np.asarray(x0, dtype=float)), dtype=float)).size
    lb = np.broadcast_to(np.asarray(lb, dtype=float), (m,))
    ub = np.broadcast_to(np.asarray(ub, dtype=float), (m,))
    if np.any(np.isnan(lb)) or np.any(np.isnan(ub)) or np.any(lb > ub):
        raise ValueError(f"constraint bounds must satisfy lb <= ub (no NaN), got lb={lb}, ub={ub}")
    val = lambda x: np.atleast_1d(np.asarray(fun(x), dtype=float))
    jv = None if jac is None else (lambda x: np.atleast_2d(np.asarray(jac(x), dtype=float)))
    out: list[tuple[str, _Block]] = []
    eq = np.flatnonzero(lb == ub)
    if eq.size:
        out.append(("eq", (lambda x: val(x)[eq] - lb[eq], None if jv is None else (lambda x: jv(x)[eq]))))
    lo = np.flatnonzero((lb < ub) & np.isfinite(lb))
    hi = np.flatnonzero((lb < ub) & np.isfinite(ub))
    if lo.size or hi.size:
        def ineq(x: np.ndarray) -> np.ndarray:
            v = val(x)
            return np.concatenate([v[lo] - lb[lo], ub[hi] - v[hi]])

        def ineq_jac(x: np.ndarray) -> np.ndarray:
            J = jv(x)  # type: ignore[misc]  # only built when jv is given
            return np.vstack([J[lo], -J[hi]])

        out.append(("ineq", (ineq, None if jv is None else ineq_jac)))
    return out


def _blocks(constraints: Any, x0: np.ndarray) -> list[tuple[str, _Block]]:
    if isinstance(constraints, (dict, NonlinearConstraint, LinearConstraint)):
        constraints = [constraints]
    out: list[tuple[str, _Block]] = []
    for c in constraints:
        if isinstance(c, NonlinearConstraint):
            out += _from_bounds_form(c.fun, c.jac if callable(c.jac) else None, c.lb, c.ub, x0)
        elif isinstance(c, LinearConstraint):
            A = np.atleast_2d(np.asarray(c.A.toarray() if hasattr(c.A, "toarray") else c.A, dtype=float))
            out += _from_bounds_form(lambda x, A=A: A @ x, lambda x, A=A: A, c.lb, c.ub, x0)
        else:
            out.append(_from_dict(c))
    return out


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
    blocks = _blocks(constraints, x0)
    ineq = [b for t, b in blocks if t == "ineq"]
    eq = [b for t, b in blocks if t == "eq"]
    kw: dict[str, Any] = {}
    if ineq:
        kw["ineq"] = _stack([f for f, _ in ineq], -1.0)
        kw["ineq_jacobian"] = _stack_jac([j for _, j in ineq], -1.0)
    if eq:
        kw["eq"] = _stack([f for f, _ in eq], 1.0)
        kw["eq_jacobian"] = _stack_jac([j for _, j in eq], 1.0)
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
        if tol is not None:
            tols = [o["name"] for o in get_solver_class(name).options()
                    if o["name"].startswith("eps") or "tol" in o["name"]]
            raise ValueError(f"method({name!r}) does not take SciPy's generic tol: set the solver's own tolerances "
                             f"in options instead ({', '.join(tols) or 'it has none'}; "
                             "python -m harness list solvers shows what each means)")
        if callback is not None:
            raise ValueError(f"method({name!r}) does not call a callback during the run; every evaluated point "
                             "is in the result's history (solvers.solve(...).history)")
        for given, what in ((hess, "hess"), (hessp, "hessp")):
            if given is not None:
                warnings.warn(f"method({name!r}) does not use Hessian information ({what})", RuntimeWarning,
                              stacklevel=3)
        problem = _to_problem(fun, x0, args, jac, bounds, constraints)
        r = solve(problem, name, **{**fixed, **options})
        return OptimizeResult(x=r.x, fun=r.f, success=r.success, status=0 if r.success else 1,
                              message=r.message, nit=r.nit, nfev=r.nf, njev=r.ng, nfg=r.nfg,
                              maxcv=r.max_violation, solver_status=r.status.value)

    _minimize.__name__ = f"haybench_{name.replace('-', '_')}"
    return _minimize
