"""Cable tensions by an optimization solver, one pose at a time (thesis Section 6.3).

The thesis solves the constrained l2 problem (6.17) with LfopC at every pose; the
constrained l1 problem (6.19) is a linear program. These per-pose solvers are the
reference (and the thesis's own method) against which the closed forms of
`_distribution` are tested and timed:

* ``lfopc``: problem (6.17) in the thesis's reduced variables t^B (n - 3 independent
  tensions; t^A = M + N t^B, eq. 6.16) with the in-house LFOPC through `solvers.solve`.
  A is the 3 x 3 block of the three cables with the best-conditioned minor (the thesis
  takes cables 1-3; any invertible choice gives the same problem). Variables and
  objective are scaled by t_max so that the penalty parameters of Appendix B fit.
* ``osqp``, ``clarabel``: l2 (QP) and l1 (LP) through cvxpy (`solvers.convex`).
* ``highs`` (cvxpy), ``linprog`` (SciPy HiGHS): l1 (LP).
"""

from __future__ import annotations

import itertools

import numpy as np

from ._distribution import min_norm

__all__ = ["BACKENDS", "solve_pointwise", "lfopc_l2"]

BACKENDS = ("lfopc", "osqp", "clarabel", "highs", "linprog")
_SUPPORTS = {
    "lfopc": ("l2",),
    "osqp": ("l2", "l1", "l1-max"),
    "clarabel": ("l2", "l1", "l1-max"),
    "highs": ("l1", "l1-max"),
    "linprog": ("l1", "l1-max"),
}


def lfopc_l2(S: np.ndarray, w: np.ndarray, t_min: float, t_max: float, feas_tol: float = 1e-6):
    """Problem (6.17) for one pose with the in-house LFOPC; (t or None, Result).

    Feasible iff LFOPC's final point violates no tension bound by more than
    ``feas_tol * t_max`` (LFOPC is a penalty method and returns a compromise point when
    the problem is infeasible, Appendix B).
    """
    from problems import Problem
    from solvers import solve

    n = S.shape[1]
    # A: the three cables with the largest |det| minor (well-conditioned t^A(t^B), eq. 6.16)
    best = max(itertools.combinations(range(n), 3), key=lambda F: abs(np.linalg.det(S[:, list(F)])))
    Acols, Bcols = list(best), [c for c in range(n) if c not in best]
    Ainv = np.linalg.inv(S[:, Acols])
    M = -Ainv @ w                    # eq. (6.19): M = -A^{-1} f^P
    N = -Ainv @ S[:, Bcols]          # N = -A^{-1} B
    s = t_max                        # scale: x = t^B / t_max

    def tensions(x):
        t = np.empty(n)
        t[Bcols] = s * x
        t[Acols] = M + N @ (s * x)
        return t

    def f(x):
        return float(np.sum((tensions(x) / s) ** 2))

    def grad(x):  # f = ||x||^2 + ||u_A||^2 with u_A = t^A / t_max = M / s + N x
        return 2.0 * (x + N.T @ ((M + N @ (s * x)) / s))

    def g(x):  # t_min <= t^A, t^A <= t_max, t_min <= t^B <= t_max, all scaled
        tA = M + N @ (s * x)
        return np.concatenate([(t_min - tA) / s, (tA - t_max) / s, t_min / s - x, x - t_max / s])

    nb = len(Bcols)
    jac = np.vstack([-N, N, -np.eye(nb), np.eye(nb)])
    tp = min_norm(S[None], w[None])[0]
    x0 = np.clip(tp[Bcols], t_min, t_max) / s
    prob = Problem("cable-l2", x0, f, gradient=grad, ineq=g, ineq_jacobian=lambda x: jac,
                   source="thesis eq. (6.17)")
    res = solve(prob, "lfopc")
    t = tensions(res.x)
    viol = max(0.0, float(np.max(t_min - t)), float(np.max(t - t_max)))
    return (t if viol <= feas_tol * t_max else None), res


def solve_pointwise(S: np.ndarray, w: np.ndarray, t_min: float, t_max: float, method: str,
                    backend: str) -> tuple[np.ndarray, np.ndarray]:
    """Tensions for k poses by solving one optimization problem per pose.

    Returns (feasible (k,), T (k, n) with NaN rows where infeasible). Poses where the
    backend cannot decide (status without a verdict) count as infeasible.
    """
    from solvers.convex import solve_lp, solve_qp

    if backend not in BACKENDS:
        raise ValueError(f"unknown tension backend {backend!r}; valid: {', '.join(BACKENDS)}")
    if method == "min-norm":
        raise ValueError("min-norm tensions (6.14) are closed-form; use backend='exact'")
    if method not in _SUPPORTS[backend]:
        raise ValueError(f"backend {backend!r} solves {', '.join(_SUPPORTS[backend])} tensions, not {method!r}"
                         + (" (maximizing a convex norm is not a convex problem)" if method == "l2-max" else ""))
    k, _, n = S.shape
    feas = np.zeros(k, dtype=bool)
    T = np.full((k, n), np.nan)
    sign = -1.0 if method == "l1-max" else 1.0
    for i in range(k):
        if not np.all(np.isfinite(S[i])):
            continue
        if backend == "lfopc":
            t, _ = lfopc_l2(S[i], w[i], t_min, t_max)
            ok = t is not None
        elif method == "l2":
            r = solve_qp(S[i], -w[i], t_min, t_max, backend=backend)
            ok, t = bool(r.feasible) and r.x is not None, r.x
        else:
            r = solve_lp(sign * np.ones(n), S[i], -w[i], t_min, t_max, backend=backend)
            ok, t = bool(r.feasible) and r.x is not None, r.x
        if ok:
            feas[i], T[i] = True, t
    return feas, T
