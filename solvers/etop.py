"""ETOP: gradient-only conjugate gradients with an Euler-trapezium step selection.

RECONSTRUCTION.  The thesis (Section 4.4) says only that EtopC is the conjugate
gradient method made gradient-only (Snyman, Quaestiones Math. 8, 1985) "by exploiting a
step size selection procedure based on an Euler-trapezium integration scheme", with
Fletcher-Reeves or Polak-Ribiere directions (Polak-Ribiere used).  The 1985 paper was
not available; everything below follows our reconstruction in algorithms.md section 5.1
[OWN] and is labelled ``ETOPC-recon`` in results:

* along u^k the particle moves with lambda'' = -phi(lambda), phi(lambda) = grad f(x + lambda u)^T u;
  forward-Euler position steps of growing length h, gamma h, gamma^2 h, ... continue while
  phi < 0 (still accelerating downhill, kinetic energy rising);
* when phi changes sign the minimum along the line is bracketed; the zero of phi is
  found by linear interpolation (regula falsi on phi, a gradient-only line search)
  until |phi| <= eta |phi(0)|;
* the trapezium rule on phi gives the decrease of f along the move (a diagnostic: if it
  is not negative the direction is reset to steepest descent);
* directions: PR+ (or FR), restart every n iterations and whenever u^T grad f >= 0.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np

__all__ = ["EtopParams", "EtopResult", "etop"]


@dataclasses.dataclass(frozen=True)
class EtopParams:
    """Parameters of ETOP (algorithms.md section 5.1, all [OWN]).

    beta : "PR" (Polak-Ribiere, truncated at 0; the thesis's choice) or "FR".
    eps_g : stop when ||grad f|| <= eps_g.
    eps_x : stop when an accepted step is shorter than eps_x.
    h0 : first trial step length along the unit direction.
    gamma : growth factor of the trial steps while phi < 0.
    max_line : gradients per line search.
    eta : accept lambda* when |phi(lambda*)| <= eta |phi(0)|.
    max_steps : maximum number of gradient evaluations.
    max_step : largest step along one direction (inf = none).
    """

    beta: str = "PR"
    eps_g: float = 1e-5
    eps_x: float = 1e-8
    h0: float = 1.0
    gamma: float = 2.0
    max_line: int = 20
    eta: float = 0.1
    max_steps: int = 10_000
    max_step: float = math.inf

    def __post_init__(self) -> None:
        if self.beta not in ("PR", "FR"):
            raise ValueError(f"etop: beta must be 'PR' or 'FR', got {self.beta!r}")
        if not (self.h0 > 0 and math.isfinite(self.h0)):
            raise ValueError(f"etop: h0 must be a positive finite number, got {self.h0!r}")
        if not (self.gamma >= 1):
            raise ValueError(f"etop: gamma must be >= 1, got {self.gamma!r}")
        if not (0 < self.eta < 1):
            raise ValueError(f"etop: eta must lie in (0, 1), got {self.eta!r}")
        if self.eps_g < 0 or self.eps_x < 0:
            raise ValueError("etop: eps_g and eps_x must be >= 0")
        if not (isinstance(self.max_line, (int, np.integer)) and self.max_line >= 2):
            raise ValueError(f"etop: max_line must be an integer >= 2, got {self.max_line!r}")
        if not (isinstance(self.max_steps, (int, np.integer)) and self.max_steps >= 1):
            raise ValueError(f"etop: max_steps must be an integer >= 1, got {self.max_steps!r}")
        if not (self.max_step > 0):
            raise ValueError(f"etop: max_step must be > 0, got {self.max_step!r}")


@dataclasses.dataclass
class EtopResult:
    """``reason``: "eps_g", "eps_x", "max_steps" or "nonfinite"; ``ng``: gradients used."""

    x: np.ndarray
    ng: int
    reason: str
    grad_norm: float
    nit: int = 0
    n_restarts: int = 0


def _norm(v: np.ndarray) -> float:
    return math.sqrt(float(v @ v))


def etop(grad: Callable[[np.ndarray], np.ndarray], x0: np.ndarray, params: EtopParams = EtopParams(),
         stop: Callable[[np.ndarray], bool] | None = None) -> EtopResult:
    """Minimize with gradient-only conjugate gradients (reconstruction, see module docstring).

    ``stop(x) -> bool`` is an extra test at every accepted point (reason "stop").
    """
    P = params
    x = np.array(x0, dtype=float).reshape(-1)
    n = x.size
    g = np.asarray(grad(x), dtype=float).reshape(-1)
    ng = 1
    gnorm = _norm(g)
    if not math.isfinite(gnorm):
        return EtopResult(x, ng, "nonfinite", gnorm)
    u = -g
    h = P.h0
    k = restarts = since_restart = 0
    while True:
        if gnorm <= P.eps_g:
            return EtopResult(x, ng, "eps_g", gnorm, k, restarts)
        if ng >= P.max_steps:
            return EtopResult(x, ng, "max_steps", gnorm, k, restarts)
        unorm = _norm(u)
        uh = u / unorm
        phi0 = float(g @ uh)
        if phi0 >= 0.0:  # not a descent direction: steepest descent restart
            u, uh, phi0 = -g, -g / gnorm, -gnorm
            restarts += 1
            since_restart = 0
        budget = min(P.max_line, P.max_steps - ng)
        # Euler phase: growing steps while the particle still accelerates (phi < 0)
        lam_lo, phi_lo, g_lo = 0.0, phi0, g
        lam = min(h, P.max_step)
        step = lam
        used = 0
        lam_hi = None
        while used < budget:
            g_try = np.asarray(grad(x + lam * uh), dtype=float).reshape(-1)
            used += 1
            phi = float(g_try @ uh)
            if not math.isfinite(phi):
                lam_hi, phi_hi, g_hi = lam, math.inf, g_try  # treat as overshoot: shrink back
                break
            if phi >= 0.0:
                lam_hi, phi_hi, g_hi = lam, phi, g_try
                break
            lam_lo, phi_lo, g_lo = lam, phi, g_try
            if lam >= P.max_step:
                break
            step *= P.gamma
            lam = min(lam + step, P.max_step)
        lam_acc, g_acc, phi_acc = lam_lo, g_lo, phi_lo
        if lam_hi is not None:
            # Bracket [lam_lo, lam_hi]: zero of the linear interpolant of phi (regula falsi)
            lam_acc, g_acc, phi_acc = lam_hi, g_hi, phi_hi
            while used < budget:
                if math.isfinite(phi_hi):
                    t = lam_lo - phi_lo * (lam_hi - lam_lo) / (phi_hi - phi_lo)
                else:
                    t = 0.5 * (lam_lo + lam_hi)
                g_t = np.asarray(grad(x + t * uh), dtype=float).reshape(-1)
                used += 1
                phi_t = float(g_t @ uh)
                lam_acc, g_acc, phi_acc = t, g_t, phi_t
                if math.isfinite(phi_t) and abs(phi_t) <= P.eta * abs(phi0):
                    break
                if math.isfinite(phi_t) and phi_t < 0.0:
                    lam_lo, phi_lo, g_lo = t, phi_t, g_t
                else:
                    lam_hi, phi_hi, g_hi = t, phi_t, g_t
            if not math.isfinite(phi_acc):  # fall back to the last downhill point
                lam_acc, g_acc, phi_acc = lam_lo, g_lo, phi_lo
        ng += used
        if lam_acc <= 0.0:
            # no progress along u: restart from steepest descent with a smaller trial step
            if since_restart == 0:
                return EtopResult(x, ng, "eps_x", gnorm, k, restarts)
            u = -g
            h = 0.25 * h
            restarts += 1
            since_restart = 0
            continue
        # Trapezium estimate of the change in f along the move (diagnostic)
        dF = 0.5 * (phi0 + phi_acc) * lam_acc
        x = x + lam_acc * uh
        g_new = g_acc
        gn_new = _norm(g_new)
        if not math.isfinite(gn_new):
            return EtopResult(x, ng, "nonfinite", gn_new, k, restarts)
        k += 1
        since_restart += 1
        h = lam_acc
        if stop is not None and stop(x):
            return EtopResult(x, ng, "stop", gn_new, k, restarts)
        if lam_acc < P.eps_x:
            return EtopResult(x, ng, "eps_x", gn_new, k, restarts)
        # Conjugate direction (PR+ or FR), restarts every n iterations or on ascent
        if P.beta == "PR":
            beta = max(0.0, float(g_new @ (g_new - g)) / (gnorm * gnorm))
        else:
            beta = (gn_new * gn_new) / (gnorm * gnorm)
        u = -g_new + beta * u
        if since_restart >= n or dF >= 0.0 or float(u @ g_new) >= 0.0:
            u = -g_new
            restarts += 1
            since_restart = 0
        g, gnorm = g_new, gn_new
