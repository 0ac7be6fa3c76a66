"""NLopt adapters: MMA (Svanberg's method of moving asymptotes) and SLSQP.

MMA is the thesis's other comparison: Table 3.1's last row reports Svanberg's MMA on
his polytope problem. NLopt's ``LD_MMA`` is Svanberg's 2002 globally convergent CCSA
variant. All values and gradients come from the counting `Oracle`.

Equality constraints. ``LD_MMA`` accepts only inequalities. We convert each h_k(x) = 0
into the two inequalities h_k - delta <= 0 and -h_k - delta <= 0 with a band
``eq_band`` (default 1e-7, below the 1e-6 feasibility tolerance of a "solved" run, so a
point accepted by the band is also counted feasible). A zero band would leave MMA's
conservative subproblems with an empty interior. ``LD_SLSQP`` takes equalities natively.

x0 is projected onto the bounds first (NLopt requires a start within them).

NLopt's failure results (FAILURE, INVALID_ARGS, OUT_OF_MEMORY) arrive as exceptions: in the
SWIG-built wheels as ``nlopt.runtime_error`` / ``nlopt.invalid_argument`` (subclasses of
``nlopt.exception``, not of Python's RuntimeError or ValueError) with an empty text. The
adapter turns them into the result code and NLopt's own reason (``opt.get_errmsg()``, e.g.
"bug: more than iter SQP iterations").

An exception from the problem's own functions inside NLopt's callbacks is re-raised by NLopt's
wrapper after it stops, indistinguishable from its failure results when it is a RuntimeError or
ValueError. The callbacks keep the first such exception and the adapter raises it after
``optimize`` returns, so that `solvers.solve` records status error with the problem's message.
`problems.BudgetExhausted` passes through the callbacks untouched and is handled by `solve`.

``nit``: NLopt reports no iteration count; ``nit`` is NLopt's own count of objective evaluations
(``opt.get_numevals()``: each call of the objective callback, with or without a gradient; the
constraint callbacks are not counted), 0 when the run ended on NLopt's ForcedStop. The oracle's
N^fg (``nfg``) is the cost reported.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from typing import Any, ClassVar, TypeVar

import nlopt
import numpy as np

from problems import BudgetExhausted, Oracle, ProblemError

from ._base import AbstractSolver, at_least, between, final, nonneg, option
from ._result import SolverOutput, Status
from ._start import more_equalities_than_variables, start_in_bounds

__all__ = ["NloptMMA", "NloptSLSQP", "STATUS_MAP"]

#: exceptions by which NLopt reports a failure result: SWIG's wrappers of C++'s std exceptions
#: (nlopt.exception and subclasses) in the PyPI wheels, Python's own in other builds
_NLOPT_FAILURES: tuple[type[BaseException], ...] = tuple(
    e for e in (getattr(nlopt, "exception", None), RuntimeError, ValueError) if isinstance(e, type))

#: NLopt result codes -> Status (the codes are NLopt's public enum values)
STATUS_MAP: dict[int, Status] = {
    nlopt.SUCCESS: Status.CONVERGED,            # 1
    nlopt.STOPVAL_REACHED: Status.CONVERGED,    # 2
    nlopt.FTOL_REACHED: Status.CONVERGED,       # 3
    nlopt.XTOL_REACHED: Status.CONVERGED,       # 4
    nlopt.MAXEVAL_REACHED: Status.MAX_ITER,     # 5
    nlopt.MAXTIME_REACHED: Status.TIMEOUT,      # 6
    nlopt.FAILURE: Status.FAILED,               # -1
    nlopt.INVALID_ARGS: Status.ERROR,           # -2
    nlopt.OUT_OF_MEMORY: Status.ERROR,          # -3
    nlopt.ROUNDOFF_LIMITED: Status.FAILED,      # -4
    nlopt.FORCED_STOP: Status.FAILED,           # -5
}

_F = TypeVar("_F", bound=Callable[..., Any])


class _Raised:
    """The first exception a callback raised (NLopt's wrapper would pass it off as a failure result)."""

    def __init__(self) -> None:
        self.first: BaseException | None = None

    def guard(self, fn: _F) -> _F:
        """``fn`` keeping the first exception it raises (BudgetExhausted excepted: it passes through as itself)."""

        @functools.wraps(fn)
        def call(*args: Any) -> Any:
            try:
                return fn(*args)
            except BudgetExhausted:
                raise
            except Exception as exc:
                if self.first is None:
                    self.first = exc
                raise

        return call  # type: ignore[return-value]  # the same signature

    def reraise(self) -> None:
        """Raise the kept exception, if any."""
        if self.first is not None:
            raise self.first


@dataclasses.dataclass(frozen=True)
class _NloptBase(AbstractSolver):
    """Shared set-up of an NLopt gradient-based local optimizer (not registered)."""

    algorithm: ClassVar[int]
    native_eq: ClassVar[bool]
    STATUS_MAP: ClassVar[dict[int, Status]] = STATUS_MAP

    ftol_rel: float = option(1e-12, "stop when |delta f| < ftol_rel |f| between iterations", "NLopt ftol_rel",
                             check=nonneg(finite=True))
    xtol_rel: float = option(1e-10, "stop when every |delta x_i| < xtol_rel |x_i|", "NLopt xtol_rel",
                             check=nonneg(finite=True))
    maxeval: int = option(3000, "cap on objective evaluations (NLopt's own count; the oracle's N^fg is reported)",
                          "NLopt maxeval", check=at_least(1))
    maxtime: float = option(0.0, "wall-clock limit in seconds, 0 = none (NLopt then ends with MAXTIME_REACHED); "
                            "any limit makes the end depend on machine load, so the default relies on maxeval and "
                            "the harness's per-run timeout", "NLopt maxtime; default [OWN] (determinism)",
                            check=nonneg(finite=True))
    constraint_tol: float = option(1e-8, "per-constraint feasibility tolerance given to NLopt", "NLopt mconstraint tol",
                                   check=nonneg(finite=True))
    eq_band: float = option(1e-7, "half-width delta of the band -delta <= h(x) <= delta used for equality "
                            "constraints when the algorithm has no native equalities (MMA)", "this module's doc",
                            check=nonneg(finite=True))

    def minimize(self, oracle: Oracle) -> SolverOutput:
        if self.native_eq:  # answered before any NLopt object is built
            over = more_equalities_than_variables(oracle, "NLopt result -2 (INVALID_ARGS)",
                                                  "its SLSQP rejects it with an empty invalid_argument",
                                                  native_status=int(nlopt.INVALID_ARGS))
            if over is not None:
                return over
        n = oracle.n
        opt = nlopt.opt(self.algorithm, n)
        raised = _Raised()

        @raised.guard
        def objective(x: np.ndarray, grad: np.ndarray) -> float:
            if grad.size:
                f, g = oracle.f_and_grad(x)
                grad[:] = g
                return f
            return oracle.f(x)

        opt.set_min_objective(objective)
        if oracle.has_bounds:
            opt.set_lower_bounds(oracle.lower)
            opt.set_upper_bounds(oracle.upper)
        m_i, m_e = oracle.n_ineq, oracle.n_eq
        if m_i:
            @raised.guard
            def ineq(result: np.ndarray, x: np.ndarray, grad: np.ndarray) -> None:
                result[:] = oracle.ineq(x)
                if grad.size:
                    grad[:] = oracle.ineq_jac(x)

            opt.add_inequality_mconstraint(ineq, [self.constraint_tol] * m_i)
        if m_e and self.native_eq:
            @raised.guard
            def eq(result: np.ndarray, x: np.ndarray, grad: np.ndarray) -> None:
                result[:] = oracle.eq(x)
                if grad.size:
                    grad[:] = oracle.eq_jac(x)

            opt.add_equality_mconstraint(eq, [self.constraint_tol] * m_e)
        elif m_e:
            band = self.eq_band

            @raised.guard
            def eq_as_ineq(result: np.ndarray, x: np.ndarray, grad: np.ndarray) -> None:
                h = oracle.eq(x)
                result[:] = np.concatenate([h - band, -h - band])
                if grad.size:
                    J = oracle.eq_jac(x)
                    grad[:] = np.vstack([J, -J])

            opt.add_inequality_mconstraint(eq_as_ineq, [self.constraint_tol] * (2 * m_e))
        self._configure(opt)
        opt.set_ftol_rel(self.ftol_rel)
        opt.set_xtol_rel(self.xtol_rel)
        opt.set_maxeval(self.maxeval)
        opt.set_maxtime(self.maxtime)
        x0 = start_in_bounds(oracle)
        try:
            return self._optimize(opt, x0, oracle)
        finally:  # an exception of the problem's (module doc), whatever NLopt made of it
            raised.reraise()

    def _optimize(self, opt: nlopt.opt, x0: np.ndarray, oracle: Oracle) -> SolverOutput:
        """Run NLopt from ``x0``: its result code, or its failure result, as a SolverOutput."""
        try:
            x = opt.optimize(x0)
            code = opt.last_optimize_result()
        except nlopt.RoundoffLimited:
            x, code = oracle.last_x, nlopt.ROUNDOFF_LIMITED
        except ProblemError:
            raise  # a bad problem definition is an error, not a solver failure
        except nlopt.ForcedStop as exc:
            return SolverOutput(oracle.last_x, Status.FAILED, f"NLopt stopped: ForcedStop: {exc}",
                                extra={"native_status": int(opt.last_optimize_result())})
        except _NLOPT_FAILURES as exc:
            # NLopt's failure results (module doc). BudgetExhausted from the oracle is re-raised
            # by NLopt's wrapper as itself and handled by solve().
            code = int(opt.last_optimize_result())
            reason = (opt.get_errmsg() if hasattr(opt, "get_errmsg") else None) or str(exc) or type(exc).__name__
            return SolverOutput(oracle.last_x, self.STATUS_MAP.get(code, Status.FAILED),
                                f"NLopt result {code} ({_code_name(code)}): {reason}", nit=int(opt.get_numevals()),
                                extra={"native_status": code})
        status = self.STATUS_MAP.get(int(code), Status.FAILED)
        return SolverOutput(np.asarray(x, dtype=float), status, f"NLopt result {code} ({_code_name(code)})",
                            nit=int(opt.get_numevals()), extra={"native_status": int(code)})

    def _configure(self, opt: nlopt.opt) -> None:
        """Algorithm-specific NLopt parameters (none by default)."""


def _code_name(code: int) -> str:
    names = {getattr(nlopt, k): k for k in ("SUCCESS", "STOPVAL_REACHED", "FTOL_REACHED", "XTOL_REACHED",
                                            "MAXEVAL_REACHED", "MAXTIME_REACHED", "FAILURE", "INVALID_ARGS",
                                            "OUT_OF_MEMORY", "ROUNDOFF_LIMITED", "FORCED_STOP")}
    return names.get(int(code), "unknown")


@final
@dataclasses.dataclass(frozen=True)
class NloptMMA(_NloptBase):
    """NLopt LD_MMA: Svanberg's method of moving asymptotes (CCSA, 2002 variant).

    Equalities become a band of half-width ``eq_band`` (see the module docstring).
    """

    name = "nlopt-mma"
    summary = "NLopt LD_MMA (Svanberg's MMA, the thesis's Table 3.1 comparison); equalities as a 1e-7 band"
    family = "established"
    handles = frozenset({"bounds", "ineq", "eq"})
    algorithm: ClassVar[int] = nlopt.LD_MMA
    native_eq: ClassVar[bool] = False

    dual_ftol_rel: float = option(1e-8, "relative f tolerance of MMA's inner dual subproblem. NLopt's default "
                                  "1e-14 made single HS runs take minutes (HS28: 100 s) with the same end point",
                                  "NLopt CCSA/MMA parameter 'dual_ftol_rel'", check=between(0, 1))
    dual_maxeval: int = option(1000, "cap on the inner dual iterations per MMA subproblem (NLopt: unlimited; "
                               "HS55 then took 250 s)", "NLopt CCSA/MMA parameter 'dual_maxeval'", check=at_least(1))

    def _configure(self, opt: nlopt.opt) -> None:
        opt.set_param("dual_ftol_rel", self.dual_ftol_rel)
        opt.set_param("dual_maxeval", self.dual_maxeval)


@final
@dataclasses.dataclass(frozen=True)
class NloptSLSQP(_NloptBase):
    """NLopt LD_SLSQP: Kraft's SLSQP (a C translation, independent of SciPy's build)."""

    name = "nlopt-slsqp"
    summary = "NLopt LD_SLSQP (Kraft's sequential least squares QP)"
    family = "established"
    handles = frozenset({"bounds", "ineq", "eq"})
    algorithm: ClassVar[int] = nlopt.LD_SLSQP
    native_eq: ClassVar[bool] = True

