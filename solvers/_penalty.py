"""The penalty form of a constrained problem and the three-phase scheme of LFOPC.

A *penalty form* is everything the gradient-only constrained methods (LFOPC, ETOPC)
need: the gradient of f, the values and gradients of the constraints g_j <= 0,
h_k = 0 and the simple bounds.  It never contains f itself.  From it we build

* the gradient of the exterior penalty function (thesis eq. B.6)
  Q(x, mu) = f + mu sum_{g_j > 0} g_j^2 + mu sum_k h_k^2  (bounds as inequalities),
* the gradient of the phase-2 function (eq. B.7) Q_a = mu1 (sum_{j in I_a} g_j^2 + sum_k h_k^2),
  where the active constraints are penalised on both sides.

`three_phase` runs any unconstrained gradient-only core (LFOP or ETOP) on the three
phases of Appendix B.4.  Three concrete forms exist: `PenaltyForm` (plain callables;
the public API, e.g. for small QPs), `OracleForm` (a problem behind the counting
oracle) and, in `solvers._spherical`, Dynamic-Q's spherical quadratic subproblem.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["Active", "PenaltyForm", "OracleForm", "PhaseRecord", "ThreePhaseResult", "three_phase"]

Core = Callable[..., Any]
_count_nonzero = np.count_nonzero
#: 0.0 as a read-only 0-d float64 array: np.maximum(v, _ZERO) is np.maximum(v, 0.0) (the same float64
#: loop on the same values) without NumPy converting a Python scalar on every call
_ZERO = np.zeros(())
_ZERO.setflags(write=False)


@dataclasses.dataclass(frozen=True)
class Active:
    """Constraints penalised in phase 2: boolean masks over g, lower and upper bounds.

    ``exterior``: the inactive inequalities and bounds keep their exterior penalty in
    phase 2 ([OWN]; eq. B.7 drops them, which lets phase 2 run off to a distant
    intersection of the active constraints when the subproblem is non-convex).
    """

    ineq: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    exterior: bool = True

    @property
    def count(self) -> int:
        return int(self.ineq.sum() + self.lower.sum() + self.upper.sum())


class _BoundsMixin:
    """Bounds l <= x <= u as the inequalities l - x <= 0, x - u <= 0 (eq. 3.7)."""

    lower: np.ndarray
    upper: np.ndarray
    has_bounds: bool

    def _set_bounds(self, n: int, lower: Any, upper: Any) -> None:
        lo = np.full(n, -np.inf) if lower is None else np.broadcast_to(np.asarray(lower, float), (n,)).copy()
        up = np.full(n, np.inf) if upper is None else np.broadcast_to(np.asarray(upper, float), (n,)).copy()
        if np.any(np.isnan(lo)) or np.any(np.isnan(up)) or np.any(lo > up):
            raise ValueError("penalty form: bounds must satisfy lower <= upper (no NaN)")
        self.lower, self.upper = lo, up
        self.has_bounds = bool(np.isfinite(lo).any() or np.isfinite(up).any())

    def _bound_penalty_grad(self, x: np.ndarray, two_mu: float, active: Active | None) -> np.ndarray:
        if active is None:  # exterior penalty: only violated bounds
            return two_mu * (np.minimum(x - self.lower, _ZERO) + np.maximum(x - self.upper, _ZERO))
        dl, du = x - self.lower, x - self.upper
        if active.exterior:
            lo = np.where(active.lower, dl, np.minimum(dl, _ZERO))
            up = np.where(active.upper, du, np.maximum(du, _ZERO))
        else:
            lo = np.where(active.lower, dl, _ZERO)
            up = np.where(active.upper, du, _ZERO)
        return two_mu * (np.where(np.isfinite(lo), lo, _ZERO) + np.where(np.isfinite(up), up, _ZERO))

    def _bound_active(self, x: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
        return (self.lower - x) > tol, (x - self.upper) > tol

    def _bound_violation(self, x: np.ndarray) -> float:
        if not self.has_bounds:
            return 0.0
        return max(float(np.max(self.lower - x)), float(np.max(x - self.upper)), 0.0)


def _weighted(w: np.ndarray, alpha: Any) -> np.ndarray:
    """w * alpha; one overall weight (alpha = 1.0, the default) leaves w as it is (exactly w * 1.0)."""
    return w if type(alpha) is float and alpha == 1.0 else w * alpha


class _FormPoint:
    """A penalty form's quantities at one point (the generic `PenaltyForm.at`)."""

    __slots__ = ("form", "x")

    def __init__(self, form: PenaltyForm, x: np.ndarray):
        self.form, self.x = form, x

    def grad(self) -> np.ndarray:
        return self.form.gradf(self.x)

    def ineq(self) -> np.ndarray:
        return self.form.ineq(self.x)

    def ineq_jac(self) -> np.ndarray:
        return self.form.ineq_jac(self.x)

    def eq(self) -> np.ndarray:
        return self.form.eq(self.x)

    def eq_jac(self) -> np.ndarray:
        return self.form.eq_jac(self.x)


