"""Dynamic-Q+'s subproblem: a spherical (one-curvature) convex QP with an elastic l1 penalty.

At the iterate x the subproblem in the step d is

    min  grad f^T d + sigma/2 ||d||^2 + mu (sum_j s_j + sum_k (t+_k + t-_k))
    s.t. g_j + grad g_j^T d <= s_j,   h_k + grad h_k^T d = t+_k - t-_k,   s, t+, t- >= 0
         max(lower - x, -rho) <= d <= min(upper - x, rho)

sigma (a scalar, or a diagonal: sum_i sigma_i d_i^2) is the curvature of the Lagrangian
(thesis eq. 3.6 applied to f + lambda^T g + nu^T h, our extension, see docs/thesis_solvers.md).
The elastic variables s, t make the QP
feasible whatever the move limit; when the linearized constraints can be met inside the box
and mu exceeds the multipliers, s = t = 0 and the step is the ordinary SQP step (Fletcher's
Sl1QP).  Solved exactly by Clarabel (interior point; dual variables give the multipliers).
When Clarabel fails on it (with mu near 1e10 it has reported the bounded QP dual infeasible),
the same QP with its objective divided by mu is solved once more.  When Clarabel ends on its
iteration cap (it can cycle when the slack costs dwarf f's gradient), the QP divided by
sqrt(mu) is solved once more (item 26); when the answer is still short of "Solved" (stalled
on an ill-conditioned model), once more with its static regularization at the curvature
floor (item 23).  Each retry keeps the step with the lower model, the QP's objective
(docs/thesis_solvers.md, Dynamic-Q+ items 23 and 26).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import clarabel
import numpy as np

__all__ = ["ElasticQPResult", "l1_model", "linearized_violations", "solve_elastic_qp"]

_sum = np.add.reduce  # ndarray.sum's reduction without its Python-level wrapper (the same floats)


@dataclass(slots=True)
class ElasticQPResult:
    """Step d, multipliers lam (ineq, >= 0) and nu (eq), the elastic slack total and the model value."""

    d: np.ndarray
    lam: np.ndarray
    nu: np.ndarray
    elastic: float
    model: float
    ok: bool
    status: str = "Solved"  # Clarabel's status (of the retry, when there was one)


def linearized_violations(d, g0, Jg, h0, Jh) -> tuple[float, float]:
    """(sum max(g + Jg d, 0), sum |h + Jh d|): the l1 infeasibility of the linearized
    inequality and equality constraints at step d."""
    return (float(_sum(np.maximum(g0 + Jg @ d, 0.0), axis=None)) if g0.size else 0.0,
            float(_sum(np.abs(h0 + Jh @ d), axis=None)) if h0.size else 0.0)


def l1_model(d, gf, sigma, g0, Jg, h0, Jh, mu) -> float:
    """Model of the l1 merit f + mu (sum max(g,0) + sum |h|) minus f(x), at step d."""
    v = float(gf @ d) + 0.5 * float(d @ _hess_times(sigma, d))
    ineq, eq = linearized_violations(d, g0, Jg, h0, Jh)
    if g0.size:
        v += mu * ineq
    if h0.size:
        v += mu * eq
    return v


def _hess_times(sigma, d: np.ndarray) -> np.ndarray:
    """The model Hessian (scalar, diagonal of shape (n,), or full matrix (n, n)) times d."""
    if type(sigma) is not np.ndarray:  # a float, or a list; an array is used as it is (one call fewer)
        sigma = np.asarray(sigma, dtype=float)
    return sigma @ d if sigma.ndim == 2 else sigma * d


@functools.cache
def _identity_blocks(n: int, p: int, q: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Positions and values of the +-1 entries of the constraint matrix below: -t+ and +t- in
    the equality rows, -s in the inequality rows, -I on the elastic rows, +I and -I on the box."""
    ne = p + 2 * q
    i_q, i_p, i_e, i_n = np.arange(q), np.arange(p), np.arange(ne), np.arange(n)
    rows = np.r_[i_q, i_q, q + i_p, q + p + i_e, q + p + ne + i_n, q + p + ne + n + i_n]
    cols = np.r_[n + p + i_q, n + p + q + i_q, n + i_p, n + i_e, i_n, i_n]
    vals = np.r_[-np.ones(q), np.ones(q), -np.ones(p), -np.ones(ne), np.ones(n), -np.ones(n)]
    return rows, cols, vals


