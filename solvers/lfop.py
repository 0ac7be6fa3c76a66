"""LFOP: Snyman's leap-frog dynamic trajectory method (thesis Appendix B.2-B.3).

A gradient-only core: `lfop(grad, x0, params)` follows the trajectory of a unit-mass
particle in the force field -grad f (eq. B.1) with the leap-frog scheme (eq. B.4),
removes kinetic energy whenever it falls ("interference", eq. B.5), and controls the
time step with the heuristics of the public implementations (LFOP1(b), Snyman 1983):
a step limit ``delta``, a magnification factor ``p`` and halving after ``m``
consecutive acceleration reversals at the step limit.  The thesis does not print these
heuristics; every choice is tagged with its source (see docs/thesis_solvers.md and the
specification, ``algorithms.md`` section 1):

[THESIS]  Appendix B of Hay (2003);
[CILIB]   ciren/cilib ``LFVelocityUpdate``/``LFDecorator`` (defaults, step structure);
[MLA3]    swantaan/ML_ass3 ``leapfrog.py`` (halving rule s >= m with /4, fixed anchor);
[OWN]     our choice where the sources are silent (switchable).

The core is used by LFOPC's three penalty phases (`solvers.lfopc`) and through them by
Dynamic-Q's subproblems; it never evaluates f.  The loop is written for small n with
scalar bookkeeping in Python floats, so one step costs a few NumPy vector operations
plus one call of ``grad``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np

__all__ = ["LfopParams", "LfopResult", "lfop"]

DT_MODES = ("fixed", "auto")
ANCHORS = ("moving", "fixed")


@dataclasses.dataclass(frozen=True)
class LfopParams:
    """Parameters of LFOP (algorithms.md section 1.2).

    Attributes
    ----------
    delta : maximum step length ||x^{k+1} - x^k|| [CILIB delta = 1; MLA3].
    dt0 : initial time step [CILIB 0.5; MLA3].
    m : consecutive acceleration reversals tolerated at the step limit before the time
        step is halved [CILIB, MLA3: 3].
    delta1 : increment of the magnification factor p [CILIB, MLA3 code: 0.001].
    j0 : interferences that keep a reduced velocity before it is zeroed [CILIB j = 2].
    eps_g : stop when ||grad|| <= eps_g [MLA3 1e-5].
    max_steps : maximum number of gradient evaluations [OWN].
    eps_x : stop when a step is shorter than eps_x (0 = off) [OWN].
    dt_mode : "fixed" (dt = dt0) [CILIB] or "auto" (dt = sqrt(delta/(5||a0||)),
        first step = delta/10) [RECALL, low confidence].
    interference_anchor : "moving" [CILIB] or "fixed" [MLA3], see algorithms.md 1.3 step 9.
    stiffness_guard : cap dt by the curvature seen along the last move [OWN, section 1.6].
    kappa_fac : guard target dt*sqrt(kappa) (applied when dt*sqrt(kappa) > 2*kappa_fac) [OWN].
    """

    delta: float = 1.0
    dt0: float = 0.5
    m: int = 3
    delta1: float = 0.001
    j0: int = 2
    eps_g: float = 1e-5
    max_steps: int = 10_000
    eps_x: float = 0.0
    dt_mode: str = "fixed"
    interference_anchor: str = "moving"
    stiffness_guard: bool = False
    kappa_fac: float = 0.5

    def __post_init__(self) -> None:
        for name in ("delta", "dt0", "kappa_fac"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"lfop: {name} must be a positive finite number, got {v!r}")
        for name in ("delta1", "eps_g", "eps_x"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and v >= 0):
                raise ValueError(f"lfop: {name} must be >= 0, got {v!r}")
        for name in ("m", "j0", "max_steps"):
            v = getattr(self, name)
            if not (isinstance(v, (int, np.integer)) and v >= 1):
                raise ValueError(f"lfop: {name} must be an integer >= 1, got {v!r}")
        if self.dt_mode not in DT_MODES:
            raise ValueError(f"lfop: dt_mode must be one of {DT_MODES}, got {self.dt_mode!r}")
        if self.interference_anchor not in ANCHORS:
            raise ValueError(f"lfop: interference_anchor must be one of {ANCHORS}, got {self.interference_anchor!r}")


@dataclasses.dataclass
class LfopResult:
    """Outcome of one LFOP run.

    ``reason`` is "eps_g", "eps_x", "max_steps" or "nonfinite"; ``ng`` counts the
    gradient evaluations of this run; ``grad_norm`` is ||grad|| at ``x``.
    """

    x: np.ndarray
    ng: int
    reason: str
    grad_norm: float
    n_interferences: int = 0
    n_halvings: int = 0
    dt: float = float("nan")  # time step at the end of the run


def _norm(v: np.ndarray) -> float:
    return math.sqrt(v.dot(v))


_F64 = np.dtype(float)


def _vector(g: object) -> np.ndarray:
    """``g`` as a float vector; a float vector is passed through (the usual case, checked cheaply)."""
    if type(g) is np.ndarray and g.dtype is _F64 and g.ndim == 1:
        return g
    return np.asarray(g, dtype=float).reshape(-1)


def lfop(grad: Callable[[np.ndarray], np.ndarray], x0: np.ndarray, params: LfopParams = LfopParams(),
         dt_init: float | None = None, stop: Callable[[np.ndarray], bool] | None = None) -> LfopResult:
    """Minimize by the leap-frog dynamic trajectory method (algorithms.md section 1.3).

    Parameters
    ----------
    grad : callable ``grad(x) -> (n,)``
        Gradient of the function to minimize (for LFOPC: of the penalty function Q).
    x0 : array_like, shape (n,)
    params : LfopParams
    dt_init : float, optional
        Initial time step overriding ``params.dt0``/``dt_mode`` (LFOPC passes the
        step reached in the previous penalty phase).
    stop : callable ``stop(x) -> bool``, optional
        Extra test at every new gradient point (LFOPC's phase 2 passes "all active
        constraints satisfied to phase2_tol"); ends the run with reason "stop".

    Returns
    -------
    LfopResult
        The final point is the last point at which ``grad`` was evaluated (never a
        "best" point: LFOP knows no function values, section 1.5 f).
    """
    P = params
    x = np.array(x0, dtype=float).reshape(-1)
    a = -np.asarray(grad(x), dtype=float).reshape(-1)
    ng = 1
    anorm = _norm(a)
    if not math.isfinite(anorm):
        return LfopResult(x, ng, "nonfinite", anorm)
    if anorm <= P.eps_g:  # section 1.5 c: stationary start
        return LfopResult(x, ng, "eps_g", anorm)
    if dt_init is not None and math.isfinite(dt_init) and dt_init > 0:
        dt = float(dt_init)
    else:
        dt = P.dt0 if P.dt_mode == "fixed" else math.sqrt(P.delta / (5.0 * anorm))
    v = 0.5 * a * dt  # v^0 = a^0 dt / 2  (eq. B.4)
    x_prev = x
    v_prev = v
    x_a = x  # where the current acceleration a was evaluated (for the stiffness guard)
    i = 0  # consecutive interferences
    j = P.j0
    s = 0  # consecutive acceleration reversals
    p = 1.0  # magnification factor
    n_int = n_half = 0
    delta, delta1, m = P.delta, P.delta1, P.m
    guard, kfac, eps_g, eps_x = P.stiffness_guard, P.kappa_fac, P.eps_g, P.eps_x
    moving = P.interference_anchor == "moving"
    last = (x, anorm)
    vv = None  # v @ v of the current v where already computed (each dot product is formed once)
    while True:
        # Steps 2-4: step length, magnification below the limit, cap (and halving) at it
        if vv is None:
            vv = float(v.dot(v))
        vnorm = math.sqrt(vv)
        if vnorm * dt < delta:
            p += delta1
            dt *= p
        else:
            v = v * (delta / (dt * vnorm))
            vv = None
            if s >= m:  # m consecutive reversals at the step limit: halve dt [MLA3]
                dt *= 0.5
                x = 0.5 * (x + x_prev)
                v = 0.25 * (v + v_prev)
                s = 0
                n_half += 1
        # Step 5: move
        x_prev = x
        x = x + v * dt
        if eps_x > 0.0 and _norm(x - x_prev) < eps_x:
            g = np.asarray(grad(x), dtype=float).reshape(-1)
            return LfopResult(x, ng + 1, "eps_x", _norm(g), n_int, n_half, dt)
        while True:
            # Step 6: kick
            a_new = -_vector(grad(x))
            ng += 1
            v_prev = v
            vv_prev = float(v.dot(v)) if vv is None else vv
            v = v + a_new * dt
            # Step 7: acceleration reversal counter
            if a_new.dot(a) > 0.0:
                s = 0
            else:
                s += 1
                p = 1.0
            if guard:
                # Section 1.6 [OWN]: curvature along the last move from two known gradients;
                # keep dt well inside the leap-frog stability limit dt*sqrt(kappa) < 2.
                dx = x - x_a
                dxx = float(dx.dot(dx))
                if dxx > 0.0:
                    kappa = -float((a_new - a).dot(dx)) / dxx
                    if kappa > 0.0 and dt * math.sqrt(kappa) > 2.0 * kfac:
                        dt = kfac / math.sqrt(kappa)
                        p = 1.0
            a = a_new
            x_a = x
            anorm = math.sqrt(a.dot(a))
            # Step 8: termination
            if not math.isfinite(anorm):
                return LfopResult(last[0], ng, "nonfinite", last[1], n_int, n_half, dt)
            last = (x, anorm)
            if anorm <= eps_g:
                return LfopResult(x, ng, "eps_g", anorm, n_int, n_half, dt)
            if stop is not None and ng % 8 == 0 and stop(x):  # every 8th point: the test costs a step
                return LfopResult(x, ng, "stop", anorm, n_int, n_half, dt)
            if ng >= P.max_steps:
                return LfopResult(x, ng, "max_steps", anorm, n_int, n_half, dt)
            # Step 9: energy test; interference when kinetic energy does not grow (eq. B.5)
            vv = float(v.dot(v))
            if vv > vv_prev:
                i = 0
                break
            n_int += 1
            x_mid = 0.5 * (x + x_prev)
            if moving:
                x_prev = x
            x = x_mid
            i += 1
            vv = None
            if i <= j:
                v = 0.25 * (v + v_prev)
            else:
                v = np.zeros_like(v)
                j = 1
