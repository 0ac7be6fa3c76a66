"""Dynamic-Q+: Dynamic-Q (thesis Algorithm 3.2) carried past the thesis (our extension).

Kept from Dynamic-Q: one oracle point per iteration (f, g, h and all gradients, one N^fg),
the two-point curvature of eq. (3.6), exact simple bounds (3.7) and a move limit (3.8).
Changed (see docs/thesis_solvers.md, "Dynamic-Q+"):

1. the model Hessian is a Powell-damped BFGS matrix of the Lagrangian f + lam^T g + nu^T h,
   started from eq. (3.6)'s spherical curvature (options: one spherical or a diagonal
   curvature instead); the constraints are linearized, so the subproblem is a convex QP;
2. the subproblem is solved exactly (`solvers._qp_subproblem`, Clarabel) instead of by LFOPC's
   penalty compromise, with elastic l1 slacks so it is always feasible, and the penalty weight
   steered (Byrd, Nocedal & Waltz) so that each step keeps reducing the linearized infeasibility;
3. the move limit is a box trust region adapted by the ratio of actual to predicted reduction
   of the l1 exact-penalty merit f + mu (sum max(g,0) + sum |h|), with Fletcher's
   second-order correction of rejected steps along curved constraints;
4. stopping tests relative to the problem's scale, one restart from the spherical model
   before stopping, and no stop where a first-order measure free of the model (the step of the
   unit model P = I) shows the point far from stationary: the model is reset instead;
5. variables whose starting magnitudes differ by orders (max(1, |x0_i|) spread over 100x) are
   scaled by them, so that the move limit is per variable;
6. with constraints, f's scale (fixed from grad f(x0)) is refreshed once the gradient has fallen
   by orders, so that f keeps its weight against the penalty term; and the model's first
   curvature is never taken from a rejected trial whose curvature (3.6) is beyond the cap;
7. without constraints, the BFGS matrix is self-scaled (Al-Baali) when a step shows it too stiff;
8. a run whose last accepted steps, all full steps between feasible points, together lowered f by
   almost nothing goes to the stopping path (restart, stationarity check, stop).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from scipy.linalg.lapack import dpotrf

from problems import Oracle

from ._base import AbstractSolver, at_least, final, option
from ._qp_subproblem import ElasticQPResult, _sum, l1_model, linearized_violations, solve_elastic_qp
from ._result import SolverOutput, Status
from ._spherical import two_point_curvature

__all__ = ["DynamicQPlus"]

CURVATURES = ("bfgs", "diagonal", "spherical")
MU_MAX = 1e10
EPS = float(np.finfo(float).eps)
COND_MAX = 1e4  # largest ratio of the diagonal curvatures
UNIT_QP_WEIGHT = 1e6  # elastic weight of the stationarity measure's QP (`DynamicQPlus._unit_model_step`)
# the ufunc reductions behind ndarray.max / .all (and .sum, `_qp_subproblem._sum`), called without
# those methods' Python-level wrappers (the same reductions, so the same floats; these run several
# times per iteration)
_max, _all = np.maximum.reduce, np.logical_and.reduce
_isfinite = np.isfinite


def _clip(v: float, lo: float, hi: float) -> float:
    """float(np.clip(v, lo, hi)) for one number (NaN stays NaN), without NumPy's call overhead."""
    return float(min(max(v, lo), hi))


def _eigen_safeguard(B: np.ndarray, lo: float, hi: float, rounding_floor: bool) -> np.ndarray:
    """B with its eigenvalues clipped to [lo, hi] (B itself when none needs it).

    [OWN] item 24, ``rounding_floor``: the small eigenvalues are also kept at or above 100 n eps
    times the largest one.  The product V diag(w) V^T that rebuilds B, like eigh's eigenvalues
    themselves, is exact only to about n eps max(w), so a smaller eigenvalue is not there in
    floating point: with the safeguards' spread of 1e20 (1e-12 .. 1e8) the rebuilt matrix had an
    eigenvalue of -1.9e-9 or exactly 0 along some directions (CUTEst MARATOSB), s^T B s <= 0
    along later steps skipped every later BFGS update, and the run crawled on a frozen model."""
    w, V = np.linalg.eigh(B)
    if rounding_floor:
        lo = max(lo, 100.0 * w.size * EPS * min(float(w[-1]), hi))
    if w[0] < lo or w[-1] > hi:
        return (V * np.clip(w, lo, hi)) @ V.T
    return B


def _objective_scale(g: np.ndarray) -> float:
    """[OWN] f's scale 1 / max(1, ||grad f||): f and the penalty term comparable where g is taken."""
    return 1.0 / max(1.0, float(np.linalg.norm(g)))


def _inf_norm(v: np.ndarray) -> float:
    """||v||_inf (0 for an empty v) by the ufunc reductions above."""
    return float(_max(np.abs(v), axis=None, initial=0.0))


def _finite(ev: dict[str, Any]) -> bool:
    if not math.isfinite(ev["f"]):
        return False
    for k in ("g", "ineq", "ineq_jac", "eq", "eq_jac"):  # a loop, not a generator: this runs at every point
        a = ev[k]
        if a.size and not _all(_isfinite(a), axis=None):
            return False
    return True


def _violation(ev: dict[str, Any]) -> float:
    g, h = ev["ineq"], ev["eq"]
    return max(float(_max(g, axis=None, initial=0.0)) if g.size else 0.0,
               float(_max(np.abs(h), axis=None)) if h.size else 0.0)


def _l1_infeas(ev: dict[str, Any]) -> float:
    # empty blocks skipped: these run at every point, and a NumPy call on an empty array costs as
    # much as on a short one (adding the empty block's 0.0 to a sum >= 0 changes nothing)
    g, h = ev["ineq"], ev["eq"]
    if not h.size:
        return float(_sum(np.maximum(g, 0.0), axis=None)) if g.size else 0.0
    if not g.size:
        return float(_sum(np.abs(h), axis=None))
    return float(_sum(np.maximum(g, 0.0), axis=None) + _sum(np.abs(h), axis=None))


def _constraint_curvatures(e_from: dict[str, Any], x_from: np.ndarray, e_at: dict[str, Any],
                           x_at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eq. (3.6) for every inequality and equality at ``x_at`` from the values at ``x_from``."""
    dx = x_from - x_at
    return (two_point_curvature(e_from["ineq"], e_at["ineq"], e_at["ineq_jac"], dx),
            two_point_curvature(e_from["eq"], e_at["eq"], e_at["eq_jac"], dx))


def _exact_constraint_jacobians(oracle: Oracle) -> bool:
    """Whether every constraint block of the oracle's problem has its Jacobian given (none from
    finite differences); True without constraints."""
    p = oracle.problem
    return (not p.n_ineq or p.ineq_jacobian is not None) and (not p.n_eq or p.eq_jacobian is not None)


def _linearized_infeasibility(d: np.ndarray, ev: dict[str, Any]) -> float:
    """The l1 infeasibility of the constraints linearized at ``ev``'s point, at the step d."""
    ineq, eq = linearized_violations(d, ev["ineq"], ev["ineq_jac"], ev["eq"], ev["eq_jac"])
    return ineq + eq