#: [OWN] item 23: the static regularization of the retry, Dynamic-Q+'s curvature floor
#: (``sigma_min``); Clarabel's default, 1e-8, exceeds the smallest curvatures of the models
#: it stalls on.
LOW_REGULARIZATION = 1e-12


@functools.cache
def _settings(low_regularization: bool = False) -> clarabel.DefaultSettings:
    """Clarabel's settings (one cached object per flag; never mutate the one returned)."""
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    settings.tol_gap_abs = settings.tol_gap_rel = 1e-10
    settings.tol_feas = 1e-10
    if low_regularization:
        settings.static_regularization_constant = LOW_REGULARIZATION
    return settings


class _CscView:
    """The CSC arrays of a matrix, as Clarabel reads them (format, shape, data, indices,
    indptr).  scipy.sparse's constructor validates and re-types the index arrays on every
    call, which cost more than the interior-point solve of these small QPs; the arrays
    here are built canonical (sorted, int64, no duplicates) by `_csc`, so nothing needs
    checking.  A plain class with slots: a frozen dataclass's constructor alone cost a
    few microseconds per QP.  `tests/solvers/test_dynamic_q_plus.py` checks the view
    against ``scipy.sparse.csc_matrix``."""

    __slots__ = ("shape", "data", "indices", "indptr")
    format = "csc"
    has_sorted_indices = True
    has_canonical_format = True

    def __init__(self, shape: tuple[int, int], data: np.ndarray, indices: np.ndarray, indptr: np.ndarray) -> None:
        self.shape, self.data, self.indices, self.indptr = shape, data, indices, indptr

    @property
    def nnz(self) -> int:
        return int(np.size(self.data))

    def as_lists(self) -> _CscView:
        """The same matrix with its arrays as Python lists, the form Clarabel reads fastest."""
        return _CscView(self.shape, self.data.tolist(), self.indices.tolist(), self.indptr.tolist())


def _csc(dense: np.ndarray) -> _CscView:
    """The nonzeros of a dense matrix in CSC form, built with NumPy; the same arrays as
    ``scipy.sparse.csc_matrix(dense)``."""
    cols, rows = np.nonzero(dense.T)  # column-major: sorted by column, then row
    indptr = np.zeros(dense.shape[1] + 1, dtype=np.int64)
    np.cumsum(np.bincount(cols, minlength=dense.shape[1]), out=indptr[1:])
    return _CscView(dense.shape, np.ascontiguousarray(dense.T[cols, rows]), rows.astype(np.int64), indptr)


def _pattern_csc(shape: tuple[int, int], vals: np.ndarray, rows: np.ndarray, indptr: np.ndarray) -> _CscView:
    """CSC arrays of a matrix given by a fixed pattern (row indices ``rows`` in CSC order, its
    column pointers ``indptr``) and this call's values: the same arrays as ``_csc`` of the
    dense matrix, i.e. exact zeros dropped (only then are the column pointers recomputed)."""
    if np.count_nonzero(vals) == vals.size:  # the usual case: a quasi-Newton matrix and most Jacobians are dense
        return _CscView(shape, vals, rows, indptr)
    keep = vals != 0.0
    # the new column pointers are the running count of kept entries at the old ones
    kept = np.zeros(vals.size + 1, dtype=np.int64)
    np.add.accumulate(keep, dtype=np.int64, out=kept[1:])  # np.cumsum's ufunc, without its wrapper
    return _CscView(shape, vals[keep], rows[keep], kept[indptr])


