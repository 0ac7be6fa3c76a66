"""LFOPC: the leap-frog method with the three-phase penalty scheme (thesis Appendix B.4).

Two layers, so that the same algorithm serves a benchmark problem and a function-free
subproblem:

(a) `LFOPC.solve_form(form, x0)` runs the algorithm on a *penalty form*
    (`solvers._penalty.PenaltyForm`: gradient of f, constraint values and Jacobians,
    bounds).  Dynamic-Q calls it on its spherical quadratic subproblems; other code
    calls it on small problems given by callables, e.g. the cable-tension QP (6.17)::

        from solvers.lfopc import LFOPC, PenaltyForm
        form = PenaltyForm(n=m, grad_f=lambda t: 2 * t,
                           eq=lambda t: S @ t + w, eq_jac=lambda t: S,
                           lower=t_min, upper=t_max)
        res = LFOPC().solve_form(form, x0)     # res.x, res.max_violation, res.ng

(b) `LFOPC.minimize(oracle)` feeds (a) from the counting oracle.  LFOPC is
    gradient-only: it never evaluates f (the front door reports f at the end,
    uncounted); every point where the penalty gradient is formed is one N^g.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from problems import Oracle

from ._base import AbstractSolver, at_least, final, nonneg, one_of, option, positive
from ._penalty import PenaltyForm, ThreePhaseResult
from ._penalty_phases import PenaltyPhases, phases_output
from ._result import SolverOutput
from .lfop import LfopParams, lfop

__all__ = ["LFOPC", "PenaltyForm"]  # PenaltyForm re-exported: the function-free entry point


@final
@dataclasses.dataclass(frozen=True)
class LFOPC(PenaltyPhases, AbstractSolver):
    """Leap-frog optimizer for constrained problems (Snyman 2000; thesis Appendix B).

    Phase 0: LFOP on the exterior penalty function Q(x, mu0) (eq. B.6) from x0;
    phase 1: LFOP on Q(x, mu1) from x*(mu0), active set I_a = {j : g_j(x*(mu1)) > 0};
    phase 2: LFOP on Q_a = mu1 (sum_{I_a} g_j^2 + sum h_k^2) (eq. B.7) from x*(mu1).
    Bounds are inequalities.  The LFOP heuristics are those of algorithms.md section 1;
    the stiffness guard (section 1.6, our addition) is on by default.
    """

    name = "lfopc"
    summary = "Leap-frog dynamic trajectory method with three-phase penalty (thesis App. B)"
    family = "thesis"
    handles = frozenset({"bounds", "ineq", "eq"})

    carry_dt: bool = option(True, "start phases 1 and 2 with the time step reached in the previous phase "
                            "(x sqrt(mu0/mu1) into phase 1) instead of dt0", "[OWN] (dt0 next to a stiff wall "
                            "first leaps far across it)")
    delta: float = option(1.0, "LFOP maximum step length", "[CILIB] LFDecorator delta = 1; [MLA3]", check=positive())
    dt0: float = option(0.5, "LFOP initial time step", "[CILIB] defaultDeltaT = 0.5; [MLA3]", check=positive())
    m: int = option(3, "acceleration reversals at the step limit before dt is halved", "[CILIB] m = 3; [MLA3]",
                    check=at_least(1))
    delta1: float = option(1e-3, "increment of the time-step magnification factor", "[CILIB]; [MLA3] code",
                           check=nonneg())
    j0: int = option(2, "interferences keeping a reduced velocity before it is zeroed", "[CILIB] j = 2; [MLA3] ix = 2",
                     check=at_least(1))
    eps_g: float = option(1e-5, "per-phase stop: ||grad Q|| <= eps_g", "[MLA3] tol = 1e-5", check=nonneg())
    max_steps: int = option(10_000, "per-phase cap on gradient evaluations", "[OWN]", check=at_least(1))
    eps_x: float = option(0.0, "per-phase stop on step length (0 = off)", "[OWN]", check=nonneg())
    dt_mode: str = option("fixed", "'fixed' (dt0) or 'auto' (first step delta/10)", "[CILIB] / [RECALL]",
                          check=one_of("fixed", "auto"))
    interference_anchor: str = option("moving", "'moving' [CILIB] or 'fixed' [MLA3] midpoint anchor",
                                      "algorithms.md 1.3 step 9", check=one_of("moving", "fixed"))
    stiffness_guard: bool = option(True, "cap dt by the curvature along the last move (penalty walls)",
                                   "[OWN] algorithms.md 1.6")
    kappa_fac: float = option(0.5, "stiffness guard target dt*sqrt(kappa)", "[OWN] algorithms.md 1.6", check=positive())

    def check_together(self) -> None:
        self._check_mu(self.name)
        self.lfop_params()  # LfopParams's own checks (the function API's front door)

    def lfop_params(self) -> LfopParams:
        """The LFOP parameters used in every phase."""
        return LfopParams(delta=self.delta, dt0=self.dt0, m=self.m, delta1=self.delta1, j0=self.j0,
                          eps_g=self.eps_g, max_steps=self.max_steps, eps_x=self.eps_x, dt_mode=self.dt_mode,
                          interference_anchor=self.interference_anchor, stiffness_guard=self.stiffness_guard,
                          kappa_fac=self.kappa_fac)

    def solve_form(self, form: PenaltyForm, x0: np.ndarray) -> ThreePhaseResult:
        """Run the three phases on a penalty form from ``x0`` (no function values used)."""
        params = self.lfop_params()
        return self._three_phase(form, x0, lambda grad, x, **kw: lfop(grad, x, params, **kw), carry_dt=self.carry_dt)

    def minimize(self, oracle: Oracle) -> SolverOutput:
        res = self.solve_form(self._oracle_form(oracle), oracle.x0)
        return phases_output(res, self.max_steps)

