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

from ._base import AbstractSolver, at_least, between, final, nonneg, one_of, option, positive
from ._penalty import PenaltyForm, ThreePhaseResult
from ._penalty_phases import PenaltyPhases, phases_output
from ._result import SolverOutput
from .etop import EtopParams, etop

__all__ = ["ETOPC"]


@final
@dataclasses.dataclass(frozen=True)
class ETOPC(PenaltyPhases, AbstractSolver):
    """ETOPC-recon: PR conjugate gradients, gradient-only Euler-trapezium steps, three-phase penalty.

    A documented reconstruction (thesis Section 4.4 gives only the idea); see
    `solvers.etop` and docs/thesis_solvers.md.
    """

    name = "etopc"
    summary = "ETOPC-recon: gradient-only PR conjugate gradients + three-phase penalty (reconstruction of Sec. 4.4)"
    family = "thesis"
    handles = frozenset({"bounds", "ineq", "eq"})

    beta: str = option("PR", "'PR' (Polak-Ribiere+, used in the thesis) or 'FR'", "Sec. 4.4 [THESIS]; PR+ [OWN]",
                       check=one_of("PR", "FR"))
    eps_g: float = option(1e-5, "per-phase stop: ||grad Q|| <= eps_g", "[OWN] (Ch. 4 used 1e-3)", check=nonneg())
    eps_x: float = option(1e-8, "per-phase stop: accepted step shorter than eps_x", "[OWN]", check=nonneg())
    h0: float = option(1.0, "first trial step length", "[OWN]", check=positive())
    gamma: float = option(2.0, "growth of the Euler trial steps", "[OWN]", check=at_least(1))
    max_line: int = option(20, "gradients per line search", "[OWN]", check=at_least(2))
    eta: float = option(0.1, "accept the step when |phi| <= eta |phi(0)|", "[OWN]", check=between(0, 1))
    max_steps: int = option(10_000, "per-phase cap on gradient evaluations", "[OWN]", check=at_least(1))
    max_step: float = option(math.inf, "largest step along one direction", "[OWN]", check=positive(finite=False))

    def check_together(self) -> None:
        self._check_mu(self.name)
        self.etop_params()  # EtopParams's own checks (the function API's front door)

    def etop_params(self) -> EtopParams:
        return EtopParams(beta=self.beta, eps_g=self.eps_g, eps_x=self.eps_x, h0=self.h0, gamma=self.gamma,
                          max_line=self.max_line, eta=self.eta, max_steps=self.max_steps, max_step=self.max_step)

    def solve_form(self, form: PenaltyForm, x0: np.ndarray) -> ThreePhaseResult:
        """Run the three phases on a penalty form from ``x0``."""
        params = self.etop_params()
        return self._three_phase(form, x0, lambda grad, x, **kw: etop(grad, x, params, **kw))

    def minimize(self, oracle: Oracle) -> SolverOutput:
        out = phases_output(self.solve_form(self._oracle_form(oracle), oracle.x0), self.max_steps)
        out.extra["reconstruction"] = "ETOPC-recon (algorithms.md section 5)"
        return out
