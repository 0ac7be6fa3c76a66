"""Adapters for SciPy's constrained minimizers: SLSQP, trust-constr and COBYLA.

Every function and derivative SciPy asks for is taken from the counting `Oracle`, so
the N^fg of these runs is measured exactly like the thesis's methods (Section 2.5).
Convention: ours g(x) <= 0, SciPy's "ineq" dicts want c(x) >= 0, so c = -g (SLSQP,
COBYLA); trust-constr takes g(x) in [-inf, 0] directly.

Each class has a ``STATUS_MAP`` from SciPy's ``OptimizeResult.status`` to `Status`.
"""

from __future__ import annotations

import dataclasses
import warnings
from typing import Any, ClassVar

import numpy as np
from scipy import optimize

from problems import Oracle, ProblemError

from ._base import AbstractSolver, at_least, final, option, positive
from ._result import SolverOutput, Status
from ._start import more_equalities_than_variables, start_in_bounds

__all__ = ["ScipySLSQP", "ScipyTrustConstr", "ScipyCOBYLA", "start_in_bounds"]


def _bounds(oracle: Oracle) -> optimize.Bounds | None:
    return optimize.Bounds(oracle.lower, oracle.upper) if oracle.has_bounds else None


@final
@dataclasses.dataclass(frozen=True)
class ScipySLSQP(AbstractSolver):
    """Sequential least-squares quadratic programming (Kraft 1988) via ``scipy.optimize``.

    The closest established relative of the SQP code of Table 3.1 (Powell's SQP as
    reported by Hock & Schittkowski): quasi-Newton SQP with an L1 merit line search.
    """

    name = "scipy-slsqp"
    summary = "SciPy SLSQP: quasi-Newton SQP (Kraft), bounds + inequality + equality constraints"
    family = "established"
    handles = frozenset({"bounds", "ineq", "eq"})

    STATUS_MAP: ClassVar[dict[int, Status]] = {
        0: Status.CONVERGED,   # Optimization terminated successfully
        1: Status.FAILED,      # function evaluation required (internal; never final)
        2: Status.FAILED,      # more equality constraints than variables
        3: Status.FAILED,      # more than 3n iterations in the LSQ subproblem
        4: Status.FAILED,      # inequality constraints incompatible
        5: Status.FAILED,      # singular matrix E in LSQ subproblem
        6: Status.FAILED,      # singular matrix C in LSQ subproblem
        7: Status.FAILED,      # rank-deficient equality constraint subproblem
        8: Status.FAILED,      # positive directional derivative in the line search
        9: Status.MAX_ITER,    # iteration limit reached
        -1: Status.FAILED,     # gradient evaluation required (internal; never final)
    }

    ftol: float = option(1e-10, "SLSQP 'ftol': precision goal for f in the stopping test "
                         "(relative to the merit function)",
                         "SciPy default 1e-6; tightened so E^r <= 1e-5 is reachable", check=positive())
    maxiter: int = option(500, "iteration cap (SLSQP major iterations)", "SciPy default 100", check=at_least(1))

    def minimize(self, oracle: Oracle) -> SolverOutput:
        over = more_equalities_than_variables(
            oracle, "SLSQP mode 2", "with inequality constraints present SciPy's SLSQP writes past its workspace "
            "and corrupts the process's heap, scipy/scipy#25665", native_status=2)
        if over is not None:
            return over
        cons: list[dict[str, Any]] = []
        if oracle.n_ineq:
            cons.append({"type": "ineq", "fun": lambda x: -oracle.ineq(x), "jac": lambda x: -oracle.ineq_jac(x)})
        if oracle.n_eq:
            cons.append({"type": "eq", "fun": oracle.eq, "jac": oracle.eq_jac})
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # e.g. "Values in x were outside bounds" (SciPy clips)
            res = optimize.minimize(oracle.f_and_grad, start_in_bounds(oracle), jac=True, method="SLSQP",
                                    bounds=_bounds(oracle), constraints=cons,
                                    options={"ftol": self.ftol, "maxiter": self.maxiter})
        status = self.STATUS_MAP.get(int(res.status), Status.FAILED)
        return SolverOutput(res.x, status, f"SLSQP mode {res.status}: {res.message}", nit=int(res.get("nit", 0)),
                            extra={"native_status": int(res.status)})


