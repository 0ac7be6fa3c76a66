"""Dynamic-Q's approximate subproblem P[i] (thesis eqs. 3.4-3.9) as a penalty form.

At the iterate x^i the functions are replaced by spherical quadratics

    f~(x)   = f(x^i)   + grad f(x^i)^T d   + a/2   ||d||^2,     d = x - x^i      (3.4, 3.5)
    g~_j(x) = g_j(x^i) + grad g_j(x^i)^T d + b_j/2 ||d||^2
    h~_k(x) = h_k(x^i) + grad h_k(x^i)^T d + c_k/2 ||d||^2

the simple bounds are kept exact (3.7) and the move limit
g_rho(x) = ||x - x^c||^2 - rho^2 <= 0 (3.8) is appended as the last inequality.  Only
gradients of the penalty function are formed (LFOPC is gradient-only); evaluating the
approximations costs a few small matrix-vector products and is not an oracle call.
"""

from __future__ import annotations

import numpy as np

from ._penalty import Active, PenaltyForm

__all__ = ["SphericalSubproblem", "two_point_curvature"]


def two_point_curvature(v_prev: np.ndarray, v: np.ndarray, grad: np.ndarray, dx: np.ndarray) -> np.ndarray:
    """Curvatures interpolating the values at x^{i-1} and x^i (eq. 3.6), vectorized.

    ``v_prev``, ``v``: values at x^{i-1} and x^i, shape (m,); ``grad``: gradients at x^i,
    shape (m, n); ``dx = x^{i-1} - x^i``.  Returns 2[v_prev - v - grad dx] / ||dx||^2.
    """
    return 2.0 * (v_prev - v - grad @ dx) / float(dx @ dx)


class SphericalSubproblem(PenaltyForm):
    """P[i] of eq. (3.9) for LFOPC.

    Parameters
    ----------
    xi : iterate x^i (expansion point)
    gf, a : gradient of f at x^i and its curvature
    g0, Jg, b : values, Jacobian (p, n) and curvatures of the inequalities
    h0, Jh, c : the same for the equalities
    lower, upper : exact bounds
    centre, rho : move-limit centre x^c and radius
    move_scale : factor on the move-limit function (1/(2 rho) normalizes its gradient on the sphere)
    """

    def __init__(self, xi, gf, a, g0, Jg, b, h0, Jh, c, lower, upper, centre, rho, move_scale=1.0):
        n = xi.size
        self.n = n
        self.xi, self.gf, self.a = xi, gf, float(a)
        self.g0, self.Jg, self.b = g0, Jg, b
        self.h0, self.Jh, self.c = h0, Jh, c
        self.centre, self.rho2 = centre, float(rho) ** 2
        self.ms = float(move_scale)  # the move limit is ms * (||x - x^c||^2 - rho^2)
        self._set_bounds(n, lower, upper)
        self.p, self.q = g0.size + 1, h0.size  # + move limit
        self._np = g0.size

    # approximations of the constraints (move limit last)
    def ineq(self, x: np.ndarray) -> np.ndarray:
        d = x - self.xi
        e = x - self.centre
        g = self.g0 + self.Jg @ d + 0.5 * self.b * float(d @ d)
        return np.append(g, self.ms * (float(e @ e) - self.rho2))

    def ineq_jac(self, x: np.ndarray) -> np.ndarray:
        d = x - self.xi
        return np.vstack([self.Jg + np.outer(self.b, d), (2.0 * self.ms) * (x - self.centre)])

    def eq(self, x: np.ndarray) -> np.ndarray:
        d = x - self.xi
        return self.h0 + self.Jh @ d + 0.5 * self.c * float(d @ d)

    def eq_jac(self, x: np.ndarray) -> np.ndarray:
        return self.Jh + np.outer(self.c, x - self.xi)

    def gradf(self, x: np.ndarray) -> np.ndarray:
        return self.gf + self.a * (x - self.xi)

    def grad_Q(self, x: np.ndarray, mu: float, active: Active | None = None) -> np.ndarray:
        """Penalty gradient without forming Jacobians: grad g~_j = grad g_j + b_j d."""
        two_mu = 2.0 * mu
        d = x - self.xi
        dd = float(d @ d)
        e = x - self.centre
        ms = self.ms
        gm = ms * (float(e @ e) - self.rho2)  # move limit
        if active is None:
            gr = self.gf + self.a * d
            if self._np:
                w = np.maximum(self.g0 + self.Jg @ d + 0.5 * self.b * dd, 0.0)
                if w.any():
                    gr = gr + two_mu * (self.Jg.T @ w + d * float(w @ self.b))
            if gm > 0.0:
                gr = gr + (2.0 * two_mu * gm * ms) * e
        else:
            gr = np.zeros(self.n)
            act, ext = active.ineq, active.exterior
            if self._np and (ext or act[:-1].any()):
                g = self.g0 + self.Jg @ d + 0.5 * self.b * dd
                w = np.where(act[:-1], g, np.maximum(g, 0.0) if ext else 0.0)
                if w.any():
                    gr = gr + two_mu * (self.Jg.T @ w + d * float(w @ self.b))
            if act[-1] or (ext and gm > 0.0):
                gr = gr + (2.0 * two_mu * gm * ms) * e
        if self.q:
            ht = self.h0 + self.Jh @ d + 0.5 * self.c * dd
            gr = gr + two_mu * (self.Jh.T @ ht + d * float(ht @ self.c))
        if self.has_bounds:
            gr = gr + self._bound_penalty_grad(x, two_mu, active)
        return gr
