"""Cable-tension distribution for many poses at once (thesis Section 6.3), in closed form.

Given structure matrices S (k, 3, n) and loads w (k, 3), the tensions t solve S t + w = 0
(6.11) within t_min <= t_i <= t_max (6.21). Everything here is vectorized over the k
poses and exact (no iterative solver):

* ``min_norm``: t^mn = -S^T (S S^T)^{-1} w (6.14); for n = 3 the unique t = -S^{-1} w (6.12).
* ``interval_4``: Algorithm 6.1 for n = 4. The thesis parametrizes the solutions by the
  fourth tension, t^A = M + N t^B (6.16) with M = -A^{-1} w, N = -A^{-1} B. Here the same
  one-parameter family is written t = t^p + lambda z with t^p the minimum-norm solution and
  z the null vector of S from its 3 x 3 minors (z_j = (-1)^j det S_{-j}); with z scaled so
  that z_4 = 1 this *is* the thesis's parametrization (N = z_{1:3}), but it needs no
  invertible A and so also holds where cables 1-3 alone are singular. Each cable bound gives
  an interval for lambda exactly as in Algorithm 6.1; their intersection [lam_lo, lam_hi]
  is non-empty iff feasible tensions exist.
* ``vertices``: any n >= 3. The feasible set {t : S t = -w, t_min <= t <= t_max} is a
  bounded polytope; a linear objective (the l1 norm (6.19) of positive tensions, or its
  maximum) is optimal at a vertex, and a vertex is a basic solution: n - 3 cables at a bound
  and 3 cables with independent columns solved from S. Enumerating the C(n, 3) 2^(n-3)
  basic solutions gives feasibility, the l1-minimal and l1-maximal tensions and the
  l2-maximal ("stiffest", Section 6.3.2) tensions exactly.
* ``distribute``: the method dispatcher used by `CableRobot` and the workspaces.
"""

from __future__ import annotations

import itertools

import numpy as np

__all__ = ["METHODS", "min_norm", "interval_4", "vertices", "distribute", "SINGULAR_TOL"]

#: Methods: minimum-norm (6.14), constrained l2 (6.17) and l1 (6.19) minima, and the
#: maximum-norm ("stiffest", Section 6.3.2 and 6.3.3) variants.
METHODS = ("min-norm", "l2", "l1", "l2-max", "l1-max")

#: |det| of a 3 x 3 minor (or |z|) below which the structure is treated as singular.
SINGULAR_TOL = 1e-12