class PenaltyForm(_BoundsMixin):
    """A constrained problem given by gradient-level callables (no objective value needed).

    Minimize f(x) s.t. ineq(x) <= 0, eq(x) = 0, lower <= x <= upper, where only
    ``grad_f`` is known of f.  Use it with `LFOPC.solve_form` or `ETOPC.solve_form`.

    Parameters
    ----------
    n : int
        Number of variables.
    grad_f : callable ``grad_f(x) -> (n,)``
    ineq, ineq_jac : callables ``(p,)`` and ``(p, n)``, optional
    eq, eq_jac : callables ``(q,)`` and ``(q, n)``, optional
    lower, upper : array_like or float, optional

    Examples
    --------
    Cable tensions (thesis eq. 6.17), min ||t||^2 s.t. S t = -w, t_min <= t <= t_max::

        form = PenaltyForm(n=S.shape[1], grad_f=lambda t: 2 * t,
                           eq=lambda t: S @ t + w, eq_jac=lambda t: S,
                           lower=t_min, upper=t_max)
        res = LFOPC().solve_form(form, x0=np.full(S.shape[1], t_min))  # from solvers.lfopc
        res.x, res.max_violation, res.ng
    """

    def __init__(self, n: int, grad_f: Callable[[np.ndarray], np.ndarray], *,
                 ineq: Callable | None = None, ineq_jac: Callable | None = None,
                 eq: Callable | None = None, eq_jac: Callable | None = None,
                 lower: Any = None, upper: Any = None, p: int | None = None, q: int | None = None):
        if not (isinstance(n, (int, np.integer)) and n >= 1):
            raise ValueError(f"PenaltyForm: n must be a positive integer, got {n!r}")
        if not callable(grad_f):
            raise ValueError("PenaltyForm: grad_f must be callable")
        if (ineq is None) != (ineq_jac is None) or (eq is None) != (eq_jac is None):
            raise ValueError("PenaltyForm: give each constraint function together with its Jacobian")
        self.n = int(n)
        self.grad_f, self._ineq, self._ineq_jac, self._eq, self._eq_jac = grad_f, ineq, ineq_jac, eq, eq_jac
        self._set_bounds(self.n, lower, upper)
        self.p = p if p is not None else (0 if ineq is None else -1)  # -1: learn at first call
        self.q = q if q is not None else (0 if eq is None else -1)
        # per-constraint penalty weights: Q = f + mu sum alpha_j g_j^2 + ... (eq. B.6 allows
        # alpha_j, beta_k per constraint; 1.0 = one overall mu, the thesis's usual choice)
        self.alpha_g: Any = 1.0
        self.alpha_h: Any = 1.0

    def scale_by_gradients(self, x: np.ndarray, floor: float = 1e-8) -> None:
        """Set alpha_j = 1/||grad g_j(x)||^2 (and beta_k likewise): walls of equal stiffness 2 mu.

        The Jacobians at ``x`` are requested once (for an oracle: at the start point,
        which is evaluated anyway).
        """
        if self.has_ineq:
            self.alpha_g = 1.0 / np.maximum(np.linalg.norm(self.ineq_jac(x), axis=1), floor) ** 2
        if self.has_eq:
            self.alpha_h = 1.0 / np.maximum(np.linalg.norm(self.eq_jac(x), axis=1), floor) ** 2

    # -- constraint access (subclasses override) -------------------------------------
    def ineq(self, x: np.ndarray) -> np.ndarray:
        return np.atleast_1d(np.asarray(self._ineq(x), dtype=float)) if self._ineq else np.zeros(0)

    def ineq_jac(self, x: np.ndarray) -> np.ndarray:
        return np.asarray(self._ineq_jac(x), dtype=float).reshape(-1, self.n)

    def eq(self, x: np.ndarray) -> np.ndarray:
        return np.atleast_1d(np.asarray(self._eq(x), dtype=float)) if self._eq else np.zeros(0)

    def eq_jac(self, x: np.ndarray) -> np.ndarray:
        return np.asarray(self._eq_jac(x), dtype=float).reshape(-1, self.n)

    def gradf(self, x: np.ndarray) -> np.ndarray:
        return np.array(self.grad_f(x), dtype=float).reshape(-1)

    @property
    def has_ineq(self) -> bool:
        return self.p != 0

    @property
    def has_eq(self) -> bool:
        return self.q != 0

    # -- penalty gradients -----------------------------------------------------------
    def at(self, x: np.ndarray) -> Any:
        """The form's quantities at ``x``: ``grad()``, ``ineq()``, ``ineq_jac()``, ``eq()``, ``eq_jac()``."""
        return _FormPoint(self, x)

    def grad_Q(self, x: np.ndarray, mu: float, active: Active | None = None) -> np.ndarray:
        """Gradient of Q(x, mu) (eq. B.6) or, with ``active``, of Q_a (eq. B.7)."""
        two_mu = 2.0 * mu
        pt = self.at(x)
        if active is None:
            gr = pt.grad()
            if self.has_ineq:
                w = np.maximum(pt.ineq(), 0.0)
                if w.any():  # Jacobian only where some constraint is violated
                    gr = gr + two_mu * (pt.ineq_jac().T @ _weighted(w, self.alpha_g))
        else:
            gr = np.zeros(self.n)
            if active.ineq.any() or (active.exterior and self.has_ineq):
                g = pt.ineq()
                w = np.where(active.ineq, g, np.maximum(g, 0.0) if active.exterior else 0.0)
                if w.any():
                    gr = gr + two_mu * (pt.ineq_jac().T @ _weighted(w, self.alpha_g))
        if self.has_eq:
            gr = gr + two_mu * (pt.eq_jac().T @ _weighted(pt.eq(), self.alpha_h))
        if self.has_bounds:
            gr = gr + self._bound_penalty_grad(x, two_mu, active)
        return gr

    def active_set(self, x: np.ndarray, tol: float = 0.0, exterior: bool = True) -> Active:
        """I_a = {j : g_j(x) > tol} over inequalities and bounds (Appendix B.4, phase 1)."""
        g = self.ineq(x) if self.has_ineq else np.zeros(0)
        lo, up = self._bound_active(x, tol)
        return Active(g > tol, lo, up, exterior)

    def active_residual(self, x: np.ndarray, active: Active) -> float:
        """max |g_j| over I_a, |h_k| and active bounds: Q_a's residual (phase 2 target is 0)."""
        r = 0.0
        if active.ineq.any():
            r = float(np.max(np.abs(self.ineq(x)[active.ineq])))
        if self.has_eq:
            r = max(r, float(np.max(np.abs(self.eq(x)), initial=0.0)))
        if active.lower.any():
            r = max(r, float(np.max(np.abs(x - self.lower)[active.lower])))
        if active.upper.any():
            r = max(r, float(np.max(np.abs(x - self.upper)[active.upper])))
        return r

    def max_violation(self, x: np.ndarray) -> float:
        v = self._bound_violation(x)
        if self.has_ineq:
            v = max(v, float(np.max(self.ineq(x), initial=0.0)))
        if self.has_eq:
            v = max(v, float(np.max(np.abs(self.eq(x)), initial=0.0)))
        return v


