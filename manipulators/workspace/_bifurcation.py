"""Exact bifurcation points: where two constraints are active at once (Appendix C.6, eq. 5.20).

Between two consecutive boundary points with different active constraints ``i`` and ``j``
the boundary has a corner where ``C_i(u) = C_j(u) = 0``. The thesis solves the
least-squares problem (5.20) with its optimizers; for smooth constraints this is a 2x2
nonlinear system, solved here by Newton's method from the two neighbouring points
(quadratic convergence, exact to round-off). For non-smooth (indicator) constraints the
corner is bracketed by bisection on the radius of a sub-chord from the earlier point: the
boundary point at radius rho has the first active constraint for rho below the corner
and the second above it. Smooth constraints whose Newton solve fails (tangent limits, a
cusp narrower than the chord) get no bifurcation point (counted in
``info["bifurcation_failures"]``).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["locate_corner", "newton_corner"]


def newton_corner(ev, p, q, i: int, j: int, *, d: float, tol: float,
                  jacobian: Callable[[np.ndarray], np.ndarray] | None = None,
                  max_iter: int = 30) -> np.ndarray | None:
    """Solve C_i(u) = C_j(u) = 0 by Newton from the midpoint of p and q.

    Returns the point, or None if Newton fails or the solution is not a feasible corner
    within reach of p and q.
    """
    u = 0.5 * (p + q)
    idx = [i, j]
    for _ in range(max_iter):
        if jacobian is None:
            h = 1e-7 * max(1.0, float(np.max(np.abs(u))))
            C = ev(np.array([u, u + (h, 0.0), u + (0.0, h)]))
            r = C[0, idx]
            J = ((C[1:, idx] - r) / h).T  # rows: constraints i, j; columns: d/dx, d/dy
        else:
            C = ev(u[None, :])
            r = C[0, idx]
            J = np.asarray(jacobian(u[None, :]), dtype=float)[0][idx, :]
        if np.max(np.abs(r)) <= 1e-3 * tol:
            break
        try:
            delta = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError:
            return None
        if not np.all(np.isfinite(delta)):
            return None
        nd = float(np.hypot(*delta))
        if nd > d:  # keep the iterate near the chord
            delta *= d / nd
        u = u + delta
        if nd <= 1e-3 * tol:
            C = ev(u[None, :])
            r = C[0, idx]
            break
    else:
        return None
    others = np.delete(C[0], idx)
    if np.max(np.abs(r)) > tol or (others.size and np.max(others) > tol):
        return None
    reach = 1.5 * d
    if np.hypot(*(u - p)) > reach or np.hypot(*(u - q)) > reach:
        return None
    return u


def bisect_corner(ev, p, i: int, *, d: float, tol: float, theta: float, smooth: bool,
                  n_refine: int, base: np.ndarray, chord_step) -> np.ndarray | None:
    """Corner between p (active i) and the next point, by bisection on the sub-chord radius."""
    # The point on the *first* constraint at radius rho_lo is within ~(rho_hi - rho_lo) of
    # the corner along that constraint; the one on the second at rho_hi is only within
    # ~sqrt(2 L (rho_hi - rho_lo)) (it moves along the other side), so p_lo is returned.
    lo, hi = 0.0, d
    p_lo = p
    for _ in range(200):
        if hi - lo <= tol:
            break
        mid = 0.5 * (lo + hi)
        step = chord_step(ev, p, theta, mid, base, tol, smooth, n_refine)
        if step is None:
            return None
        pt, jm = step
        if jm == i:
            lo, p_lo = mid, pt
        else:
            hi = mid
    return p_lo


def locate_corner(ev, p, q, i: int, j: int, *, d: float, tol: float, smooth: bool,
                  jacobian=None, theta: float, n_refine: int, base: np.ndarray,
                  chord_step) -> np.ndarray | None:
    """The bifurcation point between boundary points p (active i) and q (active j)."""
    if smooth:
        # Newton only: if it fails the constraints do not cross near here (a tangency or
        # a cusp narrower than the chord), and a bisected "corner" would not be one
        return newton_corner(ev, p, q, i, j, d=d, tol=tol, jacobian=jacobian)
    return bisect_corner(ev, p, i, d=d, tol=tol, theta=theta, smooth=smooth, n_refine=n_refine,
                         base=base, chord_step=chord_step)
