"""The options and the run of the three-phase penalty scheme (thesis Appendix B.4), shared by LFOPC and ETOPC.

`PenaltyPhases` is a dataclass part (not a solver): the two gradient-only constrained
solvers inherit its six options and differ only in the unconstrained core they run in
each phase (LFOP or ETOP).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from problems import Oracle

from ._base import nonneg, option, positive
from ._penalty import Core, OracleForm, PenaltyForm, ThreePhaseResult, three_phase
from ._result import SolverOutput, Status

__all__ = ["PenaltyPhases", "phases_output"]


@dataclasses.dataclass(frozen=True)
class PenaltyPhases:
    """Penalty parameters and phase-2 rules of the three-phase scheme (eqs. B.6, B.7)."""

    mu0: float = option(1e2, "phase-0 penalty parameter", "App. B.4 [THESIS] (ETOPC: by analogy with LFOPC [OWN])",
                        check=positive())
    mu1: float = option(1e4, "phase-1/2 penalty parameter (>= mu0)",
                        "App. B.4 [THESIS] (ETOPC: by analogy with LFOPC [OWN])", check=positive())
    phase2_exterior: bool = option(True, "keep the exterior penalty on inactive inequalities in phase 2 "
                                   "(False: eq. B.7 literally)", "[OWN] (B.7 lets phase 2 run away on "
                                   "non-convex subproblems, e.g. Dynamic-Q on HS23)")
    scale_constraints: bool = option(False, "in minimize(oracle): penalty weight alpha_j = mu/||grad g_j(x0)||^2 "
                                     "per constraint (walls of equal stiffness) instead of one mu",
                                     "eq. (B.6) allows alpha_j, beta_k per constraint [THESIS]; choice [OWN]")
    phase2_tol: float = option(1e-10, "phase 2 also ends when every active constraint satisfies |g_j|, |h_k| <= "
                               "phase2_tol (0 = gradient test only)", "[OWN] (Q_a's minimum is 0; at degenerate "
                               "intersections, e.g. the cusp of HS13, its gradient test takes thousands of steps)",
                               check=nonneg())
    active_tol: float = option(0.0, "g_j(x*(mu1)) > active_tol marks constraint j active for phase 2",
                               "App. B.4 '> 0' [THESIS]; tolerance [OWN]", check=nonneg())

    def _check_mu(self, name: str) -> None:
        if not self.mu0 <= self.mu1:
            raise ValueError(f"{name}: need 0 < mu0 <= mu1 < inf, got mu0={self.mu0}, mu1={self.mu1}")

    def _three_phase(self, form: PenaltyForm, x0: np.ndarray, core: Core, **kw: Any) -> ThreePhaseResult:
        return three_phase(form, x0, core, self.mu0, self.mu1, self.active_tol,
                           phase2_exterior=self.phase2_exterior, phase2_tol=self.phase2_tol, **kw)

    def _oracle_form(self, oracle: Oracle) -> OracleForm:
        form = OracleForm(oracle)
        if self.scale_constraints:
            form.scale_by_gradients(oracle.x0)
        return form



def phases_output(res: ThreePhaseResult, max_steps: int) -> SolverOutput:
    """Status and message from the phase end reasons."""
    reasons = [ph.reason for ph in res.phases]
    msg = "; ".join(f"phase {ph.phase}: {ph.reason} after {ph.ng} gradients" for ph in res.phases)
    if "nonfinite" in reasons:
        status = Status.ERROR
    elif res.converged:
        status = Status.CONVERGED
    else:
        status = Status.MAX_ITER
        msg += f" (cap {max_steps} per phase)"
    extra = res.summary()
    return SolverOutput(res.x, status, msg, nit=res.ng, extra=extra)
