"""Cable-tension distribution for spatial robots (6 x m structure matrices), vectorized.

The planar closed forms of `manipulators.cable._distribution` carried to six dimensions:
tensions t solve S t + w = 0 (eq. 6.11 with a 6-D wrench) within t_min <= t_i <= t_max
(6.21). For the small redundancy r = m - 6 of practical cable robots the feasible set is
a bounded polytope of dimension r, and a linear objective (the l1 norm (6.19) of the
positive tensions) is minimal at one of its vertices. A vertex is a basic solution:
r cables at a bound and 6 cables with independent columns solved from S (the
generalization of Algorithm 6.1's interval ends), found in the null-space form
t = t^p + N lambda as r x r systems. Enumerating the C(m, 6) 2^r basic
solutions, vectorized over poses, gives feasibility and the exact l1 optimum with no
iterative solver. The minimum-norm solution -S^+ w (6.14) is also given here; the
constrained l2 problem (6.17) is a QP solved per pose (`SpatialCableRobot.tensions`).
"""

from __future__ import annotations

import itertools
from functools import lru_cache

import numpy as np

__all__ = ["basic_solutions", "distribute6", "null_space_form", "min_norm6", "full_rank6", "SINGULAR_TOL",
           "VECTOR_METHODS"]

#: |det| of a 6 x 6 minor, relative to the product of its column norms, below which the
#: minor is treated as singular.
SINGULAR_TOL = 1e-12

#: Methods with a vectorized exact path.
VECTOR_METHODS = ("min-norm", "l1")


@lru_cache(maxsize=16)
def _bases(m: int) -> tuple[tuple[tuple[int, ...], ...], np.ndarray]:
    """(r-subsets of cables at a bound, patterns (2^r, r) of 0 = t_min / 1 = t_max), r = m - 6."""
    free = tuple(itertools.combinations(range(m), m - 6))
    patterns = np.array(list(itertools.product((0, 1), repeat=m - 6)), dtype=int).reshape(-1, m - 6)
    return free, patterns