@final
@dataclasses.dataclass(frozen=True)
class ScipyTrustConstr(AbstractSolver):
    """Trust-region interior-point / equality-constrained SQP (Byrd-Omojokun) via SciPy.

    Second derivatives are BFGS quasi-Newton approximations (SciPy's
    ``HessianUpdateStrategy``) for the objective and for every constraint; only first
    derivatives are requested from the oracle.
    """

    name = "scipy-trust-constr"
    summary = "SciPy trust-constr: trust-region interior point / Byrd-Omojokun SQP with BFGS Hessians"
    family = "established"
    handles = frozenset({"bounds", "ineq", "eq"})

    STATUS_MAP: ClassVar[dict[int, Status]] = {
        0: Status.MAX_ITER,    # maximum number of iterations / evaluations exceeded
        1: Status.CONVERGED,   # gtol: first-order optimality and constraint violation small
        2: Status.CONVERGED,   # xtol: trust radius smaller than xtol
        3: Status.FAILED,      # callback requested termination (not used here)
    }

    gtol: float = option(1e-8, "stop when the Lagrangian gradient norm and the constraint violation are below gtol",
                         "SciPy default 1e-8", check=positive())
    xtol: float = option(1e-10, "stop when the trust-region radius is below xtol", "SciPy default 1e-8",
                        check=positive())
    maxiter: int = option(1000, "iteration cap", "SciPy default 1000", check=at_least(1))

    def minimize(self, oracle: Oracle) -> SolverOutput:
        over = more_equalities_than_variables(
            oracle, "trust-constr", "its projections would raise SciPy's bare 'expected square matrix' ValueError")
        if over is not None:
            return over
        cons = []
        if oracle.n_ineq:
            cons.append(optimize.NonlinearConstraint(oracle.ineq, -np.inf, 0.0, jac=oracle.ineq_jac,
                                                     hess=optimize.BFGS()))
        if oracle.n_eq:
            cons.append(optimize.NonlinearConstraint(oracle.eq, 0.0, 0.0, jac=oracle.eq_jac, hess=optimize.BFGS()))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # delta_grad == 0 / singular Jacobian notes from SciPy
            try:
                res = optimize.minimize(oracle.f_and_grad, start_in_bounds(oracle), jac=True, hess=optimize.BFGS(),
                                        method="trust-constr", bounds=_bounds(oracle), constraints=cons,
                                        options={"gtol": self.gtol, "xtol": self.xtol, "maxiter": self.maxiter,
                                                 "verbose": 0})
            except ProblemError:
                raise  # a bad problem definition is an error, not a solver failure
            except ValueError as exc:
                if "infs or NaNs" not in str(exc):
                    raise
                # SciPy's linear algebra met a non-finite f, gradient or constraint value at a trial
                # point and cannot go on (S2MPJ HS101, HS103, HS112, HIMMELBJ, WATER)
                return SolverOutput(oracle.last_x, Status.FAILED, "trust-constr stopped: a non-finite f, gradient "
                                    f"or constraint value at a trial point (SciPy: {exc})")
        status = self.STATUS_MAP.get(int(res.status), Status.FAILED)
        return SolverOutput(res.x, status, f"trust-constr status {res.status}: {res.message}",
                            nit=int(res.get("nit", 0)), extra={"native_status": int(res.status)})


@final
@dataclasses.dataclass(frozen=True)
class ScipyCOBYLA(AbstractSolver):
    """COBYLA (Powell 1994; SciPy's PRIMA implementation): derivative-free baseline.

    Uses only f and the constraint values. Equality constraints h(x) = 0 are passed
    as the two inequalities h >= 0 and -h >= 0 (COBYLA's linear models treat them
    exactly; no tolerance band is added). Bounds are passed to PRIMA directly.
    """

    name = "scipy-cobyla"
    summary = "SciPy COBYLA (PRIMA): derivative-free linear-approximation trust region (baseline)"
    family = "established"
    handles = frozenset({"bounds", "ineq", "eq"})

    STATUS_MAP: ClassVar[dict[int, Status]] = {
        0: Status.CONVERGED,   # SMALL_TR_RADIUS: trust region shrank to tol
        1: Status.CONVERGED,   # FTARGET_ACHIEVED
        2: Status.FAILED,      # TRSUBP_FAILED
        3: Status.MAX_ITER,    # MAXFUN_REACHED
        20: Status.MAX_ITER,   # MAXTR_REACHED
        -1: Status.ERROR,      # NAN_INF_X
        -2: Status.ERROR,      # NAN_INF_F
        -3: Status.ERROR,      # NAN_INF_MODEL
        6: Status.FAILED,      # NO_SPACE_BETWEEN_BOUNDS
        7: Status.FAILED,      # DAMAGING_ROUNDING
        8: Status.FAILED,      # ZERO_LINEAR_CONSTRAINT
        30: Status.FAILED,     # CALLBACK_TERMINATE
        100: Status.ERROR,     # INVALID_INPUT
        101: Status.ERROR,     # ASSERTION_FAILS
        102: Status.ERROR,     # VALIDATION_FAILS
        103: Status.ERROR,     # MEMORY_ALLOCATION_FAILS
    }

    rhobeg: float = option(1.0, "initial trust-region radius (initial change of the variables)", "SciPy default",
                          check=positive())
    tol: float = option(1e-8, "final trust-region radius (accuracy in x)", "SciPy default 1e-4; tightened",
                       check=positive())
    maxfev: int = option(5000, "cap on function evaluations (each is one N^fg); PRIMA in Python costs ~10 ms per "
                         "evaluation, so this also bounds the run time", "SciPy default 1000", check=at_least(1))
    catol: float = option(1e-8, "absolute constraint-violation tolerance for PRIMA's own success test", "",
                         check=positive())

    def check_together(self) -> None:
        if self.tol > self.rhobeg:
            raise ValueError(f"{self.name}: tol ({self.tol}) must not exceed rhobeg ({self.rhobeg})")

    def minimize(self, oracle: Oracle) -> SolverOutput:
        cons: list[dict[str, Any]] = []
        if oracle.n_ineq:
            cons.append({"type": "ineq", "fun": lambda x: -oracle.ineq(x)})
        if oracle.n_eq:
            cons.append({"type": "ineq", "fun": oracle.eq})
            cons.append({"type": "ineq", "fun": lambda x: -oracle.eq(x)})
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = optimize.minimize(oracle.f, start_in_bounds(oracle), method="COBYLA", bounds=_bounds(oracle),
                                    constraints=cons, options={"rhobeg": self.rhobeg, "tol": self.tol,
                                                               "maxiter": self.maxfev, "catol": self.catol})
        status = self.STATUS_MAP.get(int(res.status), Status.FAILED)
        return SolverOutput(res.x, status, f"COBYLA status {res.status}: {res.message}",
                            extra={"native_status": int(res.status)})
