"""Multistart with Snyman and Fatti's Bayesian stopping rule: a global search over any local solver (our extension).

The thesis uses its optimizers as local methods and notes that LFOP "seeks a low local
minimum and can therefore be used as a basic component in a methodology for global
minimization" (App. B.1).  That methodology is Snyman and Fatti's multistart (J. Optim.
Theory Appl. 54:121-141, 1987): run the local method from random starts and stop when the
Bayesian probability that the best end found is the global minimum reaches a target.

Theorem (Snyman & Fatti 1987).  If the region of convergence of the global minimum is at
least as large as that of any other local minimum, and r of n uniformly sampled starts
have converged to the best value f~ found, then

    P[f~ = f*] >= q(n, r) = 1 - (n + 1)! (2n - r)! / ((2n + 1)! (n - r)!).

`Multistart` holds a local solver (composition, as Dynamic-Q holds LFOPC); every local run
evaluates the problem through the same counting oracle, so N^fg is the whole search's cost.
The first start is the problem's own x0, so the search never ends worse than the local
solver from x0 (if that run converges).
"""

from __future__ import annotations

import dataclasses
import math
import time
from typing import Any

import numpy as np

from problems import BudgetExhausted, Oracle, Problem

from ._base import AbstractSolver, Check, at_least, between, final, nonneg, option, positive
from ._deadline import run_deadline
from ._registry import make_solver
from ._result import SolverOutput, Status
from .dynamic_q_plus import DynamicQPlus

__all__ = ["Multistart", "bayes_confidence", "sampling_box"]

DEADLINE_MARGIN = 0.5  # seconds kept for the end of the run (the harness's last evaluations, the row)
#: a point is refused when this many of the slowest evaluations so far would not fit before the hard
#: stop: the one asked for, and the harness's report of f and the violation at the returned point
EVALUATIONS_RESERVED = 3


def bayes_confidence(n: int, r: int) -> float:
    """q(n, r) of Snyman and Fatti's theorem: a lower bound on P[best end found is the global minimum].

    ``n`` starts sampled, ``r`` (1 <= r <= n) of them converged to the best value found.
    q(1, 1) = 2/3; q(4, 4) = 0.992; q(n, 1) < 3/4 for every n (one hit says little).  As n
    grows, q(n, r) tends to 1 - 2^-(r+1): confidence 0.99 then needs r >= 6 hits.
    """
    if not (isinstance(n, int) and isinstance(r, int) and 0 <= r <= n):
        raise ValueError(f"bayes_confidence needs integers 0 <= r <= n, got n={n!r}, r={r!r}")
    if r == 0:
        return 0.0
    log_ratio = math.lgamma(n + 2) + math.lgamma(2 * n - r + 1) - math.lgamma(2 * n + 2) - math.lgamma(n - r + 1)
    return 1.0 - math.exp(log_ratio)


def sampling_box(x0: np.ndarray, lower: np.ndarray, upper: np.ndarray, spread: float) -> tuple[np.ndarray, np.ndarray]:
    """The region starts are drawn from: x0_i +- spread * max(1, |x0_i|), within the bounds.

    Scaled by x0 so that the region suits the problem's units; bounds cut it but never widen
    it (a box of +-1e20 bounds would make every start meaningless).
    """
    w = spread * np.maximum(1.0, np.abs(x0))
    lo = np.maximum(x0 - w, lower)
    hi = np.minimum(x0 + w, upper)
    return lo, np.maximum(hi, lo)


#: the oracle's methods that take a point (every evaluation passes through one of them)
_EVALUATIONS = frozenset({"f", "grad", "f_and_grad", "ineq", "eq", "ineq_jac", "eq_jac", "at", "evaluate"})


class _OutOfTime(BudgetExhausted):
    """A local run asked for a point after the search's hard stop (the run's deadline less the margin).

    A `BudgetExhausted`, so that every adapter passes it through as it does an evaluation budget.
    """


