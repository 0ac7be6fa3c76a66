"""Finite-difference derivatives (thesis Sections 4.5.2, 5.8.2, 6.6.2).

Vectorized over the n perturbations where the function allows it is not assumed: the
callables are user functions of one point, so each perturbed point is one call and one
counted function evaluation.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ._problem import ProblemError, _real_array, _shown

__all__ = ["fd_gradient", "fd_jacobian"]

_F64 = np.dtype(float)


def fd_jacobian(
    fun: Callable[[np.ndarray], np.ndarray],
    x: np.ndarray,
    f0: np.ndarray | None,
    step: float,
    scheme: str = "forward",
    *,
    m: int | None = None,
    name: str = "the function",
) -> tuple[np.ndarray, int]:
    """Jacobian of a vector function by forward or central differences.

    Parameters
    ----------
    fun : callable returning an array of shape (m,) (or a scalar, m = 1)
    x : (n,) point
    f0 : value of ``fun`` at x, or None (forward differences then evaluate it)
    step : interval Gamma
    scheme : "forward" (n evaluations) or "central" (2n evaluations)
    m : number of values ``fun`` must return (None: as many as ``f0`` or its first value has)
    name : names ``fun`` in the `ProblemError` raised when it returns anything else

    Returns
    -------
    J : (m, n) array
    n_evals : number of calls of ``fun`` made
    """
    x = np.asarray(x, dtype=float)
    n = x.size
    if f0 is not None:
        f0 = np.atleast_1d(f0)
        m = f0.size if m is None else m

    def call(z: np.ndarray) -> np.ndarray:
        nonlocal m
        r = fun(z)
        v = r if type(r) is np.ndarray and r.dtype is _F64 else _real_array(r)
        if v is None or (m is not None and v.size != m):
            want = "numbers" if m is None else f"{m} numbers"
            raise ProblemError(f"{name} returned {_shown(r)} near x (finite differences); expected {want}")
        m = v.size
        return v.reshape(-1)

    evals = 0
    if scheme == "forward" and f0 is None:
        f0 = call(x)
        evals += 1
    cols = []
    for i in range(n):
        e = np.zeros(n)
        e[i] = step
        fp = call(x + e)
        evals += 1
        if scheme == "central":
            fm = call(x - e)
            evals += 1
            cols.append((fp - fm) / (2.0 * step))
        else:
            assert f0 is not None  # evaluated above for forward differences
            cols.append((fp - f0) / step)
    return np.column_stack(cols), evals


def fd_gradient(
    fun: Callable[[np.ndarray], float],
    x: np.ndarray,
    f0: float | None,
    step: float,
    scheme: str = "forward",
    *,
    name: str = "the function",
) -> tuple[np.ndarray, int]:
    """Gradient of a scalar function by finite differences; returns (g, n_evals)."""
    J, evals = fd_jacobian(fun, x, None if f0 is None else np.atleast_1d(f0), step,  # type: ignore[arg-type]
                           scheme, m=1, name=name)  # a scalar function is the m = 1 case of fd_jacobian
    return J[0], evals
