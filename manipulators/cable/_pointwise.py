"""Cable tensions by an optimization solver, one pose at a time (thesis Section 6.3).

The thesis solves the constrained l2 problem (6.17) with LfopC at every pose; the
constrained l1 problem (6.19) is a linear program. These per-pose solvers are the
reference (and the thesis's own method) against which the closed forms of
`_distribution` are tested and timed:

* ``lfopc``: problem (6.17) with the in-house LFOPC through `solvers.solve`, as in the
  thesis (see `lfopc_l2` for why the tensions are not eliminated first). Variables and
  objective are scaled by t_max so that the penalty parameters of Appendix B fit.
* ``osqp``, ``clarabel``: l2 (QP) and l1 (LP) through cvxpy (`solvers.convex`).
* ``highs`` (cvxpy), ``linprog`` (SciPy HiGHS): l1 (LP).
"""

from __future__ import annotations

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

    Posed in all n tensions, scaled by t_max (x = t / t_max): minimize ||x||^2 subject to
    the equilibrium S x + w / t_max = 0 (equalities, rows whitened) and the bounds
    (inequalities). This
    is the thesis's problem (6.17) without the elimination t^A = M + N t^B (6.16). The
    elimination makes the objective anisotropic (Hessian 2 (I + N^T N)); LFOPC's phase-2
    projection of its penalty solution onto the active constraints (Appendix B) then
    leaves errors of order 1/mu_1 along them (~1e-3 tension units, measured), while with
    the isotropic objective of the full form the projection is exact.

    Feasible iff LFOPC's final point violates no bound by more than ``feas_tol * t_max``
    and equilibrium by more than ``feas_tol`` (LFOPC is a penalty method and returns a
    compromise point when the problem is infeasible, Appendix B).
    """
    from problems import Problem
    from solvers import solve

    n = S.shape[1]
    s = t_max
    lo, hi = t_min / s, t_max / s
    eye = np.eye(n)
    jac_g = np.vstack([-eye, eye])
    # equilibrium rows whitened, E = (S S^T)^{-1/2} S (orthonormal rows, same solution set):
    # near-singular poses otherwise get a soft penalty mu sigma^2 along S's weak direction
    lam, V = np.linalg.eigh(S @ S.T)
    Wh = (V / np.sqrt(np.maximum(lam, 1e-300))) @ V.T
    E, e = Wh @ S, Wh @ (w / s)
    x0 = np.clip(min_norm(S[None], w[None])[0], t_min, t_max) / s
    prob = Problem("cable-l2", x0, lambda x: float(x @ x), gradient=lambda x: 2.0 * x,
                   ineq=lambda x: np.concatenate([lo - x, x - hi]), ineq_jacobian=lambda x: jac_g,
                   eq=lambda x: E @ x + e, eq_jacobian=lambda x: E,
                   source="thesis eq. (6.17)")
    # phase 2 on the active constraints only (Appendix B, eq. B.7, as in the thesis): the
    # variant that keeps exterior penalties on inactive constraints in phase 2 was seen to
    # drift along the active constraint here (errors of several tension units).
    # mu1 = 1e5 (Appendix B: 1e4) [OWN]: with tensions near t_max the phase-1 offsets
    # lambda / (2 mu1) reach ~5e-4 (scaled) and flag nearly-active bounds as active (seen
    # for a bound inactive by 0.044); eps_g = 1e-7 for ~1e-6 accurate tensions.
    res = solve(prob, "lfopc", phase2_exterior=False, eps_g=1e-7, mu1=1e5)
    t = s * res.x
    viol = max(0.0, float(np.max(t_min - t)), float(np.max(t - t_max)))
    ok = viol <= feas_tol * t_max and float(np.max(np.abs(S @ t + w))) <= feas_tol * max(1.0, t_max)
    return (t if ok else None), res


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