@dataclasses.dataclass
class _HardStop:
    """The search's hard stop (a `time.time` instant) and the slowest evaluation call seen so far, s."""

    at: float
    slowest: float = 0.0


class _StartedAt:
    """The oracle seen by one local run: the same counting oracle, with ``x0`` the run's start.

    Every other attribute is the wrapped oracle's, so counts, history and caching are shared.
    With ``stop`` (a `_HardStop` shared by the search's runs), asking for a point that would not
    be done before the hard stop raises `_OutOfTime` (predicted: `EVALUATIONS_RESERVED` times the
    slowest evaluation so far, so that a problem whose evaluations take 0.4 s still leaves time
    for the harness's report at the end): the search then returns its best end so far instead of
    being killed at the harness's limit with nothing (the prediction in `Multistart.minimize` is
    a guess; this is the guarantee).
    """

    def __init__(self, oracle: Oracle, x0: np.ndarray, stop: _HardStop | None = None) -> None:
        self._oracle, self._x0, self._stop = oracle, x0, stop

    @property
    def x0(self) -> np.ndarray:
        return self._x0.copy()

    def __getattr__(self, name: str) -> Any:
        attr = getattr(self._oracle, name)
        stop = self._stop
        if stop is None or name not in _EVALUATIONS:
            return attr

        def checked(*args: Any, **kwargs: Any) -> Any:
            now = time.time()
            if now + EVALUATIONS_RESERVED * stop.slowest > stop.at:
                raise _OutOfTime("the run's deadline is near: local run stopped")
            out = attr(*args, **kwargs)
            stop.slowest = max(stop.slowest, time.time() - now)
            return out

        return checked


@dataclasses.dataclass(frozen=True)
class _End:
    """Where one local run ended."""

    x: np.ndarray
    f: float
    violation: float
    status: Status
    message: str
    raised: bool = False  # the local run raised an exception (``message`` names it)


def _or_inf(v: float) -> float:
    """``v``, or inf for a NaN (so that a NaN sorts last instead of breaking the comparison)."""
    return math.inf if math.isnan(v) else v