def _pattern_of(dense: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(rows, cols, indptr) of the nonzero pattern of ``dense`` in CSC order."""
    view = _csc(dense)
    return view.indices, np.repeat(np.arange(dense.shape[1]), np.diff(view.indptr)), view.indptr


@functools.cache
def _hessian_pattern(n: int, nv: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pattern of the upper triangle of the n x n Hessian block of the nv x nv matrix P, and
    the flat indices of its entries in the n x n Hessian."""
    block = np.zeros((nv, nv))
    block[:n, :n] = np.triu(np.ones((n, n)))
    rows, cols, indptr = _pattern_of(block)
    return rows, indptr, rows * n + cols


@functools.cache
def _constraint_pattern(n: int, p: int, q: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pattern of the constraint matrix of `solve_elastic_qp` with dense Jacobians, and the
    values of its fixed +-1 entries (NaN where this call's Jacobian entries go).

    By column: j < n holds the q equality and p inequality Jacobian entries, then the box
    rows +1 and -1; the elastic columns hold only +-1 entries."""
    ne = p + 2 * q
    A = np.zeros((q + p + ne + 2 * n, n + ne))
    A[:q + p, :n] = np.nan  # nonzero, marks the Jacobian entries
    r, c, v = _identity_blocks(n, p, q)
    A[r, c] = v
    rows, cols, indptr = _pattern_of(A)
    return rows, indptr, A.T[cols, rows]


def _hessian_csc(sig: np.ndarray, n: int, nv: int) -> _CscView:
    """The upper triangle of the n x n model Hessian in the top-left of the nv x nv matrix P,
    in CSC form: the same arrays as ``_csc`` of that dense embedding."""
    rows, indptr, flat = _hessian_pattern(n, nv)
    return _pattern_csc((nv, nv), sig.take(flat), rows, indptr)


def _constraint_csc(Jg: np.ndarray, Jh: np.ndarray, n: int, p: int, q: int) -> _CscView:
    """The constraint matrix of `solve_elastic_qp` in CSC form: the same arrays as ``_csc``
    of its dense assembly, from the cached pattern."""
    rows, indptr, fixed = _constraint_pattern(n, p, q)
    vals = fixed.copy()
    # in column j < n the first q + p entries are Jh[:, j] then Jg[:, j], then the two box entries
    vals[:n * (q + p + 2)].reshape(n, q + p + 2)[:, :q + p] = (Jg if not q else Jh if not p
                                                              else np.concatenate((Jh, Jg))).T
    ne = p + 2 * q
    return _pattern_csc((q + p + ne + 2 * n, n + ne), vals, rows, indptr)


def solve_elastic_qp(gf: np.ndarray, sigma: float | np.ndarray, g0: np.ndarray, Jg: np.ndarray, h0: np.ndarray,
                     Jh: np.ndarray, d_lo: np.ndarray, d_up: np.ndarray, mu: float,
                     retry_stalled: bool = True) -> ElasticQPResult:
    """Solve the elastic QP above (box ``d_lo <= d <= d_up``; ``sigma`` a positive scalar,
    a positive diagonal of shape (n,) or a positive definite matrix of shape (n, n)).

    ``retry_stalled``: when Clarabel ends on its iteration cap (and mu > 1), solve once more
    divided by sqrt(mu); when the status is then still not "Solved", once more with the static
    regularization at `LOW_REGULARIZATION`; each time keep the usable step with the lower l1 model."""
    n, p, q = gf.size, g0.size, h0.size
    nv = n + p + 2 * q
    ne = p + 2 * q  # elastic variables s, t+, t-
    sig = np.asarray(sigma, dtype=float)
    if sig.ndim == 2:  # full (quasi-Newton) Hessian: Clarabel reads the upper triangle
        P = _hessian_csc(sig, n, nv)
    else:
        diag = np.broadcast_to(sig, (n,)).astype(float)
        P = _CscView((nv, nv), diag, np.arange(n, dtype=np.int64),
                     np.r_[np.arange(n + 1), np.full(ne, n)].astype(np.int64))
    # rows: equalities (ZeroCone), then inequalities, elastic >= 0, box (Nonnegative): A v + s = b.
    # Built in CSC form from cached index arrays: scipy's sparse stacking, and even a dense
    # assembly scanned for its nonzeros, cost more than the interior-point solve at these sizes.
    A_csc = _constraint_csc(Jg, Jh, n, p, q)
    m = A_csc.shape[0]
    b = (-h0).tolist() + (-g0).tolist() + [0.0] * ne + d_up.tolist() + (-d_lo).tolist()
    cones = ([clarabel.ZeroConeT(q)] if q else []) + [clarabel.NonnegativeConeT(m - q)]
    # Clarabel copies its inputs element by element; from Python lists that is a quarter faster
    # than from NumPy arrays (the same doubles, so the same solve)
    A_lists = A_csc.as_lists()
    P_lists, c = P.as_lists(), gf.tolist() + [float(mu)] * ne
    v, z, status, ok = _clarabel_solve(P_lists, c, A_lists, b, cones)
    if not ok and mu > 1.0:
        # [OWN] the same QP with its objective divided by mu (the same minimizer; the duals
        # scale by 1/mu): the slack costs become 1 instead of up to 1e10
        v, z, status, ok = _scaled_solve(P, gf, mu, ne, A_lists, b, cones, mu)
    d = np.minimum(np.maximum(v[:n], d_lo), d_up) if ok else np.zeros(n)  # np.clip, without its wrapper
    model = l1_model(d, gf, sigma, g0, Jg, h0, Jh, mu)
    if retry_stalled and status == "MaxIterations" and mu > 1.0:
        # [OWN] item 26: with a large weight the interior point can cycle until its iteration cap
        # far from the minimizer (one variable, mu = 1e6: model 0.90 where the minimizer's is
        # -0.03).  The QP divided by sqrt(mu) balances the slack costs against f's gradient; the
        # model is the QP's objective, so the lower one wins.
        v2, z2, status2, ok2 = _scaled_solve(P, gf, mu, ne, A_lists, b, cones, float(np.sqrt(mu)))
        if ok2:
            d2 = np.minimum(np.maximum(v2[:n], d_lo), d_up)
            model2 = l1_model(d2, gf, sigma, g0, Jg, h0, Jh, mu)
            if not ok or model2 < model:
                v, z, status, ok, d, model = v2, z2, status2, ok2, d2, model2
    if retry_stalled and status != "Solved":
        # [OWN] item 23: Clarabel's regularization (1e-8) above the model's smallest curvatures
        # stalls the interior point ("InsufficientProgress", "AlmostSolved") at a step far from
        # the QP's minimizer (BROWNBS: model -9.8e3 where the minimizer's is -9.2e4)
        v2, z2, status2, ok2 = _clarabel_solve(P_lists, c, A_lists, b, cones, low_regularization=True)
        if ok2:
            d2 = np.minimum(np.maximum(v2[:n], d_lo), d_up)
            model2 = l1_model(d2, gf, sigma, g0, Jg, h0, Jh, mu)
            if not ok or model2 < model:
                v, z, status, ok, d, model = v2, z2, status2, ok2, d2, model2
    nu = z[:q].copy() if ok else np.zeros(q)
    lam = np.maximum(z[q:q + p], 0.0) if ok else np.zeros(p)
    elastic = float(_sum(v[n:], axis=None)) if ok else 0.0
    return ElasticQPResult(d, lam, nu, elastic, model, ok, status)


def _scaled_solve(P: _CscView, gf: np.ndarray, mu: float, ne: int, A: _CscView, b: list[float], cones: list,
                  scale: float) -> tuple[np.ndarray, np.ndarray, str, bool]:
    """`_clarabel_solve` of the elastic QP with its objective divided by ``scale`` (the same
    minimizer); the duals are returned at the QP's own scale."""
    Ps = P.as_lists()
    Ps.data = (np.asarray(P.data, dtype=float) / scale).tolist()
    v, z, status, ok = _clarabel_solve(Ps, (gf / scale).tolist() + [mu / scale] * ne, A, b, cones)
    return v, z * scale, status, ok


def _clarabel_solve(P: _CscView, c: list[float], A: _CscView, b: list[float], cones: list,
                    low_regularization: bool = False) -> tuple[np.ndarray, np.ndarray, str, bool]:
    """Clarabel's primal and dual solutions, its status, and whether the step is usable."""
    sol = clarabel.DefaultSolver(P, c, A, b, cones, _settings(low_regularization)).solve()
    v = np.asarray(sol.x)
    z = np.asarray(sol.z)
    status = str(sol.status)
    # the elastic QP is always feasible and bounded: a stalled interior point (insufficient progress,
    # iteration cap) still returns a usable finite step; only non-finite output is a failure
    ok = status in ("Solved", "AlmostSolved") or (
        status in ("InsufficientProgress", "MaxIterations", "MaxTime", "AlmostPrimalInfeasible",
                   "AlmostDualInfeasible") and bool(np.all(np.isfinite(v)) and np.all(np.isfinite(z))))
    return v, z, status, ok
