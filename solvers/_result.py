"""One result type for every solver (after SciPy's `OptimizeResult`)."""

from __future__ import annotations

import dataclasses
import enum
from typing import Any

import numpy as np

__all__ = ["Status", "Result", "SolverOutput"]


class Status(str, enum.Enum):
    """How a run ended. ``converged`` is the only success status."""

    CONVERGED = "converged"
    MAX_ITER = "max_iter"
    FAILED = "failed"
    ERROR = "error"
    TIMEOUT = "timeout"

    @property
    def message(self) -> str:
        return {
            "converged": "termination criteria satisfied",
            "max_iter": "iteration or evaluation limit reached",
            "failed": "solver stopped without meeting its termination criteria",
            "error": "exception or non-finite value in the solver or the problem",
            "timeout": "wall-clock time limit exceeded",
        }[self.value]

    def __str__(self) -> str:  # stored as plain strings in results
        return self.value


@dataclasses.dataclass
class SolverOutput:
    """What a solver's ``minimize`` returns; counts and f are added by `solve`."""

    x: np.ndarray
    status: Status
    message: str = ""
    nit: int = 0
    extra: dict[str, Any] = dataclasses.field(default_factory=dict)


@dataclasses.dataclass(frozen=True)
class Result:
    """The outcome of one solver on one problem.

    Every count is measured by the counting oracle (`problems.Oracle`), never taken
    from the solver: ``nfg`` distinct evaluation points (thesis N^fg), ``nf``/``ng``
    objective/gradient executions (finite differences included in ``nf``), ``nc``/``nj``
    constraint/Jacobian executions, ``nh`` Hessian evaluations.

    ``f`` and ``max_violation`` are recomputed at ``x`` outside the count, so they are
    true values even for solvers (LFOP) that never evaluate f.
    ``history`` is an array of rows [nfg, f, max_violation], one per distinct point.
    """

    solver: str
    problem: str
    x: np.ndarray
    f: float
    status: Status
    message: str
    nfg: int
    nf: int
    ng: int
    nc: int
    nj: int
    nh: int
    nit: int
    max_violation: float
    success: bool
    wall_time: float
    time_in_evals: float
    options: dict[str, Any]
    history: np.ndarray
    extra: dict[str, Any] = dataclasses.field(default_factory=dict)

    def __repr__(self) -> str:
        return (
            f"Result(solver={self.solver!r}, problem={self.problem!r}, status={self.status.value!r}, "
            f"f={self.f:.10g}, nfg={self.nfg}, nit={self.nit}, max_violation={self.max_violation:.2e})"
        )
