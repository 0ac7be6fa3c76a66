"""SQSD: the spherical quadratic steepest descent method (thesis Algorithm 2.2)."""

from __future__ import annotations

import dataclasses

import numpy as np

from problems import Oracle

from ._base import AbstractSolver, option
from ._result import SolverOutput, Status

__all__ = ["SQSD"]

C_MIN = 1e-60  # Algorithm 2.2 step 3: replacement curvature when c_k < 0


@dataclasses.dataclass(frozen=True)
class SQSD(AbstractSolver):
    """Spherical quadratic steepest descent, Algorithm 2.2 exactly.

    Each iteration minimizes the spherical quadratic approximation
    f(x^{k-1}) + grad f^T (x - x^{k-1}) + c_{k-1}/2 ||x - x^{k-1}||^2 (eq. 2.3),
    limits the step to rho, and updates the curvature c_k by two-point interpolation
    (eq. 2.4). One N^fg per iteration: N^it = N^fg (Section 2.5).
    """

    name = "sqsd"
    summary = "Spherical quadratic steepest descent (thesis Algorithm 2.2)"
    family = "thesis"
    handles = frozenset()

    rho: float = option(
        1.0, "step limit; c_0 = ||grad f(x0)||/rho makes the first step of length rho", "Alg. 2.2, Table 2.1"
    )
    eps_g: float = option(1e-5, "stop when ||grad f|| < eps_g", "Alg. 2.2 step 1, Sec. 2.5")
    eps_x: float = option(1e-8, "stop when ||x^k - x^(k-1)|| < eps_x", "Alg. 2.2 step 2, Sec. 2.5")
    max_iter: int = option(200_000, "iteration cap (N^fg cap)", "Tables 2.1-2.2 (20000-100000 for SD/FR/PR)")

    def __post_init__(self) -> None:
        if not (self.rho > 0 and np.isfinite(self.rho)):
            raise ValueError(f"sqsd: rho must be a positive finite number, got {self.rho}")
        if self.eps_g < 0 or self.eps_x < 0:
            raise ValueError("sqsd: eps_g and eps_x must be >= 0")
        if self.max_iter < 1:
            raise ValueError("sqsd: max_iter must be >= 1")

    def minimize(self, oracle: Oracle) -> SolverOutput:
        x_prev = oracle.x0
        f_prev, g_prev = oracle.f_and_grad(x_prev)
        gnorm = float(np.linalg.norm(g_prev))
        c = gnorm / self.rho  # c_0
        for k in range(1, self.max_iter + 1):
            # Step 1: gradient test, then the minimizer of the spherical approximation
            if gnorm < self.eps_g:
                return SolverOutput(x_prev, Status.CONVERGED, "||grad f|| < eps_g", nit=k - 1)
            if c <= 0.0 or not np.isfinite(c):  # c_0 = 0 only if grad f = 0 (caught above)
                c = C_MIN
            step = -g_prev / c
            # Step 2: step limit rho (the text: x^k := x^(k-1) - rho grad f/||grad f||)
            slen = float(np.linalg.norm(step))
            if slen > self.rho:
                step = -self.rho * g_prev / gnorm
                slen = self.rho
            x = x_prev + step
            if slen < self.eps_x:
                return SolverOutput(x, Status.CONVERGED, "||x^k - x^(k-1)|| < eps_x", nit=k)
            # Step 3: evaluate and update the curvature by two-point interpolation (eq. 2.4)
            f, g = oracle.f_and_grad(x)
            d = x_prev - x
            dd = float(d @ d)
            c = 2.0 * (f_prev - f - float(g @ d)) / dd if dd > 0 else C_MIN
            if not (c >= 0.0):  # c_k < 0 (or NaN) -> 1e-60
                c = C_MIN
            x_prev, f_prev, g_prev = x, f, g
            gnorm = float(np.linalg.norm(g))
            if not np.isfinite(gnorm) or not np.isfinite(f):
                return SolverOutput(x, Status.FAILED, "non-finite function or gradient value", nit=k)
        return SolverOutput(x_prev, Status.MAX_ITER, f"max_iter = {self.max_iter} reached", nit=self.max_iter)