@final
@dataclasses.dataclass(frozen=True)
class Multistart(AbstractSolver):
    """Snyman-Fatti multistart: local runs from x0 and uniform random starts, Bayesian stopping.

    Start 1 is x0; the others are drawn uniformly from `sampling_box` with a fixed seed.  After
    each run, the best end is the lowest f among feasible converged ends (violation <=
    ``feas_tol``); r counts the ends within ``f_same`` of it (relative to max(1, |f|)).  Stops
    when `bayes_confidence` (n, r) >= ``confidence`` (status converged), or at ``max_starts``,
    ``max_time`` or the harness's deadline for the run (`solvers._deadline`: the next local
    run would not fit) with status max_iter: the best end is returned, the rule did not
    certify it.  A local run that raises is recorded as a failed start; the search goes on (if
    every local run raised, the run ends with status error and the first exception's message).
    """

    name = "multistart"
    summary = "Multistart over a local solver (default Dynamic-Q+), Snyman-Fatti Bayesian stopping rule [OWN]"
    family = "own"
    handles = frozenset({"bounds", "ineq", "eq"})

    local: AbstractSolver = option(DynamicQPlus(), "local solver run from every start (an instance, or a "
                                   "registry id such as 'scipy-slsqp')", "App. B.1 [THESIS]; Snyman & Fatti 1987")
    confidence: float = option(0.99, "stop when q(n, r) >= this (Snyman-Fatti bound on P[best = global])",
                               "Snyman & Fatti 1987", check=between(0.0, 1.0))
    max_starts: int = option(50, "largest number of local runs", "[OWN]", check=at_least(1))
    spread: float = option(1.0, "starts drawn from x0_i +- spread * max(1, |x0_i|), cut by the bounds",
                           "[OWN]", check=positive())
    f_same: float = option(1e-3, "two ends reached the same minimum when their f differ by at most this "
                           "times max(1, |f|) (loose: local ends carry the local method's tolerance, "
                           "and a design problem's its numerical noise)", "[OWN]", check=positive())
    feas_tol: float = option(1e-6, "an end is feasible when every violation is at most this (left at its "
                             "default, solvers.solve runs it with solve's own feas_tol)", "[OWN]; "
                             "solvers.solve's success rule", check=nonneg())
    seed: int = option(0, "seed of the random starts (fixed: same inputs, same runs)", "[OWN]", check=at_least(0))
    max_time: float | None = option(None, "start no new local run after this many seconds (None: no limit)",
                                    "[OWN]", check=Check(lambda v: v is None or v > 0, "a number > 0 or None"))

    def __post_init__(self) -> None:
        if isinstance(self.local, str):  # a registry id from a spec: "multistart[local='scipy-slsqp']"
            try:
                object.__setattr__(self, "local", make_solver(self.local))
            except KeyError as exc:  # UnknownSolver: its message lists the valid ids
                raise ValueError(f"multistart: option local={self.local!r} is invalid: {exc}") from None
        super().__post_init__()

    def check_together(self) -> None:
        if not isinstance(self.local, AbstractSolver):
            raise ValueError(f"multistart: local must be a solver instance or registry id, got {self.local!r}")
        if isinstance(self.local, Multistart):
            raise ValueError("multistart: local must be a local solver, not another multistart")

    def can_solve(self, problem: Problem) -> str | None:
        """Whatever the local solver can solve (``handles`` lists the default local solver's forms)."""
        return self.local.can_solve(problem)

    # ------------------------------------------------------------------ helpers
    def _run(self, oracle: Oracle, start: np.ndarray, stop: _HardStop | None = None) -> _End:
        """One local run from ``start``, and f and the violation at its end (through the oracle)."""
        try:
            out = self.local.minimize(_StartedAt(oracle, start, stop))  # type: ignore[arg-type]  # a view
            x = np.clip(np.asarray(out.x, dtype=float).reshape(-1), oracle.lower, oracle.upper)
            status, message = Status(out.status), out.message
        except BudgetExhausted:
            raise
        except Exception as exc:  # noqa: BLE001 - a failed start is recorded; the search goes on
            return _End(oracle.last_x, math.inf, math.inf, Status.ERROR, f"{type(exc).__name__}: {exc}", raised=True)
        if x.size != oracle.n or not np.all(np.isfinite(x)):
            return _End(oracle.last_x, math.inf, math.inf, Status.ERROR, "non-finite end")
        f = oracle.f(x)
        parts = []
        if oracle.n_ineq:
            parts.append(float(np.max(oracle.ineq(x), initial=0.0)))
        if oracle.n_eq:
            parts.append(float(np.max(np.abs(oracle.eq(x)), initial=0.0)))
        # a NaN is kept (Python's max(0.0, nan) would drop it and call the end feasible)
        viol = math.nan if any(math.isnan(v) for v in parts) else max([0.0, *parts])
        if not (math.isfinite(f) and math.isfinite(viol)):
            return _End(x, math.inf, math.inf, Status.ERROR, f"non-finite f or violation at the end (f={f})")
        return _End(x, float(f), viol, status, message)

    def _feasible(self, e: _End) -> bool:
        """The end's violation is at most ``feas_tol`` (a NaN violation is not: the comparison is False)."""
        return bool(e.violation <= self.feas_tol)

    def _good(self, e: _End) -> bool:
        return e.status is Status.CONVERGED and self._feasible(e)

    def _same(self, a: float, b: float) -> bool:
        return abs(a - b) <= self.f_same * max(1.0, abs(b))

    # ------------------------------------------------------------------ algorithm
    def minimize(self, oracle: Oracle) -> SolverOutput:
        t0 = time.perf_counter()
        x0 = oracle.x0  # as given: the first run is exactly the local solver's own run
        lo, hi = sampling_box(np.clip(x0, oracle.lower, oracle.upper), oracle.lower, oracle.upper, self.spread)
        rng = np.random.default_rng(self.seed)
        deadline, longest = run_deadline(), 0.0
        hard_stop = None if deadline is None else _HardStop(deadline - DEADLINE_MARGIN)
        ends: list[_End] = []
        q, stop = 0.0, "max_starts"
        for k in range(self.max_starts):
            start = x0 if k == 0 else rng.uniform(lo, hi)
            t_run = time.perf_counter()
            try:
                ends.append(self._run(oracle, start, hard_stop))
            except _OutOfTime:  # the unfinished local run is dropped; the ends so far stand
                stop = "deadline"
                break
            except BudgetExhausted:
                stop = "budget"
                break
            longest = max(longest, time.perf_counter() - t_run)
            good = [e for e in ends if self._good(e)]
            if good:
                best = min(good, key=lambda e: e.f)
                r = sum(self._same(e.f, best.f) for e in good)
                q = bayes_confidence(len(ends), r)
                if q >= self.confidence:
                    stop = "confidence"
                    break
            if self.max_time is not None and time.perf_counter() - t0 >= self.max_time:
                stop = "max_time"
                break
            # under the harness: a run killed at its time limit keeps nothing, so stop while the
            # next local run (predicted: twice the longest so far) still fits
            if deadline is not None and time.time() + 2.0 * longest + DEADLINE_MARGIN > deadline:
                stop = "deadline"
                break
        return self._output(oracle, ends, q, stop)

    def _output(self, oracle: Oracle, ends: list[_End], q: float, stop: str) -> SolverOutput:
        good = [e for e in ends if self._good(e)]
        fs = sorted(e.f for e in good)
        n_min = sum(1 for a, b in zip([None, *fs], fs) if a is None or not self._same(b, a))
        extra = {"starts": len(ends), "confidence": q, "stopped_by": stop, "converged_starts": len(good),
                 "distinct_minima": n_min, "local": self.local.name}
        if good:
            best = min(good, key=lambda e: e.f)
            status = Status.CONVERGED if stop == "confidence" else Status.MAX_ITER
            msg = (f"best of {len(ends)} local runs ({len(good)} converged feasible); Bayesian confidence "
                   f"{q:.4f}" + (f" >= {self.confidence}" if stop == "confidence" else f" < {self.confidence}, "
                                 f"stopped by {stop}"))
            return SolverOutput(best.x, status, msg, nit=len(ends), extra=extra)
        if not ends:
            why = "the run's deadline reached" if stop == "deadline" else "evaluation budget exhausted"
            return SolverOutput(oracle.last_x, Status.MAX_ITER, f"{why} in the first local run", nit=0, extra=extra)
        if all(e.raised for e in ends):  # no local run ended: the search has no end to report
            return SolverOutput(oracle.last_x, Status.ERROR, f"every local run of {len(ends)} raised an exception; "
                                f"the first: {ends[0].message}", nit=len(ends), extra=extra)
        feasible = [e for e in ends if self._feasible(e)]
        if feasible:  # e.g. every local run stopped on its cap: the lowest feasible end, uncertified
            best = min(feasible, key=lambda e: e.f)
            return SolverOutput(best.x, Status.MAX_ITER, f"no local run of {len(ends)} converged; the lowest "
                                f"feasible end ({best.status.value}: {best.message})", nit=len(ends), extra=extra)
        least = min(ends, key=lambda e: (_or_inf(e.violation), _or_inf(e.f)))
        return SolverOutput(least.x, Status.FAILED, f"no local run of {len(ends)} ended feasible "
                            f"(least violation {least.violation:.3g}; last: {ends[-1].message})", nit=len(ends),
                            extra=extra)
