"""ETOPC: gradient-only Polak-Ribiere conjugate gradients with LFOPC's penalty phases.

RECONSTRUCTION (``ETOPC-recon``).  The thesis (Section 4.4) names EtopC, the
gradient-only CG method of Snyman (1985) with Euler-trapezium step selection and
Polak-Ribiere directions, but gives neither its step-size procedure nor its treatment
of constraints.  We use our reconstruction of the unconstrained method (`solvers.etop`,
algorithms.md 5.1) inside the same three-phase penalty scheme as LFOPC (Appendix B.4:
Q(., mu0 = 1e2), Q(., mu1 = 1e4), then Q_a on the active set), algorithms.md 5.2 [OWN].
Like LFOPC it is gradient-only and never evaluates f; every point is one N^g.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from problems import Oracle

from ._base import AbstractSolver, option
from ._penalty import OracleForm, PenaltyForm, ThreePhaseResult, three_phase
from ._result import SolverOutput
from .etop import EtopParams, etop
from .lfopc import _output

__all__ = ["ETOPC"]


@dataclasses.dataclass(frozen=True)
class ETOPC(AbstractSolver):
    """ETOPC-recon: PR conjugate gradients, gradient-only Euler-trapezium steps, three-phase penalty.

    A documented reconstruction (thesis Section 4.4 gives only the idea); see
    `solvers.etop` and docs/thesis_solvers.md.
    """

    name = "etopc"
    summary = "ETOPC-recon: gradient-only PR conjugate gradients + three-phase penalty (reconstruction of Sec. 4.4)"
    family = "thesis"
    handles = frozenset({"bounds", "ineq", "eq"})

    mu0: float = option(1e2, "phase-0 penalty parameter", "App. B.4 [THESIS] (by analogy with LFOPC [OWN])")
    mu1: float = option(1e4, "phase-1/2 penalty parameter", "App. B.4 [THESIS] (by analogy with LFOPC [OWN])")
    phase2_exterior: bool = option(True, "keep the exterior penalty on inactive inequalities in phase 2 "
                                   "(False: eq. B.7 literally)", "[OWN] (B.7 lets phase 2 run away on "
                                   "non-convex subproblems, e.g. Dynamic-Q on HS23)")
    scale_constraints: bool = option(False, "in minimize(oracle): penalty weight alpha_j = mu/||grad g_j(x0)||^2 "
                                     "per constraint (walls of equal stiffness) instead of one mu",
                                     "eq. (B.6) allows alpha_j, beta_k per constraint [THESIS]; choice [OWN]")
    phase2_tol: float = option(1e-10, "phase 2 also ends when every active constraint satisfies |g_j|, |h_k| <= "
                               "phase2_tol (0 = gradient test only)", "[OWN] (Q_a's minimum is 0; at degenerate "
                               "intersections, e.g. the cusp of HS13, its gradient test takes thousands of steps)")
    active_tol: float = option(0.0, "g_j(x*(mu1)) > active_tol marks constraint j active for phase 2", "[OWN]")
    beta: str = option("PR", "'PR' (Polak-Ribiere+, used in the thesis) or 'FR'", "Sec. 4.4 [THESIS]; PR+ [OWN]")
    eps_g: float = option(1e-5, "per-phase stop: ||grad Q|| <= eps_g", "[OWN] (Ch. 4 used 1e-3)")
    eps_x: float = option(1e-8, "per-phase stop: accepted step shorter than eps_x", "[OWN]")
    h0: float = option(1.0, "first trial step length", "[OWN]")
    gamma: float = option(2.0, "growth of the Euler trial steps", "[OWN]")
    max_line: int = option(20, "gradients per line search", "[OWN]")
    eta: float = option(0.1, "accept the step when |phi| <= eta |phi(0)|", "[OWN]")
    max_steps: int = option(10_000, "per-phase cap on gradient evaluations", "[OWN]")
    max_step: float = option(math.inf, "largest step along one direction", "[OWN]")

    def __post_init__(self) -> None:
        if not (np.isfinite(self.mu0) and np.isfinite(self.mu1) and 0 < self.mu0 <= self.mu1):
            raise ValueError(f"etopc: need 0 < mu0 <= mu1 < inf, got mu0={self.mu0}, mu1={self.mu1}")
        if not (self.phase2_tol >= 0):
            raise ValueError(f"etopc: phase2_tol must be >= 0, got {self.phase2_tol}")
        if not (self.active_tol >= 0):
            raise ValueError(f"etopc: active_tol must be >= 0, got {self.active_tol}")
        self.etop_params()

    def etop_params(self) -> EtopParams:
        return EtopParams(beta=self.beta, eps_g=self.eps_g, eps_x=self.eps_x, h0=self.h0, gamma=self.gamma,
                          max_line=self.max_line, eta=self.eta, max_steps=self.max_steps, max_step=self.max_step)

    def solve_form(self, form: PenaltyForm, x0: np.ndarray) -> ThreePhaseResult:
        """Run the three phases on a penalty form from ``x0``."""
        params = self.etop_params()
        return three_phase(form, x0, lambda grad, x, **kw: etop(grad, x, params, **kw), self.mu0, self.mu1,
                           self.active_tol, phase2_exterior=self.phase2_exterior, phase2_tol=self.phase2_tol)

    def _oracle_form(self, oracle: Oracle) -> OracleForm:
        form = OracleForm(oracle)
        if self.scale_constraints:
            form.scale_by_gradients(oracle.x0)
        return form

    def minimize(self, oracle: Oracle) -> SolverOutput:
        out = _output(self.solve_form(self._oracle_form(oracle), oracle.x0), self.max_steps)
        out.extra["reconstruction"] = "ETOPC-recon (algorithms.md section 5)"
        return out
