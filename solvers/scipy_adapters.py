"""Established unconstrained solvers through `scipy.optimize.minimize`.

``scipy-cg`` (SciPy's nonlinear CG, Polak-Ribiere with Wolfe line search),
``scipy-bfgs`` and ``scipy-lbfgsb``. Value and gradient are returned together
(``jac=True`` with `Oracle.f_and_grad`), so SciPy's own counters are never used:
N^fg comes from the oracle. Each adapter has a ``STATUS_MAP`` from SciPy's integer
``status`` to our `Status` (tested in tests/solvers/test_scipy_adapters.py).

Option names follow the thesis (eps_g, max_iter) and are mapped to SciPy's
(gtol, maxiter); SciPy's other settings stay at its defaults unless exposed here.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np
from scipy.optimize import minimize

from problems import Oracle, Problem

from ._base import AbstractSolver, at_least, final, nonneg, option
from ._result import SolverOutput, Status

__all__ = ["AbstractScipyMinimize", "ScipyCG", "ScipyBFGS", "ScipyLBFGSB"]

# scipy.optimize._optimize: 0 success, 1 maxiter, 2 precision loss (line search failed), 3 NaN
_GRADIENT_METHODS_STATUS = {0: Status.CONVERGED, 1: Status.MAX_ITER, 2: Status.FAILED, 3: Status.ERROR}


@dataclasses.dataclass(frozen=True)
class AbstractScipyMinimize(AbstractSolver):
    """Shared adapter: subclasses give ``method``, ``STATUS_MAP`` and `_options`."""

    family = "established"
    method: ClassVar[str]
    STATUS_MAP: ClassVar[Mapping[int, Status]]

    eps_g: float = option(1e-5, "gradient tolerance (SciPy gtol)", "Sec. 2.5 eps_g", check=nonneg())
    max_iter: int = option(20_000, "iteration cap (SciPy maxiter)", "Tables 2.1-2.2 caps", check=at_least(1))
    max_fg: int | None = option(None, "cap on N^fg, checked after each iteration (None = no cap)",
                                "Tables 2.1-2.2 print '> N' in the N^fg column", check=at_least(1, or_none=True))

    def _options(self) -> dict[str, Any]:
        raise NotImplementedError

    def _bounds(self, oracle: Oracle) -> Any:
        return None

    @classmethod
    def map_status(cls, status: int) -> Status:
        """Our status for a SciPy status integer (unknown codes -> failed)."""
        return cls.STATUS_MAP.get(int(status), Status.FAILED)

    def minimize(self, oracle: Oracle) -> SolverOutput:
        capped = []

        def callback(intermediate_result):
            # SciPy ends the run when a callback raises StopIteration (status 99)
            if self.max_fg is not None and oracle.nfg >= self.max_fg:
                capped.append(oracle.nfg)
                raise StopIteration

        res = minimize(oracle.f_and_grad, oracle.x0, jac=True, method=self.method,
                       bounds=self._bounds(oracle), options=self._options(), callback=callback)
        status, message = self.map_status(res.status), f"scipy {self.method}: {res.message}"
        if capped:
            status, message = Status.MAX_ITER, f"N^fg cap max_fg = {self.max_fg} reached"
        return SolverOutput(np.asarray(res.x, dtype=float), status, message,
                            nit=int(getattr(res, "nit", 0) or 0), extra={"scipy_status": int(res.status)})


@final
@dataclasses.dataclass(frozen=True)
class ScipyCG(AbstractScipyMinimize):
    """SciPy's nonlinear conjugate gradient method (``method="CG"``)."""

    name = "scipy-cg"
    summary = "scipy.optimize.minimize(method='CG'): Polak-Ribiere CG with Wolfe line search"
    method = "CG"
    STATUS_MAP = _GRADIENT_METHODS_STATUS

    norm: float = option(2.0, "norm of the gradient test (thesis: Euclidean)", "Sec. 2.5")

    def _options(self) -> dict[str, Any]:
        return {"gtol": self.eps_g, "maxiter": self.max_iter, "norm": self.norm}


@final
@dataclasses.dataclass(frozen=True)
class ScipyBFGS(AbstractScipyMinimize):
    """SciPy's BFGS (dense n x n inverse Hessian: skipped above ``max_n`` variables).

    SciPy updates the inverse Hessian with two dense matrix products, O(n^3) flops per
    iteration, so large problems are left out rather than run for hours.
    """

    name = "scipy-bfgs"
    summary = "scipy.optimize.minimize(method='BFGS') (dense; n <= max_n)"
    method = "BFGS"
    STATUS_MAP = _GRADIENT_METHODS_STATUS

    norm: float = option(2.0, "norm of the gradient test (thesis: Euclidean)", "Sec. 2.5")
    max_n: int = option(200, "largest n run (SciPy's dense BFGS update costs O(n^3) per iteration)", "")

    def can_solve(self, problem: Problem) -> str | None:
        if problem.n > self.max_n:
            return f"{self.name}: n = {problem.n} > max_n = {self.max_n} (dense O(n^3) update per iteration)"
        return super().can_solve(problem)

    def _options(self) -> dict[str, Any]:
        return {"gtol": self.eps_g, "maxiter": self.max_iter, "norm": self.norm}


@final
@dataclasses.dataclass(frozen=True)
class ScipyLBFGSB(AbstractScipyMinimize):
    """SciPy's L-BFGS-B (bounds passed through)."""

    name = "scipy-lbfgsb"
    summary = "scipy.optimize.minimize(method='L-BFGS-B')"
    method = "L-BFGS-B"
    handles = frozenset({"bounds"})
    # scipy/optimize/_lbfgsb_py.py: 0 converged (gradient or relative f reduction),
    # 1 maxiter or maxfun reached, 2 abnormal termination (line search failed)
    STATUS_MAP = {0: Status.CONVERGED, 1: Status.MAX_ITER, 2: Status.FAILED}

    max_fun: int | None = option(None, "cap on SciPy's function evaluations (None: max_iter)", "")
    maxcor: int = option(10, "number of stored correction pairs", "SciPy default")
    ftol: float = option(2.220446049250313e-09, "relative f-reduction stop (SciPy ftol)", "SciPy default")

    def _options(self) -> dict[str, Any]:
        return {"gtol": self.eps_g, "maxiter": self.max_iter, "maxfun": self.max_fun or self.max_iter,
                "maxcor": self.maxcor, "ftol": self.ftol}

    def _bounds(self, oracle: Oracle) -> Any:
        if not oracle.has_bounds:
            return None
        lo = [None if not np.isfinite(v) else float(v) for v in oracle.lower]
        up = [None if not np.isfinite(v) else float(v) for v in oracle.upper]
        return list(zip(lo, up))