def _solve3(M: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve stacks of 3 x 3 systems M x = rhs by the adjugate (Cramer), vectorized.

    M : (k, 3, 3); rhs : (k, 3) or (k, 3, r). Returns (x, det); x is NaN where det == 0.
    """
    a, b, c = M[:, 0, 0], M[:, 0, 1], M[:, 0, 2]
    d, e, f = M[:, 1, 0], M[:, 1, 1], M[:, 1, 2]
    g, h, i = M[:, 2, 0], M[:, 2, 1], M[:, 2, 2]
    adj = np.stack([
        np.stack([e * i - f * h, c * h - b * i, b * f - c * e], axis=-1),
        np.stack([f * g - d * i, a * i - c * g, c * d - a * f], axis=-1),
        np.stack([d * h - e * g, b * g - a * h, a * e - b * d], axis=-1),
    ], axis=1)
    det = a * adj[:, 0, 0] + b * adj[:, 1, 0] + c * adj[:, 2, 0]
    with np.errstate(invalid="ignore", divide="ignore"):
        if rhs.ndim == 2:
            x = np.einsum("kij,kj->ki", adj, rhs) / det[:, None]
        else:
            x = np.einsum("kij,kjr->kir", adj, rhs) / det[:, None, None]
    return x, det


def _rows(S: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The rows of S (k, 3, n) in the cable-major layout (n, k) of the fast path."""
    return S[:, 0, :].T, S[:, 1, :].T, S[:, 2, :].T


def _min_norm_rows(X, Y, M, w, refine: bool = True) -> np.ndarray:
    """t^mn = -S^T (S S^T)^{-1} w from the rows of S (each (n, k)), by the symmetric adjugate.

    Returns t in the cable-major layout (n, k).
    """
    G00, G01, G02 = (X * X).sum(0), (X * Y).sum(0), (X * M).sum(0)
    G11, G12, G22 = (Y * Y).sum(0), (Y * M).sum(0), (M * M).sum(0)
    A00, A01, A02 = G11 * G22 - G12 * G12, G02 * G12 - G01 * G22, G01 * G12 - G02 * G11
    A11, A12, A22 = G00 * G22 - G02 * G02, G01 * G02 - G00 * G12, G00 * G11 - G01 * G01
    with np.errstate(invalid="ignore", divide="ignore"):
        inv = 1.0 / (G00 * A00 + G01 * A01 + G02 * A02)

    def back(r0, r1, r2):  # t = -S^T G^{-1} r  (NaN where S is singular, silently)
        with np.errstate(invalid="ignore", over="ignore"):
            y0 = (A00 * r0 + A01 * r1 + A02 * r2) * inv
            y1 = (A01 * r0 + A11 * r1 + A12 * r2) * inv
            y2 = (A02 * r0 + A12 * r1 + A22 * r2) * inv
            return -(X * y0 + Y * y1 + M * y2)

    w0, w1, w2 = w[:, 0], w[:, 1], w[:, 2]
    t = back(w0, w1, w2)
    if refine:  # one step of iterative refinement on the residual S t + w
        with np.errstate(invalid="ignore", over="ignore"):
            r0, r1, r2 = (X * t).sum(0) + w0, (Y * t).sum(0) + w1, (M * t).sum(0) + w2
        t = t + back(r0, r1, r2)
    return t


def min_norm(S: np.ndarray, w: np.ndarray, refine: bool = True) -> np.ndarray:
    """Minimum-norm tensions t^mn = -S^+ w, eq. (6.14) (= -S^{-1} w for n = 3, eq. 6.12).

    One step of iterative refinement brings the equilibrium residual to rounding level
    even where S S^T is ill-conditioned. NaN rows where S has rank < 3.
    """
    k = S.shape[0]
    return _min_norm_rows(*_rows(S), np.broadcast_to(np.asarray(w, dtype=float), (k, 3)), refine).T


def _det_cols(X, Y, M, a: int, b: int, c: int) -> np.ndarray:
    """det[s_a, s_b, s_c] of three columns of S, from its rows (n, k)."""
    return (X[a] * (Y[b] * M[c] - M[b] * Y[c])
            - Y[a] * (X[b] * M[c] - M[b] * X[c])
            + M[a] * (X[b] * Y[c] - Y[b] * X[c]))


def _null4_rows(X, Y, M) -> np.ndarray:
    return np.stack([_det_cols(X, Y, M, 1, 2, 3), -_det_cols(X, Y, M, 0, 2, 3),
                     _det_cols(X, Y, M, 0, 1, 3), -_det_cols(X, Y, M, 0, 1, 2)], axis=0)


def interval_4(S: np.ndarray, w: np.ndarray, t_min: float, t_max: float, tol: float = 1e-10):
    """Algorithm 6.1 (tension limits) for n = 4, in null-space form; vectorized.

    Returns
    -------
    tp : (k, 4) minimum-norm particular solution
    z : (k, 4) null vector (unit length)
    lam_lo, lam_hi : (k,) the interval of the free parameter; feasible iff lam_lo <= lam_hi
        (and S has rank 3). Bounds are relaxed by ``tol`` so that points on the boundary
        count as feasible.
    """
    k = S.shape[0]
    tp, z, lo, hi = _interval4_rows(*_rows(S), np.broadcast_to(np.asarray(w, dtype=float), (k, 3)),
                                    t_min, t_max, tol)
    return tp.T, z.T, lo, hi


def _interval4_rows(X, Y, M, w, t_min, t_max, tol):
    """Algorithm 6.1 on the cable-major rows; tp, z are (4, k)."""
    z = _null4_rows(X, Y, M)
    zn = np.sqrt((z * z).sum(0))
    with np.errstate(invalid="ignore", divide="ignore"):
        z = z / zn
        tp = _min_norm_rows(X, Y, M, w)
        lo_b, hi_b = t_min - tol - tp, t_max + tol - tp  # bounds on lambda * z_i
        pos, neg = z > 0, z < 0
        # Algorithm 6.1: the sign of N_i (here z_i) decides which bound is the lower one
        r_lo, r_hi = lo_b / z, hi_b / z
        low = np.where(pos, r_lo, np.where(neg, r_hi, -np.inf))
        high = np.where(pos, r_hi, np.where(neg, r_lo, np.inf))
        # z_i = 0: cable i's tension does not move; it must already be within its bounds
        fixed_bad = ~(pos | neg) & ((lo_b > 0) | (hi_b < 0))
        lam_lo = low.max(0)
        lam_hi = high.min(0)
    bad = ~(zn > SINGULAR_TOL) | fixed_bad.any(0) | np.isnan(tp).any(0)
    lam_lo[bad] = np.inf
    lam_hi[bad] = -np.inf
    return tp, z, lam_lo, lam_hi


def _bases(n: int):
    """(free 3-subsets, list of bound patterns) of the basic solutions for n cables."""
    free = list(itertools.combinations(range(n), 3))
    patterns = np.array(list(itertools.product((0, 1), repeat=n - 3)), dtype=int).reshape(-1, n - 3)
    return free, patterns


def vertices(S: np.ndarray, w: np.ndarray, t_min: float, t_max: float, tol: float = 1e-10):
    """All basic solutions of S t + w = 0 with n - 3 cables at a bound; vectorized.

    Returns
    -------
    T : (k, V, n) tensions at each basic solution (V = C(n,3) 2^(n-3))
    valid : (k, V) bool, True where the basic solution exists and satisfies every bound
        to within ``tol``.
    """
    k, _, n = S.shape
    free, patterns = _bases(n)
    bounds = np.array([t_min, t_max])
    Ts, valid = [], []
    for F in free:
        B = [c for c in range(n) if c not in F]
        tB = bounds[patterns]  # (P, n-3)
        rhs = -w[:, :, None] - np.einsum("kib,pb->kip", S[:, :, B], tB)  # (k, 3, P)
        tF, det = _solve3(S[:, :, list(F)], rhs)
        T = np.empty((k, len(patterns), n))
        T[:, :, list(F)] = np.swapaxes(tF, 1, 2)
        T[:, :, B] = tB[None, :, :]
        ok = (np.abs(det) > SINGULAR_TOL)[:, None] & np.all(
            (tF >= t_min - tol) & (tF <= t_max + tol), axis=1)
        Ts.append(T)
        valid.append(ok)
    return np.concatenate(Ts, axis=1), np.concatenate(valid, axis=1)


def _pick(T: np.ndarray, valid: np.ndarray, score: np.ndarray, best: str):
    """Select per pose the valid vertex with the smallest or largest score."""
    fill = np.inf if best == "min" else -np.inf
    s = np.where(valid, score, fill)
    idx = np.argmin(s, axis=1) if best == "min" else np.argmax(s, axis=1)
    return T[np.arange(T.shape[0]), idx]


def distribute(S: np.ndarray, w: np.ndarray, t_min: float, t_max: float, method: str = "l1",
               tol: float = 1e-10, need_tensions: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
    """Feasibility and tensions for k poses by ``method`` (one of `METHODS`), exactly.

    ``l2`` is exact here for n <= 4 only (n = 3: the unique solution; n = 4: the
    one-variable QP min ||t^p + lambda z||^2 on [lam_lo, lam_hi], whose minimizer is the
    clamped lambda = 0 because t^p is orthogonal to z). For n >= 5 use a QP backend
    (`CableRobot.tensions(..., backend=...)`); feasibility alone (``need_tensions=False``)
    is exact for every method and n.

    Parameters
    ----------
    S : (k, 3, n) structure matrices, or a tuple (X, Y, M) of its rows in the
        cable-major layout, each (n, k) (as from `structure_rows`)
    w : (3,) or (k, 3) loads [f_x, f_y, tau]

    Returns
    -------
    feasible : (k,) bool
    T : (k, n) tensions (NaN rows where infeasible), or None if ``need_tensions`` is False.
    """
    if method not in METHODS:
        raise ValueError(f"unknown tension method {method!r}; valid: {', '.join(METHODS)}")
    X, Y, M = S if isinstance(S, tuple) else _rows(S)
    n, k = X.shape
    w = np.broadcast_to(np.asarray(w, dtype=float), (k, 3))
    lo_t, hi_t = t_min - tol, t_max + tol
    if method == "min-norm" or n == 3:
        t = _min_norm_rows(X, Y, M, w)
        if n == 3:  # unique solution (6.12): also require a non-singular S
            t[:, ~(np.abs(_det_cols(X, Y, M, 0, 1, 2)) > SINGULAR_TOL)] = np.nan
        feas = ((t >= lo_t) & (t <= hi_t)).all(0)
        return np.asarray(feas), (np.where(feas, t, np.nan).T if need_tensions else None)
    if n == 4:
        tp, z, lo, hi = _interval4_rows(X, Y, M, w, t_min, t_max, tol)
        feas = lo <= hi
        if not need_tensions:
            return feas, None
        if method == "l2":
            lam = np.clip(0.0, lo, hi)  # t^p is orthogonal to z, so lambda* = 0 before clamping
        elif method == "l2-max":  # convex objective: maximal at an end of the interval
            with np.errstate(invalid="ignore", over="ignore"):
                nlo = np.sum((tp + lo * z) ** 2, axis=0)
                nhi = np.sum((tp + hi * z) ** 2, axis=0)
            lam = np.where(nlo >= nhi, lo, hi)
        else:  # l1: linear in lambda, so an end of the interval (Algorithm 6.1 remark)
            slope = np.sum(z, axis=0)
            take_lo = slope >= 0 if method == "l1" else slope < 0
            lam = np.where(take_lo, lo, hi)
        # keep lambda inside the exact (un-relaxed) interval where that is non-empty, so that
        # returned tensions meet their bounds to rounding; otherwise (feasible only within
        # tol) take the middle of the relaxed interval
        _, _, lo0, hi0 = _interval4_rows(X, Y, M, w, t_min, t_max, 0.0)
        with np.errstate(invalid="ignore"):  # infeasible poses: inf - inf, masked below
            lam = np.where(lo0 <= hi0, np.clip(lam, lo0, hi0), 0.5 * (lo + hi))
            t = tp + lam * z
        return feas, np.where(feas, t, np.nan).T
    S3 = np.stack([X.T, Y.T, M.T], axis=1)
    T, valid = vertices(S3, w, t_min, t_max, tol)
    feas = np.any(valid, axis=1)
    if not need_tensions:
        return feas, None
    if method == "l2":
        raise NotImplementedError("exact vectorized l2 tensions exist for n <= 4 only; "
                                  "use a QP backend (osqp, clarabel, lfopc) for n >= 5")
    if method in ("l1", "l1-max"):
        t = _pick(T, valid, T.sum(axis=2), "min" if method == "l1" else "max")
    else:  # l2-max
        t = _pick(T, valid, np.sum(T**2, axis=2), "max")
    return feas, np.where(feas[:, None], t, np.nan)