class OracleForm(PenaltyForm):
    """A problem behind the counting `Oracle` as a penalty form (LFOPC.minimize, ETOPC.minimize).

    Every point at which the penalty gradient is requested is one oracle point
    (N^g for the gradient-only methods).  Phase 2 asks only for constraints.
    """

    def __init__(self, oracle: Any):
        super().__init__(oracle.n, oracle.grad, lower=oracle.lower, upper=oracle.upper,
                         p=oracle.n_ineq, q=oracle.n_eq)
        self.oracle = oracle

    def ineq(self, x: np.ndarray) -> np.ndarray:
        return self.oracle.ineq(x)

    def ineq_jac(self, x: np.ndarray) -> np.ndarray:
        return self.oracle.ineq_jac(x)

    def eq(self, x: np.ndarray) -> np.ndarray:
        return self.oracle.eq(x)

    def eq_jac(self, x: np.ndarray) -> np.ndarray:
        return self.oracle.eq_jac(x)

    def gradf(self, x: np.ndarray) -> np.ndarray:
        return self.oracle.grad(x)

    def at(self, x: np.ndarray) -> Any:
        """One oracle entry per point, however many quantities grad_Q reads there."""
        return self.oracle.at(x)

    def grad_Q(self, x: np.ndarray, mu: float, active: Active | None = None) -> np.ndarray:
        """`PenaltyForm.grad_Q` read straight from the oracle (the step loop's hot path).

        The same quantities in the same order and the same floating-point operations as
        the generic version through ``self.at(x)``: the point is entered once, at the
        first quantity read (none read, none entered), and each read is counted by the
        oracle as ``OraclePoint`` counts it.  ``w.any()`` is ``np.count_nonzero(w)``
        (NaN counts in both) and ``J.T @ w`` is ``J.T.dot(w)`` (the same BLAS call),
        both without NumPy's Python-level wrappers.
        """
        o = self.oracle
        two_mu = 2.0 * mu
        if active is None:
            xe = o._enter(x)
            gr = o._grad_at(xe)
            if self.p:
                w = np.maximum(o._constraint_at("ineq", xe), _ZERO)
                if _count_nonzero(w):  # Jacobian only where some constraint is violated
                    gr = gr + two_mu * o._constraint_jac_at("ineq", xe).T.dot(_weighted(w, self.alpha_g))
        else:
            xe = None
            gr = np.zeros(self.n)
            if active.ineq.any() or (active.exterior and self.p):
                xe = o._enter(x)
                g = o._constraint_at("ineq", xe)
                w = np.where(active.ineq, g, np.maximum(g, _ZERO) if active.exterior else 0.0)
                if _count_nonzero(w):
                    gr = gr + two_mu * o._constraint_jac_at("ineq", xe).T.dot(_weighted(w, self.alpha_g))
        if self.q:
            if xe is None:
                xe = o._enter(x)
            gr = gr + two_mu * o._constraint_jac_at("eq", xe).T.dot(_weighted(o._constraint_at("eq", xe), self.alpha_h))
        if self.has_bounds:
            gr = gr + self._bound_penalty_grad(x, two_mu, active)
        return gr


