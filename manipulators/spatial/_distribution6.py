"""Cable-tension distribution for spatial robots (6 x m structure matrices), vectorized.

The planar closed forms of `manipulators.cable._distribution` carried to six dimensions:
tensions t solve S t + w = 0 (eq. 6.11 with a 6-D wrench) within t_min <= t_i <= t_max
(6.21). For the small redundancy r = m - 6 of practical cable robots the feasible set is
a bounded polytope of dimension r, and a linear objective (the l1 norm (6.19) of the
positive tensions) is minimal at one of its vertices. A vertex is a basic solution:
r cables at a bound and 6 cables with independent columns solved from S (the
generalization of Algorithm 6.1's interval ends). Enumerating the C(m, 6) 2^r basic
solutions, vectorized over poses, gives feasibility and the exact l1 optimum with no
iterative solver. The minimum-norm solution -S^+ w (6.14) is also given here; the
constrained l2 problem (6.17) is a QP solved per pose (`SpatialCableRobot.tensions`).
"""

from __future__ import annotations

import itertools
from functools import lru_cache

import numpy as np

__all__ = ["basic_solutions", "distribute6", "min_norm6", "SINGULAR_TOL", "VECTOR_METHODS"]

#: |det| of a 6 x 6 minor, relative to the product of its column norms, below which the
#: minor is treated as singular.
SINGULAR_TOL = 1e-12

#: Methods with a vectorized exact path.
VECTOR_METHODS = ("min-norm", "l1")


@lru_cache(maxsize=16)
def _bases(m: int) -> tuple[tuple[tuple[int, ...], ...], np.ndarray]:
    """(free 6-subsets, bound patterns (2^r, r) of 0 = t_min / 1 = t_max) for m cables."""
    free = tuple(itertools.combinations(range(m), 6))
    patterns = np.array(list(itertools.product((0, 1), repeat=m - 6)), dtype=int).reshape(-1, m - 6)
    return free, patterns


def min_norm6(S: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Minimum-norm tensions t = -S^+ w, eq. (6.14), for stacks S (k, 6, m), w (k, 6)."""
    return -np.einsum("kmi,ki->km", np.linalg.pinv(S), w)


def basic_solutions(S: np.ndarray, w: np.ndarray, t_min: float, t_max: float, tol: float = 1e-10):
    """Every basic solution of S t + w = 0 with m - 6 cables at a bound; vectorized over poses.

    Parameters
    ----------
    S : (k, 6, m) structure matrices; w : (k, 6) external wrenches.

    Returns
    -------
    T : (k, V, m) tensions of the basic solutions, V = C(m, 6) 2^(m-6)
    valid : (k, V) bool, True where the 6 free columns are independent and the free
        tensions meet their bounds to within ``tol``.
    """
    k, _, m = S.shape
    if m < 7:
        raise ValueError(f"spatial cable robot needs m >= 7 cables for redundancy; got m = {m}")
    free, patterns = _bases(m)
    bounds = np.array([t_min, t_max], dtype=float)
    tB = bounds[patterns]  # (P, r)
    P = len(patterns)
    T = np.empty((k, len(free) * P, m))
    valid = np.empty((k, len(free) * P), dtype=bool)
    for j, F in enumerate(free):
        B = [c for c in range(m) if c not in F]
        A = S[:, :, list(F)]
        scale = np.prod(np.linalg.norm(A, axis=1), axis=1)
        det = np.linalg.det(A)
        ok = np.abs(det) > SINGULAR_TOL * scale
        A = np.where(ok[:, None, None], A, np.eye(6))  # singular minors: solve a dummy system
        rhs = -w[:, :, None] - np.einsum("kib,pb->kip", S[:, :, B], tB)  # (k, 6, P)
        tF = np.linalg.solve(A, rhs)  # (k, 6, P)
        sl = slice(j * P, (j + 1) * P)
        T[:, sl][:, :, list(F)] = np.swapaxes(tF, 1, 2)
        T[:, sl][:, :, B] = tB[None]
        valid[:, sl] = ok[:, None] & np.all((tF >= t_min - tol) & (tF <= t_max + tol), axis=1)
    return T, valid


def distribute6(S: np.ndarray, w: np.ndarray, t_min: float, t_max: float, method: str = "l1",
                tol: float = 1e-10, need_tensions: bool = True, chunk: int = 4096):
    """Feasibility and tensions for k poses, exactly, by ``method`` in `VECTOR_METHODS`.

    Returns (feasible (k,), T (k, m) with NaN rows where infeasible, or None).
    Poses are processed ``chunk`` at a time to bound memory (V grows as C(m, 6) 2^(m-6)).
    """
    if method not in VECTOR_METHODS:
        raise ValueError(f"unknown vectorized tension method {method!r}; valid: {', '.join(VECTOR_METHODS)}")
    S = np.asarray(S, dtype=float)
    k, _, m = S.shape
    w = np.broadcast_to(np.asarray(w, dtype=float), (k, 6))
    if method == "min-norm":
        t = min_norm6(S, w)
        feas = np.all((t >= t_min - tol) & (t <= t_max + tol), axis=1)
        return feas, (np.where(feas[:, None], t, np.nan) if need_tensions else None)
    V = len(_bases(m)[0]) * 2 ** (m - 6)
    step = max(1, min(chunk, 2_000_000 // (V * m)))
    feas = np.empty(k, dtype=bool)
    out = np.full((k, m), np.nan) if need_tensions else None
    for s in range(0, k, step):
        T, valid = basic_solutions(S[s:s + step], w[s:s + step], t_min, t_max, tol)
        f = valid.any(axis=1)
        feas[s:s + step] = f
        if need_tensions:
            score = np.where(valid, T.sum(axis=2), np.inf)
            best = T[np.arange(T.shape[0]), np.argmin(score, axis=1)]
            # clip rounding-level excursions of the free tensions back onto the bounds
            out[s:s + step] = np.where(f[:, None], np.clip(best, t_min, t_max), np.nan)
    return feas, out
