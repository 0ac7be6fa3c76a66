"""One-variable boundary searches of the chord method (reduced form, Section 5.4.2).

Every subproblem of the chord method in its reduced-variable form has one variable (the
ray length r, eq. 5.16, or the chord angle omega) and asks for the first crossing of the
feasibility boundary along it. The thesis solves these with LfopC / Dynamic-Q
(Appendix C, eqs. C.9, C.12) or by bisection for discontinuous cable constraints
(Algorithm 6.3). A bracketed 1-D root is found faster and exactly (to ``xtol``) by a
safeguarded Newton iteration (smooth constraints) or by bisection (indicator
constraints), so that is what is used here. All evaluations are vectorized: one call of
the constraint function evaluates several trial points.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["Evaluator", "solve_bracket"]


class Evaluator:
    """Counting, validating wrapper of a vectorized constraint function ``C(U) -> (k, m)``.

    A point is feasible iff all ``C[:, j] <= 0``. NaN values count as violated (+inf).
    """

    def __init__(self, constraints: Callable[[np.ndarray], np.ndarray]):
        if not callable(constraints):
            raise TypeError("constraints must be a callable C(U) -> array (k, m)")
        self.constraints = constraints
        self.calls = 0
        self.points = 0
        self.m: int | None = None

    def __call__(self, U: np.ndarray) -> np.ndarray:
        C = self.constraints(U)
        if type(C) is not np.ndarray or C.dtype != np.float64:
            C = np.asarray(C, dtype=float)
        k = U.shape[0]
        if C.ndim == 1:
            C = C[:, None]
        if C.ndim != 2 or C.shape[0] != k:
            raise ValueError(f"constraints(U) must return shape (k, m) for U of shape ({k}, 2), got {C.shape}")
        if self.m is None:
            self.m = C.shape[1]
        self.calls += 1
        self.points += k
        if np.isnan(C.sum()):  # one reduction instead of an elementwise where on every call
            C = np.where(np.isnan(C), np.inf, C)
        return C

    def phi(self, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """max_j C_j at each point and the index of the largest constraint."""
        C = self(U)
        return C.max(axis=1), C.argmax(axis=1)


def solve_bracket(phi_of: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
                  a: float, b: float, fa: float, fb: float, ja: int, *,
                  xtol: float, smooth: bool = True, n_refine: int = 15,
                  max_iter: int = 100, first=None) -> tuple[float, int]:
    """First feasibility crossing in a bracket of one variable.

    Parameters
    ----------
    phi_of : callable ``phi_of(xs) -> (max_j C_j, argmax_j)`` at the trial values ``xs``.
    a, b : the infeasible end (``fa > 0``) and the feasible end (``fb <= 0``); ``a`` may be
        larger or smaller than ``b``.
    ja : index of the violated constraint at ``a``.
    xtol : absolute accuracy in the variable.
    smooth : True -> safeguarded Newton with a one-sided difference of width ``xtol``
        (two points per call; quadratic convergence, bisection when Newton leaves the
        bracket or stalls); False -> multi-point bisection with ``n_refine`` points per call
        (Algorithm 6.3 generalized; values of ``phi`` are only used for their sign).
    first : optional ``(x, v, j)``: values already computed at the Newton pair
        ``[x, x + sigma h]`` with ``h = min(xtol, |b - a|/4)`` (the chord method evaluates
        it at a predicted angle together with its scan), used instead of a first call.

    Returns
    -------
    x : a *feasible* value within ``xtol`` of the crossing.
    j : the constraint violated just beyond it (the active constraint).
    """
    if not smooth:
        while abs(b - a) > xtol and max_iter > 0:
            max_iter -= 1
            xs = a + (b - a) * np.arange(1, n_refine + 1) / (n_refine + 1)
            v, j = phi_of(xs)
            feas = v <= 0
            if feas.any():
                k = int(np.argmax(feas))
                if k > 0:
                    a, ja = xs[k - 1], int(j[k - 1])
                b = xs[k]
            else:
                a, ja = xs[-1], int(j[-1])
        return float(b), int(ja)

    sigma = 1.0 if b > a else -1.0  # direction from the infeasible to the feasible end
    x = b - fb * (b - a) / (fb - fa) if fa != fb else 0.5 * (a + b)  # regula falsi start
    dx_old = abs(b - a)
    for _ in range(max_iter):
        if abs(b - a) <= xtol:
            break
        h = min(xtol, 0.25 * abs(b - a))
        if first is not None:
            x, v, j = first
            first = None
            lo, hi = min(a, b), max(a, b)
            if not (lo < x < hi and lo < x + sigma * h < hi):
                x = b - fb * (b - a) / (fb - fa) if fa != fb else 0.5 * (a + b)
                continue
            xs = np.array([x, x + sigma * h])
        else:
            xs = np.array([x, x + sigma * h])
            v, j = phi_of(xs)
        if v[0] > 0:
            a, fa, ja = x, v[0], int(j[0])
            if v[1] <= 0:
                b, fb = xs[1], v[1]
                break
            a, fa, ja = xs[1], v[1], int(j[1])
            push = 0.0
        else:
            b, fb = x, v[0]
            push = -sigma * h  # approaching from the feasible side: aim just past the root
        deriv = (v[1] - v[0]) / (sigma * h)
        xn = x - v[0] / deriv + push if deriv != 0 and np.isfinite(deriv) else np.nan
        lo, hi = min(a, b), max(a, b)
        # rtsafe-style safeguard: bisect when Newton leaves the bracket or does not
        # at least halve its step (kinks of max_j C_j at corners, flat stretches)
        if not (lo < xn < hi) or abs(xn - x) > 0.5 * dx_old:
            xn = 0.5 * (a + b)
        dx_old = abs(xn - x)
        x = float(xn)
    return float(b), int(ja)