def _removes_a_tenth(d: np.ndarray, ev: dict[str, Any]) -> bool:
    """Whether the step d removes at least a tenth of the linearized l1 infeasibility: the test of
    the steering rule (`DynamicQPlus._steer`) and, failed while the slacks are in use, the
    condition of item 18's curvature correction."""
    l0 = ev["l1"]
    return l0 - _linearized_infeasibility(d, ev) >= 0.1 * l0


def _lagrangian_gradient_change(ev_old: dict[str, Any], ev_new: dict[str, Any], lam: np.ndarray,
                                nu: np.ndarray) -> np.ndarray:
    """y = grad L(x_new) - grad L(x_old) at fixed multipliers, the empty blocks skipped (the same sum)."""
    y = ev_new["g"] - ev_old["g"]
    if lam.size:
        y = y + (ev_new["ineq_jac"] - ev_old["ineq_jac"]).T @ lam
    if nu.size:
        y = y + (ev_new["eq_jac"] - ev_old["eq_jac"]).T @ nu
    return y


def _lagrangian_gradient(ev: dict[str, Any], lam: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """grad f + Jg^T lam + Jh^T nu, the empty blocks skipped (the same sum)."""
    out = ev["g"]
    if lam.size:
        out = out + ev["ineq_jac"].T @ lam
    if nu.size:
        out = out + ev["eq_jac"].T @ nu
    return out


class _ScaledVariables:
    """[OWN] The oracle seen in y = x / s (s > 0 fixed): gradients and Jacobian columns times s.

    Counting is untouched: every point is passed to the wrapped oracle (clipped to its bounds,
    so rounding in s * y never leaves them).
    """

    def __init__(self, oracle: Oracle, s: np.ndarray) -> None:
        self._o, self._s = oracle, s
        self.lower, self.upper = oracle.lower / s, oracle.upper / s
        self.x0 = oracle.x0 / s
        self.n, self.n_ineq, self.n_eq = oracle.n, oracle.n_ineq, oracle.n_eq

    def evaluate(self, y: np.ndarray) -> dict[str, Any]:
        s = self._s
        e = self._o.evaluate(np.clip(s * y, self._o.lower, self._o.upper))
        return {**e, "g": s * e["g"], "ineq_jac": e["ineq_jac"] * s, "eq_jac": e["eq_jac"] * s}


@final
@dataclasses.dataclass(frozen=True)
class DynamicQPlus(AbstractSolver):
    """Dynamic-Q with exact elastic QP subproblems and a trust-region move limit (our extension).

    Iteration: solve the elastic QP at x^i with box radius rho; evaluate the trial point (one
    N^fg); accept it when the l1 merit falls by at least ``eta`` of the model's prediction.
    rho shrinks to ``shrink * ||d||_inf`` on rejection and doubles on a very good step that
    reached the box.  Stops when feasible (violation <= eps_c) and the accepted step or the
    predicted reduction is small relative to the scale of x and f, and the unit model's step
    (`_unit_model_step`) is below ``eps_kkt``.
    """

    name = "dynamic-q-plus"
    summary = ("Dynamic-Q+: BFGS Lagrangian Hessian started from eq. (3.6), exact elastic QP subproblems, "
               "trust region, second-order correction [OWN]")
    family = "own"
    handles = frozenset({"bounds", "ineq", "eq"})

    rho: float = option(1.0, "initial move limit (box half-width) relative to max(1, ||x0||_inf)",
                        "Sec. 3.4 rho = 1 [THESIS], scaled [OWN]")
    eps_x: float = option(1e-7, "stop: ||d||_inf / (1 + ||x||_inf) below this at a feasible point (when the "
                          "solver works in scaled variables y = x / s: in y and in x)", "[OWN]")
    eps_f: float = option(1e-14, "stop: predicted merit reduction / (1 + |f|) below this at a feasible point "
                          "(both unscaled)", "[OWN]")
    eps_df: float = option(0.0, "stop: an accepted interior (full) step of a model with curvature information, "
                           "between feasible points, changed f by less than this relative to 1 + |f| (the "
                           "thesis's test (3.11), guarded); 0: off (1e-9 until item 15 of docs/thesis_solvers.md: "
                           "it ended runs crossing a plateau)", "[OWN]; (3.11)")
    eps_stall: float = option(1e-10, "stop (through the restart and the stationarity check, as the other tests): "
                              "the last `stall_window` accepted steps, each a full step of a model with curvature "
                              "information between feasible points, lowered f by less than this relative to "
                              "1 + |f| in all; 0: off (before item 22 of docs/thesis_solvers.md)",
                              "[OWN] item 22; Ipopt's acceptable_iter = 15")
    stall_window: int = option(15, "the number of accepted steps `eps_stall` looks back over", "[OWN] item 22")
    eps_c: float = option(1e-7, "feasibility: every constraint violation <= eps_c", "[OWN]")
    eps_kkt: float = option(0.01, "a stopping test ends the run only where the unit model's step (x in units of "
                            "1 + ||x||_inf, f in units of 1 + |f|, every curvature 1, box [-1, 1]; r ||grad f||_inf "
                            "/ (1 + |f|) capped at 1 away from constraints) is below this; otherwise the model is "
                            "reset to that one (again at the same point only after a trial from it, with the "
                            "move limit the rejections left); inf: no check", "[OWN]")
    eta: float = option(0.1, "accept a step when actual / predicted merit reduction >= eta", "[OWN] trust region")
    shrink: float = option(0.3, "on rejection rho = shrink * ||d||_inf", "[OWN] trust region")
    sigma_min: float = option(1e-12, "lower safeguard on the curvatures (eigenvalues of the BFGS matrix, of the "
                              "scaled problem); small, because ill-conditioned least squares have curvatures "
                              "near 1e-11 that a larger floor overestimates (docs/thesis_solvers.md)", "[OWN]")
    sigma_max: float = option(1e8, "upper safeguard on the curvatures (eigenvalues of the BFGS matrix, of the "
                              "scaled problem); 1e12 was tried and solves 4 fewer CUTEst problems "
                              "(docs/thesis_solvers.md)", "[OWN]")
    curvature: str = option("bfgs", "'bfgs': Powell-damped BFGS matrix of the Lagrangian started from "
                            "eq. (3.6)'s spherical curvature; 'diagonal': per-variable curvatures of the "
                            "Lagrangian by the weak-secant "
                            "update started from eq. (3.6); 'spherical': one curvature, eq. (3.6) on the Lagrangian",
                            "[OWN]; eq. (3.6) [THESIS]; Zhu-Nazareth-Wolkowicz diagonal weak secant")
    constraint_curvature: bool = option(False, "correct the linearized constraints by their spherical curvatures "
                                        "(3.6) at the previous subproblem step length (second-order correction "
                                        "without oracle calls)", "[OWN]; eq. (3.6) [THESIS]")
    stuck_curvature: bool = option(True, "where the QP step removes less than a tenth of the linearized l1 "
                                   "infeasibility (the linearization cannot restore feasibility), correct the "
                                   "constraints by their curvatures (3.6), as constraint_curvature does at every step",
                                   "[OWN] item 18; eq. (3.6) [THESIS]")
    rise_curvature: bool = option(True, "after a trial whose plain step was rejected with the constraint violation "
                                  "risen (the linearization missed the constraints' curvature; the trigger of the "
                                  "second-order correction), correct the next QP's constraints by their curvatures "
                                  "(3.6), as constraint_curvature does at every step; only with exact constraint "
                                  "Jacobians (none from finite differences)",
                                  "[OWN] item 19; eq. (3.6) [THESIS]")
    mu0: float = option(10.0, "initial l1 penalty weight (raised to 2 x the largest multiplier)", "[OWN]")
    second_order_correction: bool = option(True, "on a rejected step that raised the constraint violation, try "
                                           "one corrected step (one more oracle point)",
                                           "[OWN] Fletcher's second-order correction")
    memory: int = option(4, "non-monotone merit: compare with the worst of this many last accepted points",
                         "[OWN] (Grippo-Lampariello-Lucidi style; 1 = monotone)", check=at_least(1))
    steering: bool = option(True, "raise the penalty weight until the step achieves at least a tenth of the "
                            "linearized infeasibility reduction the move limit allows (one more QP, only while "
                            "the elastic slacks are in use)", "[OWN] Byrd-Nocedal-Waltz steering rule")
    penalty_decrease: bool = option(True, "at a feasible point, lower the penalty weight to 10x what the "
                                    "multipliers need when it has grown past 100x that and the step uses no slacks "
                                    "(the step is the same for any weight above the multipliers; only the merit "
                                    "changes); once raised past a lowered value, it is not lowered again in the run. "
                                    "False: never lowered (before item 17 of docs/thesis_solvers.md)", "[OWN]")
    scale_spread: float = option(100.0, "work in y = x / s, s_i = max(1, |x0_i|), when the largest s_i is over this "
                                 "many times the smallest (variables of different orders of magnitude); "
                                 "inf: never, 1: always", "[OWN]")
    rescale_f: float = option(100.0, "with constraints: when ||grad f|| at an accepted point has fallen below "
                              "1 / this of the ||grad f|| that set f's scale (at x0: f is scaled by "
                              "1 / max(1, ||grad f(x0)||)), f is scaled by 1 / max(1, ||grad f||) there instead (and "
                              "the model with it, up to the cap sigma_max); inf: never", "[OWN]")
    self_scaling: bool = option(True, "without general constraints (bounds allowed): before a BFGS update whose "
                                "step measured less curvature than the model's (0 < s^T y < s^T B s), scale B by "
                                "s^T y / s^T B s, so that a model made too stiff by earlier steps softens in every "
                                "direction, not only along the step; False: before item 21 of "
                                "docs/thesis_solvers.md", "[OWN] item 21; Al-Baali's conditional self-scaling")
    definite_model: bool = option(True, "where a BFGS update meets s^T B s <= 0 (a matrix that the rounding of the "
                                  "eigenvalue safeguard left indefinite), first raise B's small eigenvalues to "
                                  "100 n eps times its largest and then update, instead of skipping this update "
                                  "and every later one along such steps; False: before item 24 of "
                                  "docs/thesis_solvers.md", "[OWN] item 24")
    probe_model: bool = option(True, "where a stopping test meets a point far from stationary (as eps_kkt) after a "
                               "reset has happened in the run, and the model has had at most n updates since the "
                               "last one, take the model's short step once at that point (to gain its secant "
                               "pair; a rejected probe leaves the move limit) instead of resetting again; False: "
                               "before item 25 of docs/thesis_solvers.md", "[OWN] item 25")
    stuck_reset: bool = option(True, "at an infeasible point where the model finds no descent of the merit even "
                               "with the weight at its cap, reset the model to the unit model once (after any "
                               "update since the last reset) before failing; False: before item 27 of "
                               "docs/thesis_solvers.md", "[OWN] item 27")
    qp_retry: bool = option(True, "when Clarabel ends a subproblem short of 'Solved', solve it once more with "
                            "its static regularization at 1e-12 (its default, 1e-8, exceeds the smallest "
                            "curvatures of the models it stalls on) and keep the step with the lower model; "
                            "where it ended on its iteration cap, first once more divided by sqrt(mu) (item "
                            "26); False: before item 23 of docs/thesis_solvers.md", "[OWN] items 23, 26")
    max_iter: int = option(3000, "maximum number of iterations, each one trial point of a QP step (rejected "
                           "trials included), plus one more when a second-order correction is tried; Ipopt's "
                           "default cap (item 20: 1000 before, which stopped BFGS crawls such as PFIT1LS and "
                           "MARATOSB short of their optima)", "[OWN]")

    def check_together(self) -> None:  # called by AbstractSolver.__post_init__ after the per-option checks
        for k in ("rho", "sigma_min", "sigma_max", "mu0"):
            v = getattr(self, k)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"dynamic-q-plus: {k} must be a positive finite number, got {v!r}")
        if not (self.rescale_f >= 1.0):  # inf allowed (never); NaN fails here
            raise ValueError(f"dynamic-q-plus: rescale_f must be >= 1 (inf: never), got {self.rescale_f!r}")
        if not (self.scale_spread >= 1.0):  # inf allowed (never scale); NaN fails here
            raise ValueError(f"dynamic-q-plus: scale_spread must be >= 1 (inf: never scale), got {self.scale_spread!r}")
        for k in ("eps_x", "eps_f", "eps_df", "eps_stall", "eps_c", "eps_kkt"):
            v = getattr(self, k)
            if not (isinstance(v, (int, float)) and v >= 0):
                raise ValueError(f"dynamic-q-plus: {k} must be >= 0, got {v!r}")
        for k in ("eta", "shrink"):
            v = getattr(self, k)
            if not (isinstance(v, (int, float)) and 0 < v < 1):
                raise ValueError(f"dynamic-q-plus: {k} must be in (0, 1), got {v!r}")
        if self.curvature not in CURVATURES:
            raise ValueError(f"dynamic-q-plus: curvature must be one of {CURVATURES}, got {self.curvature!r}")
        if not (isinstance(self.stall_window, (int, np.integer)) and self.stall_window >= 1):
            raise ValueError(f"dynamic-q-plus: stall_window must be an integer >= 1, got {self.stall_window!r}")
        if not (isinstance(self.max_iter, (int, np.integer)) and self.max_iter >= 1):
            raise ValueError(f"dynamic-q-plus: max_iter must be an integer >= 1, got {self.max_iter!r}")

    def _curvature(self, ev_old, ev_new, lam, nu, dx) -> float | None:
        """Eq. (3.6) on the Lagrangian: 2 [L(x_new) - L(x_old) - grad L(x_old)^T dx] / ||dx||^2."""
        dd = float(dx @ dx)
        if dd <= 0.0:
            return None
        L_old, L_new = ev_old["f"], ev_new["f"]
        if lam.size:
            L_old, L_new = L_old + float(lam @ ev_old["ineq"]), L_new + float(lam @ ev_new["ineq"])
        if nu.size:
            L_old, L_new = L_old + float(nu @ ev_old["eq"]), L_new + float(nu @ ev_new["eq"])
        gL = _lagrangian_gradient(ev_old, lam, nu)
        return 2.0 * (L_new - L_old - float(gL @ dx)) / dd

    def _update(self, sigma, s_sph, ev_old, ev_new, lam, nu, dx, first: bool) -> np.ndarray:
        """New curvatures after the step dx (from x_old to x_new), safeguarded to [sigma_min, sigma_max].

        'spherical' (and the first update of 'diagonal'): sigma_i = eq. (3.6) on the Lagrangian.
        'diagonal': least change of diag(sigma) in the Frobenius norm that meets the weak secant
        condition dx^T diag(sigma) dx = dx^T y, y the change of the Lagrangian's gradient.
        """
        if self.curvature == "bfgs":
            return self._bfgs(sigma, s_sph, ev_old, ev_new, lam, nu, dx, first)
        if self.curvature == "spherical" or first:
            new = np.full(dx.size, s_sph)
        else:
            y = _lagrangian_gradient_change(ev_old, ev_new, lam, nu)
            s2 = dx * dx
            new = sigma + (float(dx @ y) - float(s2 @ sigma)) / float(s2 @ s2) * s2
        new = np.clip(new, self.sigma_min, self.sigma_max)
        # [OWN] keep the diagonal's spread <= COND_MAX: a near-zero curvature makes the model linear
        # in that variable and the steps run to the move limit (seen on HS72)
        return np.maximum(new, float(new.max()) / COND_MAX)

    def _bfgs(self, B, s_sph, ev_old, ev_new, lam, nu, dx, first: bool) -> np.ndarray:
        """Powell-damped BFGS update of the Lagrangian Hessian B from the step dx.

        The first update starts from B0 = sigma I with sigma the spherical curvature of eq. (3.6)
        (Dynamic-Q's own estimate, safeguarded), so the quasi-Newton matrix refines the thesis's
        one-number model with the same one point per iteration.  Damping (Powell 1978) keeps B
        positive definite when the Lagrangian's curvature along dx is negative or tiny.
        """
        y = _lagrangian_gradient_change(ev_old, ev_new, lam, nu)
        B_in = B
        if first:
            B = _clip(s_sph, self.sigma_min, self.sigma_max) * np.eye(dx.size)
        Bs = B @ dx
        sBs = float(dx @ Bs)
        sy = float(dx @ y)
        finite = _all(_isfinite(y), axis=None)
        if self.definite_model and finite and sBs <= 0.0:
            # [OWN] item 24: B lost definiteness to rounding (below); without the repair this update and
            # every later one along such steps is skipped, and the model stays frozen
            B = _eigen_safeguard(B, self.sigma_min, self.sigma_max, rounding_floor=True)
            Bs = B @ dx
            sBs = float(dx @ Bs)
        if not (sBs > 0.0 and finite):
            return B
        if self.self_scaling and not first and not lam.size and not nu.size and 0.0 < sy < sBs:
            # [OWN] item 21: Al-Baali's conditional self-scaling (JOTA 96, 1998), tau = min(1, s^T y / s^T B s).
            # BFGS corrects an overestimated curvature only along each step, so a model made too stiff
            # by earlier steps crawls (HEART8LS: B's largest eigenvalue rose to 5e4 while every interior
            # step gained more than predicted, to the cap at f = 1.14, optimum 0).  Only without
            # constraints: there y is the change of the Lagrangian's gradient under changing
            # multipliers, and scaling the whole model by it lost more runs than it gained (CUTEst)
            tau = sy / sBs
            B, Bs, sBs = B * tau, Bs * tau, sy
        theta = 1.0 if sy >= 0.2 * sBs else 0.8 * sBs / (sBs - sy)
        r = theta * y + (1.0 - theta) * Bs
        sr = float(dx @ r)
        if sr <= 1e-12 * sBs:
            return B
        # B - Bs Bs^T / sBs + r r^T / sr, np.outer's own arithmetic, in place (the same roundings)
        t = Bs[:, None] * Bs
        t /= sBs
        Bn = B - t
        t = r[:, None] * r
        t /= sr
        Bn += t
        Bn = Bn + Bn.T
        Bn *= 0.5
        # safeguard: eigenvalues within [sigma_min, sigma_max] (B stays positive definite)
        if self._inside_bounds(Bn):
            return Bn
        if not _all(_isfinite(Bn), axis=None):  # [OWN] overflow in the outer products (CUTEst GAUSS2LS): no update
            return B_in
        return _eigen_safeguard(Bn, self.sigma_min, self.sigma_max, rounding_floor=False)

    def _inside_bounds(self, B: np.ndarray) -> bool:
        """True when B's eigenvalues are surely inside [sigma_min, sigma_max], shown without an
        eigendecomposition: B - (sigma_min + margin) I has a Cholesky factor, and the trace
        (the sum of the then positive eigenvalues) is at most sigma_max.  The margin, 1e-10
        of the trace, exceeds eigh's rounding, so whenever this says True, eigh would not clip
        either; otherwise eigh decides (the result is the same, only cheaper)."""
        tr = float(B.trace())
        if not (tr <= self.sigma_max):
            return False
        shifted = B.copy()
        shifted.ravel()[::B.shape[0] + 1] -= self.sigma_min + 1e-10 * tr  # B - c I without building I (ravel: a view)
        # LAPACK's Cholesky (as np.linalg.cholesky) called directly: info > 0 = not positive definite
        return dpotrf(shifted, lower=1, clean=0, overwrite_a=1)[1] == 0

    def _qp(self, gf, sigma, g0, Jg, h0, Jh, d_lo, d_up, mu) -> ElasticQPResult:
        """`solve_elastic_qp` with this solver's `qp_retry`."""
        return solve_elastic_qp(gf, sigma, g0, Jg, h0, Jh, d_lo, d_up, mu, retry_stalled=self.qp_retry)

    def _steer(self, res, mu: float, ev: dict[str, Any], sigma, d_lo: np.ndarray, d_up: np.ndarray):
        """[OWN] Steering rule for the penalty weight (Byrd, Nocedal & Waltz 2008, eps1 = 0.1).

        While the elastic slacks are in use, the step for the current mu may trade feasibility
        for f (rpr3 SO P1: mu = 10 throughout, the violation rising from 0.03 to 0.06 until
        the move limit collapsed).  The ideal reduction of the linearized l1 infeasibility
        within the move limit is that of the feasibility step (the QP without f, slacks
        weighted 1e6); mu is raised tenfold until the step achieves a tenth of it.  The ideal
        reduction is at most the current infeasibility, so a step that already removes a tenth
        of that passes without the feasibility QP (the same step and mu, one QP fewer).
        """
        if _removes_a_tenth(res.d, ev):
            return res, mu
        feas = self._qp(np.zeros_like(ev["g"]), sigma, ev["ineq"], ev["ineq_jac"], ev["eq"], ev["eq_jac"],
                        d_lo, d_up, 1e6)
        if not feas.ok:
            return res, mu
        l0 = ev["l1"]
        ideal = l0 - _linearized_infeasibility(feas.d, ev)
        while ideal > 0.0 and l0 - _linearized_infeasibility(res.d, ev) < 0.1 * ideal and mu < MU_MAX:
            mu *= 10.0
            new = self._qp(ev["g"], sigma, ev["ineq"], ev["ineq_jac"], ev["eq"], ev["eq_jac"], d_lo, d_up, mu)
            if not new.ok:
                break
            res = new
        return res, mu

    def _restart_before_stop(self, restarted: bool, n_upd: int) -> bool:
        """[OWN] Restart the quasi-Newton matrix once instead of stopping.

        The BFGS matrix can keep a large curvature from far away in directions it has not
        explored since (HS64: steps of 1e-6 at a non-stationary point).  Before the first stop,
        the solver restarts from Dynamic-Q's spherical model and stops only if that model makes
        no progress either.
        """
        return self.curvature == "bfgs" and not restarted and n_upd > 1

    def _spherical_restart(self, s_last: float, n: int) -> np.ndarray:
        """sigma I with sigma the spherical curvature of eq. (3.6) along the last step, safeguarded."""
        return _clip(s_last, self.sigma_min, self.sigma_max) * np.eye(n)

    @staticmethod
    def _unit_model_step(ev: dict[str, Any], x: np.ndarray, lo: np.ndarray, up: np.ndarray,
                         retry_stalled: bool = True) -> float:
        """[OWN] A first-order stationarity measure independent of the quasi-Newton matrix and of
        the scaling of f fixed at x0: with the step in units of r = 1 + ||x||_inf and f in units of
        1 + |f|, the step of the QP with every curvature 1 in the box [-1, 1] (linearized
        constraints as in the iteration).  Where no constraint is near, r ||grad f||_inf / (1 + |f|)
        capped at 1: the relative decrease of f per relative step.  inf when the QP fails."""
        r = 1.0 + _inf_norm(x)
        raw = ev["raw"]
        g = (r / (1.0 + abs(raw["f"]))) * raw["g"]
        res = solve_elastic_qp(g, np.ones(x.size), ev["ineq"], r * ev["ineq_jac"], ev["eq"], r * ev["eq_jac"],
                               np.maximum((lo - x) / r, -1.0), np.minimum((up - x) / r, 1.0), UNIT_QP_WEIGHT,
                               retry_stalled)
        return _inf_norm(res.d) if res.ok else math.inf

    @staticmethod
    def _unit_model_step_bound(ev: dict[str, Any], x: np.ndarray, lo: np.ndarray, up: np.ndarray, lam: np.ndarray,
                               nu: np.ndarray, sf: float) -> float:
        """[OWN] An upper bound on `_unit_model_step` without solving its QP: weak duality with
        the multipliers of the iteration's QP (``lam``, ``nu``, carried to the unit model's units
        and clipped to its elastic weight M) and, on each variable, a bound's multiplier where
        that lowers the bound.  The unit QP's objective q is 1-strongly convex, so
        ||d*||^2 <= 2 (q(0) - q_dual) = ||grad_d L||^2 + 2 (M l1 - lam^T g - nu^T h) + bound terms.
        Where it is below ``eps_kkt`` the QP's answer is too, and the QP (a tenth of a
        millisecond, one per stop) is not needed."""
        r = 1.0 + _inf_norm(x)
        raw = ev["raw"]
        a = r / (1.0 + abs(raw["f"]))
        k = a / (sf * r)  # so that a g + r J^T lam_u = (a / sf) (sf g + J^T lam): the iteration's Lagrangian gradient
        grad, gap = a * raw["g"], UNIT_QP_WEIGHT * ev["l1"]
        if lam.size:  # empty blocks skipped (this runs once per stop, on every run)
            lam_u = np.minimum(np.maximum(k * lam, 0.0), UNIT_QP_WEIGHT)
            grad = grad + r * (ev["ineq_jac"].T @ lam_u)
            gap -= float(lam_u @ ev["ineq"])
        if nu.size:
            nu_u = np.minimum(np.maximum(k * nu, -UNIT_QP_WEIGHT), UNIT_QP_WEIGHT)
            grad = grad + r * (ev["eq_jac"].T @ nu_u)
            gap -= float(nu_u @ ev["eq"])
        terms = grad * grad
        # a bound's multiplier mu_i = |grad_i| where grad pushes against a finite bound: the term
        # grad_i^2 becomes 2 |grad_i| (distance to the bound) / r, whichever is smaller
        for pushing, gap_to_bound in ((grad > 0.0, x - lo), (grad < 0.0, up - x)):
            on = pushing & (gap_to_bound < math.inf)
            if on.any():
                terms[on] = np.minimum(terms[on], 2.0 * np.abs(grad[on]) * np.maximum(gap_to_bound[on], 0.0) / r)
        return math.sqrt(max(float(terms.sum()) + 2.0 * gap, 0.0))

    def _stationarity(self, ev: dict[str, Any], x: np.ndarray, lo: np.ndarray, up: np.ndarray,
                      res: ElasticQPResult, sf: float) -> float:
        """[OWN] `_unit_model_step`, or its upper bound `_unit_model_step_bound` where that is
        already below ``eps_kkt`` (the same decision, without the QP)."""
        bound = self._unit_model_step_bound(ev, x, lo, up, res.lam, res.nu, sf)
        return bound if bound <= self.eps_kkt else self._unit_model_step(ev, x, lo, up, self.qp_retry)

    def _unit_model(self, ev: dict[str, Any], x: np.ndarray, sf: float, n: int) -> np.ndarray:
        """[OWN] The model of `_unit_model_step` in the iteration's units (f times sf, x): P = c I
        with c = sf (1 + |f|) / (1 + ||x||_inf)^2, so that its step is the measure's step."""
        c = _clip(sf * (1.0 + abs(ev["raw"]["f"])) / (1.0 + _inf_norm(x)) ** 2, self.sigma_min, self.sigma_max)
        return c * np.eye(n) if self.curvature == "bfgs" else np.full(n, c)

    def _objective_rescale(self, sf: float, g_raw: np.ndarray, sigma: np.ndarray) -> float:
        """[OWN] The factor c >= 1 by which f's scale sf grows at an accepted point (1: unchanged).

        sf = 1 / max(1, ||grad f(x0)||) balances f against the penalty term at x0.  Where x0 is
        far out (LUKVLE4: ||grad f(x0)|| = 3e7, about 10 near the optimum) f shrinks to 1e-7 of
        the weight mu0 there, every step is judged by its violation alone, and the run crawls
        along the constraints on rejected plain steps and second-order corrections until the cap.
        Once ||grad f|| has fallen below sf's gradient by the factor ``rescale_f``, f is scaled by
        1 / max(1, ||grad f||) instead.  The model is the Hessian of the scaled Lagrangian and is
        scaled with it, so c stops where its trace would pass sigma_max (the cap would change the
        model; STREGNE, whose gradient falls by 1e10 in three steps).
        """
        sf_now = _objective_scale(g_raw)
        if not sf_now > self.rescale_f * sf:
            return 1.0
        trace = float(sigma.trace()) if sigma.ndim == 2 else float(sigma.sum())
        return max(1.0, min(sf_now / sf, self.sigma_max / trace))

    def minimize(self, oracle: Oracle) -> SolverOutput:
        """[OWN] Variable scaling, then the iteration (`_minimize`).

        With one box half-width rho for every variable, a problem whose variables are of
        different orders (S2MPJ HS116: 0.1 to 650 at x0) gets a move limit far too large for the
        small ones and too small for the large ones.  When the largest s_i = max(1, |x0_i|) exceeds
        ``scale_spread`` times the smallest, the solver works in y = x / s (so rho is relative to
        each variable's start); otherwise (a spread under 100: every hs, 2-RPR and 3-RPR problem)
        the run is exactly the unscaled one.  Scaling every problem was tried: +1 on hs-all, but
        rpr2 P1 and E and 3-RPR MO P1 ended worse (docs/thesis_solvers.md).
        """
        s = np.maximum(1.0, np.abs(np.clip(oracle.x0, oracle.lower, oracle.upper)))
        exact = _exact_constraint_jacobians(oracle)
        if not float(s.max()) > self.scale_spread * float(s.min()):
            return self._minimize(oracle, exact_jacobians=exact)
        out = self._minimize(_ScaledVariables(oracle, s), var_scale=s, exact_jacobians=exact)  # type: ignore[arg-type]
        return dataclasses.replace(out, x=np.clip(s * out.x, oracle.lower, oracle.upper))

    def _minimize(self, oracle: Oracle, var_scale: np.ndarray | None = None,
                  exact_jacobians: bool = True) -> SolverOutput:
        """The iteration, on ``oracle`` as given; ``var_scale`` is s when it is the scaled view
        y = x / s (`minimize`), so that the step test can measure steps in x too;
        ``exact_jacobians``: no constraint Jacobian comes from finite differences."""
        lo, up = oracle.lower, oracle.upper
        x = np.clip(oracle.x0, lo, up)
        ev0 = oracle.evaluate(x)
        if not _finite(ev0):
            return SolverOutput(x, Status.ERROR, "non-finite f, gradient or constraint at x0", nit=0)
        # [OWN] fixed scaling from x0: constraints by 1/||grad|| where it exceeds 1 (as dynamic-q's
        # 'cap' normalization) and f likewise, so mu and the QP are well scaled (e.g. HS106)
        sf = _objective_scale(ev0["g"])
        sg = 1.0 / np.maximum(np.linalg.norm(ev0["ineq_jac"], axis=1), 1.0)
        sh = 1.0 / np.maximum(np.linalg.norm(ev0["eq_jac"], axis=1), 1.0)

        sg_rows, sh_rows = sg[:, None], sh[:, None]
        has_ineq, has_eq = oracle.n_ineq > 0, oracle.n_eq > 0
        # `_objective_rescale` can return more than 1 only while rescale_f sf < 1 (the new sf is at most
        # 1): tested once here and after each rescale, not by a gradient norm at every accepted point
        rescalable = (has_ineq or has_eq) and self.rescale_f * sf < 1.0

        def scaled(e: dict[str, Any]) -> dict[str, Any]:
            out = {"f": sf * e["f"], "g": sf * e["g"], "raw": e}
            # an empty block is passed through: scaling it would give an equal empty array
            out["ineq"], out["ineq_jac"] = ((sg * e["ineq"], sg_rows * e["ineq_jac"]) if has_ineq
                                            else (e["ineq"], e["ineq_jac"]))
            out["eq"], out["eq_jac"] = (sh * e["eq"], sh_rows * e["eq_jac"]) if has_eq else (e["eq"], e["eq_jac"])
            out["l1"] = _l1_infeas(out)  # the merit's infeasibility, used several times per point
            out["viol"] = _violation(e)  # unscaled, for the feasibility tests
            return out

        ev = scaled(ev0)
        scale_x = max(1.0, float(np.abs(x).max(initial=0.0)))
        rho = float(self.rho) * scale_x
        n_upd = 0
        # the last step's two points (values, x), for the constraint curvatures (3.6)
        last_step: tuple[dict[str, Any], np.ndarray, dict[str, Any], np.ndarray] | None = None
        # P[0]: no curvature information yet (the thesis' P[0] is linear)
        sigma: Any = np.eye(oracle.n) if self.curvature == "bfgs" else np.ones(oracle.n)
        mu = float(self.mu0)
        mu_lowered = math.inf  # [OWN] the weight the last decrease set; raised past it, never lowered again
        log: list[dict[str, Any]] = []
        n_rej = 0
        x_probe = None  # [OWN] item 25: the last point whose model step was taken as a probe
        n_reset, x_reset = 0, None  # [OWN] resets to the unit model by the stationarity check, and where the last was
        restarted, s_last = False, 1.0  # [OWN] one restart of the quasi-Newton matrix before stopping
        recent: list[dict[str, Any]] = [ev]  # [OWN] non-monotone reference: last accepted points
        risen = False  # [OWN] item 19: the last trial's plain step was rejected with the violation risen
        # item 19 needs exact Jacobians: (3.6)'s error from a finite-difference Jacobian is the
        # difference error over the step length, as large as the curvature itself on short steps
        rise_curvature = self.rise_curvature and exact_jacobians
        # [OWN] item 22: unscaled f after each of the last accepted full steps between feasible points
        window: list[float] = []
        for it in range(1, self.max_iter + 1):
            probing = False
            d_lo, d_up = np.maximum(lo - x, -rho), np.minimum(up - x, rho)  # simple bounds (3.7), move limit (3.8)
            res = self._qp(ev["g"], sigma, ev["ineq"], ev["ineq_jac"], ev["eq"], ev["eq_jac"], d_lo, d_up, mu)
            if not res.ok:  # [OWN] numerical trouble in the QP solver: retry with a smaller move limit
                rho *= self.shrink
                if rho / (1.0 + float(np.abs(x).max(initial=0.0))) < 1e-3 * self.eps_x:
                    return SolverOutput(x, Status.FAILED, f"QP subproblem failed (Clarabel: {res.status}, penalty "
                                        f"weight {mu:.3g}) down to a collapsed move limit", nit=it,
                                        extra=self._extra(log, n_rej, n_reset=n_reset))
                continue
            # largest multiplier (lam >= 0 already); empty blocks skipped
            mult = max(float(_max(res.lam, axis=None)) if res.lam.size else 0.0,
                       float(_max(np.abs(res.nu), axis=None)) if res.nu.size else 0.0)
            if mult > 0.5 * mu and res.elastic <= self.eps_c:
                # [OWN] the exact-penalty weight must exceed the multipliers.  Not raised while the
                # slacks are in use: then the multipliers sit at mu because the move limit cuts the
                # linearization, not because mu is too small (raising it there ran mu to 1e7 on HS104);
                # a merit-stationary infeasible point raises it below
                mu = 2.0 * mult
                res = self._qp(ev["g"], sigma, ev["ineq"], ev["ineq_jac"], ev["eq"], ev["eq_jac"],
                               d_lo, d_up, mu)
            elif (self.penalty_decrease and mu <= mu_lowered and res.elastic <= self.eps_c
                  and ev["viol"] <= self.eps_c and mu > 100.0 * max(float(self.mu0), 2.0 * mult)):
                # [OWN] lower an overgrown weight.  Steering can raise mu by 1e4 far from the solution;
                # kept there, the merit rejects every plain step whose violation is 1e-8 (DEMBO7: on
                # the cap at f = 228, optimum 175).  With no slacks in use and mu above the multipliers
                # the QP step does not depend on mu, so only the merit changes.  Not again once mu has
                # had to rise past the lowered value (3-RPR MO P1 cycled 2.8e5 -> 100 -> 2.8e5 to the cap)
                mu = mu_lowered = 10.0 * max(float(self.mu0), 2.0 * mult)
            if self.steering and res.elastic > self.eps_c and mu < MU_MAX:
                res, mu = self._steer(res, mu, ev, sigma, d_lo, d_up)
            # [OWN] item 18: where the step removes less than a tenth of the linearized infeasibility
            # (the steering rule's test), the linearization cannot restore feasibility (FLETCHER: a
            # constraint whose gradient vanishes at x0); with the curvatures (3.6) it can (CRESC4,
            # stuck at violation 1.5 with the weight at its cap, needs item 27 too).  Not wherever the
            # slacks are in use: that also bent steps the move limit merely cut (2-RPR E, LUKVLE11,
            # LUKVLE17 ended higher).  The curvatures are computed only here, where used
            stuck = self.stuck_curvature and res.elastic > self.eps_c and not _removes_a_tenth(res.d, ev)
            # [OWN] item 19: likewise after a trial whose violation rose against the linearization's
            # prediction (TENBARS3: a plain step rejected and a second-order correction accepted, in
            # turn, for 1000 iterations; TRO3X3)
            correct = self.constraint_curvature or stuck or (rise_curvature and risen)
            curv = _constraint_curvatures(*last_step) if correct and last_step else None
            if curv is not None and (np.any(curv[0]) or np.any(curv[1])):
                bq, cq = curv
                # [OWN] the thesis's constraint curvatures (3.6) as a model-based second-order
                # correction: g~_j(d) = g_j + grad g_j^T d + b_j/2 ||d||^2 with ||d|| frozen at the
                # previous solution (fixed point, no oracle calls); keeps steps on curved
                # constraints (the Maratos zig-zag of HS27)
                rc = res
                for _ in range(2):
                    dd = float(rc.d @ rc.d)
                    rc = self._qp(ev["g"], sigma, ev["ineq"] + 0.5 * bq * dd, ev["ineq_jac"],
                                  ev["eq"] + 0.5 * cq * dd, ev["eq_jac"], d_lo, d_up, mu)
                # predicted reduction of the curvature-corrected model at its own step; kept only if
                # it is a descent step of that model
                dd = float(rc.d @ rc.d)
                mq = l1_model(rc.d, ev["g"], sigma, ev["ineq"] + 0.5 * bq * dd, ev["ineq_jac"],
                              ev["eq"] + 0.5 * cq * dd, ev["eq_jac"], mu)
                if rc.ok and mu * ev["l1"] - mq > 0.0:
                    res = dataclasses.replace(rc, model=mq)
            d = res.d
            viol = ev["viol"]
            phi = ev["f"] + mu * ev["l1"]
            pred = mu * ev["l1"] - res.model  # model reduction of phi
            dn = _inf_norm(d)
            xs = 1.0 + _inf_norm(x)
            # [OWN] the stopping quantities of the problem itself, not of its scaled form.  With scaled
            # variables the step must be small in y = x / s *and* in x: in y alone, a variable scaled
            # by a large |x0_i| that goes to 0 stopped the run 1/s_i too early (STREGNE: s = 1e10,
            # stopped at f = 1.4e-5, optimum 0); in x alone, 1 + ||x||_inf is set by the largest
            # variable, and a step in the small ones looks negligible (MEYER3: x0 = (0.02, 4000, 250),
            # stopped at x0).  The predicted reduction against the unscaled f: pred is in scaled units
            # (f times sf <= 1), and 1 + |sf f| would loosen the test by 1/sf (CLIFF: sf 7e-11, so a
            # predicted gain of 1e-4 of f passed as 1e-14; KIRBY2LS, MEXHAT)
            small_step = dn / xs < self.eps_x
            if small_step and var_scale is not None:
                small_step = _inf_norm(var_scale * d) < self.eps_x * (1.0 + _inf_norm(var_scale * x))
            if viol <= self.eps_c and (small_step or pred / (sf * (1.0 + abs(ev["raw"]["f"]))) < self.eps_f):
                if self._restart_before_stop(restarted, n_upd):
                    sigma, restarted = self._spherical_restart(s_last, oracle.n), True
                    continue
                chi = self._stationarity(ev, x, lo, up, res, sf)
                # [OWN] a point far from stationary: reset to the unit model (item 13).  Again at the
                # same point once a trial has been evaluated since (item 16), with the move limit
                # as the rejections left it, so the run is a trust region on that model until a
                # step is accepted or the limit collapses (a repeat needs a trial evaluated since)
                # [OWN] item 25: but where resets recur and the model has had at most n updates since the
                # last, its short step says only that its curvatures are too large: after a reset the first
                # update scales the whole matrix by one curvature, the largest (POWELLBSLS, a valley 1e8
                # times stiffer across than along: every cycle of reset, rejected unit-model steps and one
                # update moved f by 1e-13).  The step is taken once at that point, for its secant pair
                probing = (self.probe_model and chi > self.eps_kkt and n_reset > 0 and 0 < n_upd <= oracle.n
                           and x is not x_probe and dn > 0.0 and pred > 0.0)
                if probing:
                    x_probe = x
                elif chi > self.eps_kkt and (x is not x_reset or n_upd > 0):
                    if x is not x_reset:
                        rho = max(rho, chi * xs)
                    sigma = self._unit_model(ev, x, sf, oracle.n)
                    n_upd, n_reset, x_reset = 0, n_reset + 1, x
                    continue
                else:
                    return SolverOutput(x, Status.CONVERGED, "feasible and step / predicted reduction below "
                                        "tolerance", nit=it, extra=self._extra(log, n_rej, chi, n_reset))
            if dn == 0.0 or pred <= 0.0:  # no descent for the model of the merit
                if viol > self.eps_c and mu < MU_MAX:
                    mu *= 10.0  # [OWN] stationary for the merit but infeasible: weigh feasibility more
                    continue
                if self.stuck_reset and viol > self.eps_c and n_upd > 0:
                    # [OWN] item 27: infeasible with the weight at its cap: the quasi-Newton curvatures
                    # can be what stops it (CRESC4: up to 1e8, steps of 1e-8 that gained 1e6 times their
                    # prediction, violation stuck at 1.5); once more from the unit model, as item 13
                    # does at a stop far from stationary
                    sigma = self._unit_model(ev, x, sf, oracle.n)
                    n_upd, n_reset, x_reset = 0, n_reset + 1, x
                    continue
                return SolverOutput(x, Status.FAILED if viol > self.eps_c else Status.CONVERGED,
                                    "no descent step for the l1 merit (stationary for the model)", nit=it,
                                    extra=self._extra(log, n_rej, n_reset=n_reset))
            xt = np.minimum(np.maximum(x + d, lo), up)  # np.clip, without its wrapper
            evt = scaled(oracle.evaluate(xt))
            ok = _finite(evt)
            phit = evt["f"] + mu * evt["l1"] if ok else math.inf
            # non-monotone ratio (against the worst of the last few accepted merits) so that a
            # step along a curved constraint is not rejected by the l1 merit (Maratos effect)
            phi_ref = max(phi, max([e["f"] + mu * e["l1"] for e in recent]))
            ratio = (phi_ref - phit) / pred
            n_soc_step = 0
            risen = ok and ratio < self.eta and evt["l1"] > ev["l1"]
            if self.second_order_correction and risen:
                # [OWN] second-order correction (Fletcher 1982): the linearization at x shifted to the
                # constraint values at the trial point, so the corrected step follows curved constraints
                # where the l1 merit rejected the plain one (Maratos effect; HS27, HS47).  One more point.
                rs = self._qp(ev["g"], sigma, evt["ineq"] - ev["ineq_jac"] @ d, ev["ineq_jac"],
                              evt["eq"] - ev["eq_jac"] @ d, ev["eq_jac"], d_lo, d_up, mu)
                if rs.ok and _inf_norm(rs.d) > 0.0:
                    xc = np.minimum(np.maximum(x + rs.d, lo), up)
                    evc = scaled(oracle.evaluate(xc))
                    if _finite(evc):
                        ratio_c = (phi_ref - (evc["f"] + mu * evc["l1"])) / pred
                        if ratio_c >= self.eta:
                            xt, evt, ratio, n_soc_step = xc, evc, ratio_c, 1
            log.append({"i": it, "f": ev["f"], "max_violation": viol, "rho": rho,
                        "sigma": sigma.diagonal().copy() if sigma.ndim == 2 else sigma, "mu": mu,
                        "ratio": ratio, "elastic": res.elastic, "pred": pred, "dn": dn,
                        "soc": n_soc_step, "probe": probing})
            lam_new, nu_new = res.lam, res.nu
            dx = xt - x
            if ok:
                s = self._curvature(ev, evt, lam_new, nu_new, dx)
                if s is not None and math.isfinite(s):
                    s_last = s
            if ok and (self.constraint_curvature or self.stuck_curvature or rise_curvature) and (has_ineq or has_eq):
                # eq. (3.6) at the new iterate xt from the old one, or, the iterate staying, at x from
                # the rejected trial point
                last_step = (ev, x, evt, xt) if ratio >= self.eta else (evt, xt, ev, x)
            if ratio >= self.eta:
                # [OWN] whether this step came from a model with curvature information: the first one
                # comes from P[0] = I, whose scale is arbitrary, so a small change of f along it says
                # nothing about stationarity (FLETBV3M: |g| = 1e-5, stopped by (3.11) after one step)
                informed = n_upd > 0
                if ok and s is not None:
                    sigma = self._update(sigma, s, ev, evt, lam_new, nu_new, dx, first=n_upd == 0)
                    n_upd += 1
                if ratio >= 0.25 and dn >= 0.99 * rho:  # the box limited a useful step
                    rho *= 2.0
                f_change = abs(evt["raw"]["f"] - ev["raw"]["f"]) / (1.0 + abs(ev["raw"]["f"]))  # unscaled f
                interior = dn < 0.99 * rho  # the full QP step, not cut by the move limit
                x, ev = xt, evt
                full_feasible = informed and interior and viol <= self.eps_c and evt["viol"] <= self.eps_c
                # [OWN] item 22: a crawl.  Near a degenerate minimizer (DENSCHND's is quartic; WATSON)
                # every step gains what the BFGS model predicts (the logged ratio reads 4 only because
                # the non-monotone reference is the worst of the last 4 accepted points), yet the steps
                # and the predicted reductions stay above their tests while f falls by 1e-13 per step,
                # to the cap or the time limit.  At this rate the remaining iterations could not move
                # f by 1e-7.
                window = (window + [float(evt["raw"]["f"])])[-self.stall_window - 1:] if full_feasible else []
                stop = None
                if full_feasible and ratio >= 0.75 and f_change < self.eps_df:
                    stop = "feasible full step with normalized change of f < eps_df (as 3.11)"
                elif (len(window) > self.stall_window
                      and window[0] - window[-1] < self.eps_stall * (1.0 + abs(window[-1]))):
                    stop = f"f lowered by less than eps_stall over the last {self.stall_window} full steps"
                if stop is not None:
                    window = []
                    if self._restart_before_stop(restarted, n_upd):
                        sigma, restarted = self._spherical_restart(s_last, oracle.n), True
                        recent = [evt]
                        continue
                    chi = self._stationarity(ev, x, lo, up, res, sf)
                    if chi > self.eps_kkt:  # x is a new point here
                        sigma, rho = self._unit_model(ev, x, sf, oracle.n), max(rho, chi * xs)
                        n_upd, n_reset, x_reset = 0, n_reset + 1, x
                        recent = [evt]
                        continue
                    return SolverOutput(x, Status.CONVERGED, stop, nit=it, extra=self._extra(log, n_rej, chi, n_reset))
                c = self._objective_rescale(sf, evt["raw"]["g"], sigma) if rescalable else 1.0
                if c > 1.0:  # `scaled` reads sf; the non-monotone reference restarts in the new units
                    sf, sigma, recent = sf * c, sigma * c, []
                    ev = evt = scaled(evt["raw"])
                    rescalable = self.rescale_f * sf < 1.0
                recent = (recent + [evt])[-self.memory:]
            else:
                n_rej += 1
                if not probing:  # the probe's step was far inside the limit: shrinking to it would collapse it
                    rho = self.shrink * dn
                # [OWN] the model's first curvature is not taken from a trial whose curvature (3.6) is
                # beyond the cap: the model would start at sigma_max in every direction and keep it in
                # those its steps do not explore (OSBORNEA, SSBRYBND: overflowing exponentials at the
                # first trial, curvature 1e42; the run crawled on steps of 1e-5 to the iteration cap)
                informative = ok and s is not None and (n_upd > 0 or s <= self.sigma_max)
                if informative and self.curvature == "bfgs":  # secant information of the trial
                    sigma = self._update(sigma, s, ev, evt, lam_new, nu_new, dx, first=n_upd == 0)
                    n_upd += 1
                elif informative:  # the model was too optimistic along d: only raise curvatures
                    sigma = np.maximum(sigma, self._update(sigma, s, ev, evt, lam_new, nu_new, dx, first=n_upd == 0))
                    n_upd += 1
                if rho / xs < 1e-3 * self.eps_x:
                    return SolverOutput(x, Status.CONVERGED if viol <= self.eps_c else Status.FAILED,
                                        "move limit collapsed", nit=it, extra=self._extra(log, n_rej, n_reset=n_reset))
        return SolverOutput(x, Status.MAX_ITER, f"max_iter = {self.max_iter} iterations reached",
                            nit=self.max_iter, extra=self._extra(log, n_rej, n_reset=n_reset))

    @staticmethod
    def _extra(log: list[dict[str, Any]], n_rej: int, chi: float | None = None, n_reset: int = 0) -> dict[str, Any]:
        """The run's record: rejected trials, resets to the unit model, the stationarity measure
        of `_unit_model_step` where a stopping test ended the run, and the iteration log."""
        out: dict[str, Any] = {"n_rejected": n_rej, "n_reset": n_reset, "iterations": log}
        if chi is not None:
            out["unit_model_step"] = chi
        return out