@dataclasses.dataclass
class PhaseRecord:
    phase: int
    mu: float
    ng: int
    reason: str
    grad_norm: float


@dataclasses.dataclass
class ThreePhaseResult:
    """Result of the three-phase penalty scheme (Appendix B.4).

    ``x``: final point; ``x_mu1``: x*(mu1) (end of phase 1); ``active``: I_a;
    ``ng``: gradient evaluations of the core over all phases; ``phases``: per phase
    (mu, ng, end reason, final gradient norm); ``max_violation`` at ``x``.
    """

    x: np.ndarray
    x_mu1: np.ndarray
    active: Active
    ng: int
    phases: list[PhaseRecord]
    max_violation: float

    @property
    def converged(self) -> bool:
        return all(ph.reason in ("eps_g", "eps_x", "stop") for ph in self.phases)

    def summary(self) -> dict[str, Any]:
        return {
            "ng": self.ng,
            "n_active": self.active.count,
            "phases": [dataclasses.asdict(ph) for ph in self.phases],
            "max_violation": self.max_violation,
        }


def three_phase(form: PenaltyForm, x0: np.ndarray, core: Core, mu0: float, mu1: float,
                active_tol: float = 0.0, phase2: bool = True, phase2_exterior: bool = True,
                carry_dt: bool = False, phase2_tol: float = 0.0) -> ThreePhaseResult:
    """Appendix B.4: phase 0 on Q(., mu0), phase 1 on Q(., mu1), phase 2 on Q_a(., mu1).

    ``core(grad, x)`` is an unconstrained gradient-only minimizer returning an object
    with ``x``, ``ng``, ``reason``, ``grad_norm`` (LFOP or ETOP); every phase restarts it.
    Phase 2 is skipped when there is no active inequality and no equality.
    ``phase2_exterior`` keeps the exterior penalty on the inactive inequalities in
    phase 2 (see `Active`); False gives eq. (B.7) literally.
    ``carry_dt``: start each phase with the time step the previous phase ended with
    (scaled by sqrt(mu0/mu1) from phase 0 to 1, since the wall stiffness scales with
    mu); ``core`` must then accept ``dt_init`` and return ``dt`` (LFOP).  [OWN]: a phase
    that restarts with dt0 next to a stiff wall first leaps far across it.
    ``phase2_tol`` > 0 ends phase 2 as soon as every active constraint is satisfied to
    that tolerance (Q_a's minimum is 0; at degenerate intersections its gradient test
    is reached only very slowly) [OWN]; ``core`` must then accept ``stop``.
    """
    phases: list[PhaseRecord] = []
    x = np.array(x0, dtype=float).reshape(-1)
    kw: dict[str, Any] = {}
    for ph, mu in ((0, mu0), (1, mu1)):
        r = core(lambda z, mu=mu: form.grad_Q(z, mu), x, **kw)
        phases.append(PhaseRecord(ph, mu, r.ng, r.reason, r.grad_norm))
        x = r.x
        if carry_dt:
            kw = {"dt_init": r.dt * (np.sqrt(mu0 / mu1) if ph == 0 else 1.0)}
        if r.reason == "nonfinite":
            break
    x_mu1 = x
    active = form.active_set(x, active_tol, phase2_exterior)
    if phase2 and (active.count or form.has_eq) and phases[-1].reason != "nonfinite":
        if phase2_tol > 0:
            kw["stop"] = lambda z: form.active_residual(z, active) <= phase2_tol
        r = core(lambda z: form.grad_Q(z, mu1, active), x, **kw)
        phases.append(PhaseRecord(2, mu1, r.ng, r.reason, r.grad_norm))
        x = r.x
    ng = sum(ph.ng for ph in phases)
    return ThreePhaseResult(x, x_mu1, active, ng, phases, form.max_violation(x))