def min_norm6(S: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Minimum-norm tensions t = -S^+ w, eq. (6.14), for stacks S (k, 6, m), w (k, 6)."""
    return -np.einsum("kmi,ki->km", np.linalg.pinv(S), w)


def _rank_test(R6: np.ndarray) -> np.ndarray:
    """Full rank from the triangular factor R6 (k, 6, 6) of S^T: min |R_ii| / max |R_ii| > SINGULAR_TOL."""
    d = np.abs(np.diagonal(R6, axis1=1, axis2=2))
    return d.min(axis=1) > SINGULAR_TOL * d.max(axis=1)


def full_rank6(S: np.ndarray) -> np.ndarray:
    """(k,) True where the structure matrix S (k, 6, m) has rank 6, by the test of `null_space_form`."""
    R = np.asarray(np.linalg.qr(np.swapaxes(S, 1, 2), mode="r"))  # (k, 6, 6) for m >= 6 cables
    return _rank_test(R[:, :6, :])


def null_space_form(S: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """All solutions of S t + w = 0 as t = t^p + N lambda, from one batched QR of S^T.

    Returns t^p (k, m) = -S^+ w (eq. 6.14), an orthonormal null-space basis N (k, m, r) and
    a mask (k,) of full-rank S (min |R_ii| / max |R_ii| > SINGULAR_TOL, R from S^T = Q R).
    This is the 6-D form of the thesis's parametrization t^A = M + N t^B (6.16), without
    needing an invertible A. (QR is ~4x faster than an SVD for these small stacks.)
    """
    Q, R = np.linalg.qr(np.swapaxes(S, 1, 2), mode="complete")  # Q (k, m, m), R (k, m, 6)
    R6 = R[:, :6, :]
    full = _rank_test(R6)
    safe = np.where(full[:, None, None], R6, np.eye(6))
    # S = R6^T Q1^T, so the minimum-norm solution is t^p = Q1 y with R6^T y = -w
    y = np.linalg.solve(np.swapaxes(safe, 1, 2), -w[..., None])[..., 0]
    tp = np.einsum("kmj,kj->km", Q[:, :, :6], y)
    tp[~full] = np.nan
    return tp, Q[:, :, 6:], full


def _solve_small(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve stacks A (k, r, r) x = b (k, P, r) (Cramer for r <= 2); (x (k, P, r), det (k,)).

    Where |det| <= `SINGULAR_TOL` the system is solved with det replaced by 1 (r <= 2) or A by
    the identity: finite values the callers mask out by det, never inf or NaN.
    """
    r = A.shape[-1]
    if r == 1:
        det = A[:, 0, 0]
        return b / _nonsingular(det)[:, None, None], det
    if r == 2:
        a, bb, c, d = A[:, 0, 0], A[:, 0, 1], A[:, 1, 0], A[:, 1, 1]
        det = a * d - bb * c
        div = _nonsingular(det)[:, None]
        x0 = (d[:, None] * b[..., 0] - bb[:, None] * b[..., 1]) / div
        x1 = (a[:, None] * b[..., 1] - c[:, None] * b[..., 0]) / div
        return np.stack([x0, x1], axis=-1), det
    det = np.linalg.det(A)
    safe = np.where((np.abs(det) > SINGULAR_TOL)[:, None, None], A, np.eye(r))
    x = np.linalg.solve(safe[:, None], b[..., None])[..., 0]
    return x, det


def _nonsingular(det: np.ndarray) -> np.ndarray:
    """det where |det| > `SINGULAR_TOL`, else 1."""
    return np.where(np.abs(det) > SINGULAR_TOL, det, 1.0)


def basic_solutions(S: np.ndarray, w: np.ndarray, t_min: float, t_max: float, tol: float = 1e-10):
    """Every basic solution of S t + w = 0 with r = m - 6 cables at a bound; vectorized over poses.

    In the null-space form t = t^p + N lambda the feasible tensions are an r-dimensional
    polytope in lambda, and its vertices are where r cable bounds are active: r x r
    systems N_B lambda = t_B - t^p_B (the 6-D generalization of the interval ends of
    Algorithm 6.1, which is the case r = 1).

    Parameters
    ----------
    S : (k, 6, m) structure matrices; w : (k, 6) external wrenches.

    Returns
    -------
    T : (k, V, m) tensions of the basic solutions, V = C(m, r) 2^r
    valid : (k, V) bool, True where S has rank 6, the r bound cables' rows of N are
        independent and all tensions meet their bounds to within ``tol``.
    """
    k, _, m = S.shape
    if m < 7:
        raise ValueError(f"spatial cable robot needs m >= 7 cables for redundancy; got m = {m}")
    tp, N, full = null_space_form(S, w)
    subsets, patterns = _bases(m)
    bounds = np.array([t_min, t_max], dtype=float)
    tB = bounds[patterns]  # (P, r)
    P = len(patterns)
    mid, half = 0.5 * (t_min + t_max), 0.5 * (t_max - t_min) + tol
    T = np.empty((k, len(subsets) * P, m))
    valid = np.empty((k, len(subsets) * P), dtype=bool)
    for j, B in enumerate(subsets):
        Bl = list(B)
        lam, det = _solve_small(N[:, Bl, :], tB[None] - tp[:, None, Bl])  # (k, P, r)
        sl = slice(j * P, (j + 1) * P)
        Tj = T[:, sl]
        np.multiply(lam[:, :, None, 0], N[:, None, :, 0], out=Tj)  # tp + N lambda, term by term
        Tj += tp[:, None, :]
        for q in range(1, lam.shape[2]):
            Tj += lam[:, :, None, q] * N[:, None, :, q]
        Tj[:, :, Bl] = tB[None]  # exactly at the bounds
        with np.errstate(invalid="ignore"):  # |t - mid| <= half-range: one pass for both bounds
            inside = np.all(np.abs(Tj - mid) <= half, axis=2)
        valid[:, sl] = (full & (np.abs(det) > SINGULAR_TOL))[:, None] & inside
    return T, valid


def _l1_search(tp, N, full, t_min, t_max, tol, need_tensions):
    """Feasibility and the l1-minimal basic solution without storing all V vertices.

    Loops over the C(m, r) bound subsets (vectorized over poses and the 2^r patterns),
    keeping per pose the best valid vertex found so far. Only the 6 free cables need a
    bound check; the r bound cables are at their bounds by construction.
    """
    k, m, r = N.shape
    subsets, patterns = _bases(m)
    bounds = np.array([t_min, t_max], dtype=float)
    tB = bounds[patterns]  # (P, r)
    sum_tB = tB.sum(axis=1)  # (P,)
    mid, half = 0.5 * (t_min + t_max), 0.5 * (t_max - t_min) + tol
    feas = np.zeros(k, dtype=bool)
    best = np.full(k, np.inf)
    best_lam = np.zeros((k, r))
    best_set = np.zeros(k, dtype=int)
    best_pat = np.zeros(k, dtype=int)
    for j, B in enumerate(subsets):
        Bl = list(B)
        F = [c for c in range(m) if c not in B]
        lam, det = _solve_small(N[:, Bl, :], tB[None] - tp[:, None, Bl])  # (k, P, r)
        Tf = tp[:, None, F] + lam[:, :, None, 0] * N[:, None, F, 0]
        for q in range(1, r):
            Tf += lam[:, :, None, q] * N[:, None, F, q]
        with np.errstate(invalid="ignore"):
            ok = np.all(np.abs(Tf - mid) <= half, axis=2) & (np.abs(det) > SINGULAR_TOL)[:, None]
        feas |= ok.any(axis=1)
        if not need_tensions:
            continue
        score = np.where(ok, Tf.sum(axis=2) + sum_tB, np.inf)  # (k, P)
        p = np.argmin(score, axis=1)
        sp = score[np.arange(k), p]
        better = sp < best
        best[better] = sp[better]
        best_lam[better] = lam[better, p[better]]
        best_set[better] = j
        best_pat[better] = p[better]
    feas &= full
    if not need_tensions:
        return feas, None
    T = tp + np.einsum("kmr,kr->km", N, best_lam)
    for j, B in enumerate(subsets):  # put the bound cables exactly on their bounds
        sel = feas & (best_set == j)
        if sel.any():
            T[np.ix_(np.flatnonzero(sel), list(B))] = tB[best_pat[sel]]
    # clip rounding-level excursions of the free tensions back onto the bounds
    return feas, np.where(feas[:, None], np.clip(T, t_min, t_max), np.nan)


def distribute6(S: np.ndarray, w: np.ndarray, t_min: float, t_max: float, method: str = "l1",
                tol: float = 1e-10, need_tensions: bool = True, chunk: int = 8192):
    """Feasibility and tensions for k poses, exactly, by ``method`` in `VECTOR_METHODS`.

    Returns (feasible (k,), T (k, m) with NaN rows where infeasible, or None).
    Poses are processed ``chunk`` at a time to bound memory.
    """
    if method not in VECTOR_METHODS:
        raise ValueError(f"unknown vectorized tension method {method!r}; valid: {', '.join(VECTOR_METHODS)}")
    S = np.asarray(S, dtype=float)
    if S.ndim != 3 or S.shape[1] != 6:
        raise ValueError(f"S must be a stack of 6 x m structure matrices (k, 6, m); got shape {S.shape}")
    k, _, m = S.shape
    if m < 7:
        raise ValueError(f"spatial cable robot needs m >= 7 cables for redundancy; got m = {m}")
    w = np.broadcast_to(np.asarray(w, dtype=float), (k, 6))
    if method == "min-norm":
        t = min_norm6(S, w)
        feas = np.all((t >= t_min - tol) & (t <= t_max + tol), axis=1)
        return feas, (np.where(feas[:, None], np.clip(t, t_min, t_max), np.nan) if need_tensions else None)
    P = 2 ** (m - 6)
    step = max(1, min(chunk, 1_000_000 // (P * 6)))
    feas = np.empty(k, dtype=bool)
    out = np.full((k, m), np.nan) if need_tensions else None
    for s in range(0, k, step):
        tp, N, full = null_space_form(S[s:s + step], w[s:s + step])
        f, T = _l1_search(tp, N, full, t_min, t_max, tol, need_tensions)
        feas[s:s + step] = f
        if out is not None:
            out[s:s + step] = T
    return feas, out
