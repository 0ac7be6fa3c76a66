"""Multistart (Snyman-Fatti Bayesian stopping) over a local solver."""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from problems import Problem, ProblemError
from solvers import AbstractSolver, NotApplicable, SolverOutput, Status, make_solver, solve
from solvers._deadline import DEADLINE_ENV, run_deadline, set_run_deadline
from solvers.multistart import Multistart, bayes_confidence, sampling_box


def double_well(x0: float = 0.5, lower: float = -math.inf) -> Problem:
    """f = (x^2 - 1)^2 + 0.3 x: local minimum near x = 0.96, global near x = -1.0356, maximum near 0.075."""
    return Problem(name="double-well", x0=[x0], objective=lambda x: (x[0] ** 2 - 1) ** 2 + 0.3 * x[0],
                   gradient=lambda x: np.array([4 * x[0] * (x[0] ** 2 - 1) + 0.3]), lower=[lower])


def constrained_well() -> Problem:
    """The double well in x1 with x2 tied to it by an equality and an inequality."""
    return Problem(name="constrained-well", x0=[0.5, 0.0],
                   objective=lambda x: (x[0] ** 2 - 1) ** 2 + 0.3 * x[0] + x[1] ** 2,
                   gradient=lambda x: np.array([4 * x[0] * (x[0] ** 2 - 1) + 0.3, 2 * x[1]]),
                   eq=lambda x: np.array([x[1] - 0.1 * x[0]]), ineq=lambda x: np.array([x[0] - 3.0]),
                   fd="central")


def test_bayes_confidence_values():
    assert bayes_confidence(1, 1) == pytest.approx(2 / 3)
    assert bayes_confidence(4, 4) == pytest.approx(1 - 5 * 4 * 3 * 2 * 24 / 362880)
    assert bayes_confidence(4, 3) < 0.99 < bayes_confidence(4, 4)
    assert bayes_confidence(7, 0) == 0.0
    with pytest.raises(ValueError, match="0 <= r <= n"):
        bayes_confidence(3, 4)


@given(st.integers(1, 400), st.integers(1, 30))
def test_bayes_confidence_grows_with_hits(n, r):
    r = min(r, n)
    q = bayes_confidence(n, r)
    assert 0.0 < q <= 1.0
    if r < n:
        assert bayes_confidence(n, r + 1) >= q and (q > 1 - 1e-12 or bayes_confidence(n, r + 1) > q)


@pytest.mark.parametrize("r", [1, 3, 6])
def test_bayes_confidence_limit_of_many_starts(r):
    # (n + 1)/(2n + 1) * prod (n - i)/(2n - i) -> 2^-(r+1): with many starts, r hits give at most this
    assert bayes_confidence(100_000, r) == pytest.approx(1 - 2.0 ** -(r + 1), abs=1e-4)


def test_sampling_box_is_scaled_by_x0_and_cut_by_bounds():
    lo, hi = sampling_box(np.array([0.0, 10.0, 2.0]), np.array([-np.inf, 5.0, 2.0]), np.array([np.inf] * 3), 1.0)
    assert lo.tolist() == [-1.0, 5.0, 2.0] and hi.tolist() == [1.0, 20.0, 4.0]


def test_finds_the_global_minimum_the_local_solver_misses():
    p = double_well()
    local = solve(p, "dynamic-q-plus")
    assert local.status is Status.CONVERGED and local.x[0] > 0.9  # the local minimum
    r = solve(p, "multistart")
    assert r.success and r.x[0] == pytest.approx(-1.0356, abs=1e-3)
    assert r.f < local.f - 0.5
    assert r.extra["stopped_by"] == "confidence" and r.extra["confidence"] >= 0.99
    assert r.extra["distinct_minima"] == 2 and r.nit == r.extra["starts"] >= 4
    assert r.nfg > local.nfg  # every local run is counted by the one oracle


def test_constrained_problem_and_another_local_solver():
    r = solve(constrained_well(), "multistart[local='scipy-slsqp']")
    assert r.success and r.x[0] == pytest.approx(-1.04, abs=2e-2) and r.max_violation < 1e-8
    assert r.options["local"]["solver"] == "scipy-slsqp"


def test_deterministic():
    a, b = solve(double_well(), "multistart"), solve(double_well(), "multistart")
    assert a.x.tolist() == b.x.tolist() and a.nfg == b.nfg and a.extra == b.extra
    c = solve(double_well(), "multistart", seed=5)
    assert c.extra["starts"] != a.extra["starts"] or c.nfg != a.nfg


def test_a_failing_start_is_recorded_and_the_search_goes_on():
    def f(x):
        if x[0] > 1.2:
            raise ProblemError("undefined for x > 1.2")
        return (x[0] ** 2 - 1) ** 2 + 0.3 * x[0]

    p = Problem(name="partly-undefined", x0=[0.5], objective=f,
                gradient=lambda x: np.array([4 * x[0] * (x[0] ** 2 - 1) + 0.3]))
    r = solve(p, "multistart")
    assert r.status is Status.CONVERGED and r.x[0] < 0
    assert r.extra["converged_starts"] < r.extra["starts"]  # some starts raised


def test_budget_ends_the_search_with_the_best_end():
    r = solve(double_well(), "multistart", max_nfg=25)
    assert r.status is Status.MAX_ITER and r.nfg <= 25 and np.isfinite(r.f)
    assert r.extra["stopped_by"] == "budget"


def test_max_starts_and_max_time_end_without_certifying():
    r = solve(double_well(), "multistart", max_starts=2)
    assert r.status is Status.MAX_ITER and r.extra["stopped_by"] == "max_starts" and r.nit == 2
    t = solve(double_well(), "multistart", max_time=1e-9)
    assert t.status is Status.MAX_ITER and t.extra["stopped_by"] == "max_time" and t.nit == 1


def test_no_feasible_end_is_a_failure():
    p = Problem(name="infeasible", x0=[0.0], objective=lambda x: x[0] ** 2, gradient=lambda x: 2 * x,
                ineq=lambda x: np.array([1.0 + x[0] ** 2]), ineq_jacobian=lambda x: np.array([[2 * x[0]]]))
    r = solve(p, "multistart", max_starts=3)
    assert r.status is Status.FAILED and not r.success and "ended feasible" in r.message


def test_feasible_ends_on_the_cap_give_the_lowest_uncertified():
    r = solve(double_well(), "multistart", local="dynamic-q-plus[max_iter=2]", max_starts=4)
    assert r.status is Status.MAX_ITER and "no local run of 4 converged" in r.message


@pytest.mark.parametrize("options, match", [
    ({"confidence": 1.5}, "confidence"),
    ({"max_starts": 0}, "max_starts"),
    ({"max_time": -1.0}, "max_time"),
    ({"local": "no-such-solver"}, "no-such-solver"),
    ({"local": Multistart()}, "not another multistart"),
])
def test_bad_options_are_named(options, match):
    with pytest.raises(ValueError, match=match):
        make_solver("multistart", **options)


def test_applies_where_the_local_solver_applies():
    with pytest.raises(NotApplicable, match="sqsd"):
        solve(constrained_well(), "multistart", local="sqsd")
    assert solve(double_well(), "multistart[local='sqsd']").x[0] < 0


def test_stops_in_time_for_the_harness_deadline(monkeypatch):
    monkeypatch.setenv(DEADLINE_ENV, repr(time.time() + 0.1))  # inside the margin: no point may be asked for
    r = solve(double_well(), "multistart")
    assert r.status is Status.MAX_ITER and r.extra["stopped_by"] == "deadline" and r.nit == 0
    assert "deadline" in r.message and r.nfg == 0
    monkeypatch.setenv(DEADLINE_ENV, repr(time.time() + 3600))
    assert solve(double_well(), "multistart").extra["stopped_by"] == "confidence"


@dataclasses.dataclass(frozen=True)
class _WalksForever(AbstractSolver):
    """Converges at once from x0 on its first run; from any other start it never stops evaluating."""

    name = "test-walks-forever"
    summary = "test double"
    handles = frozenset({"bounds"})

    def minimize(self, oracle):
        x = np.asarray(oracle.x0, dtype=float)
        if x[0] == 0.5:  # the problem's own x0: the first local run
            return SolverOutput(x, Status.CONVERGED, "stopped at x0")
        give_up = time.time() + 30.0  # only so that a broken hard stop fails the test instead of hanging it
        while time.time() < give_up:
            x = x + 1e-9
            oracle.f(x)
        return SolverOutput(x, Status.FAILED, "walked until it gave up")


def test_a_local_run_that_would_overrun_the_deadline_is_stopped_and_the_ends_kept(monkeypatch):
    monkeypatch.setenv(DEADLINE_ENV, repr(time.time() + 1.0))  # 0.5 s of search after the margin
    r = solve(double_well(), Multistart(local=_WalksForever()))
    # the second local run was stopped by the view (it never gave up on its own) and dropped
    assert r.extra["stopped_by"] == "deadline" and r.nit == 1 and r.status is Status.MAX_ITER
    assert r.x[0] == 0.5 and r.nfg > 1  # the first run's end is returned; the second's points were counted


def test_the_local_runs_view_stops_only_point_requests(monkeypatch):
    from problems import BudgetExhausted, Oracle
    from solvers.multistart import _HardStop, _StartedAt

    oracle = Oracle(double_well())
    late = _StartedAt(oracle, np.array([2.0]), _HardStop(time.time() - 1.0))
    assert late.n == 1 and late.x0[0] == 2.0 and late.nfg == 0  # attributes still answer
    for call in (lambda: late.f([1.0]), lambda: late.evaluate([1.0]), lambda: late.at([1.0]).f()):
        with pytest.raises(BudgetExhausted, match="deadline"):
            call()
    assert oracle.nfg == 0
    assert _StartedAt(oracle, np.array([2.0]), _HardStop(time.time() + 60)).f([1.0]) == oracle.f([1.0])


def test_a_point_is_refused_when_slow_evaluations_would_not_fit():
    """With evaluations of 0.4 s, 1 s before the hard stop is too late for another one plus the
    harness's report at the end (3 x 0.4 s), although the instant itself is not yet reached."""
    from problems import BudgetExhausted, Oracle
    from solvers.multistart import EVALUATIONS_RESERVED, _HardStop, _StartedAt

    oracle = Oracle(double_well())
    stop = _HardStop(time.time() + 1.0, slowest=0.4)
    assert EVALUATIONS_RESERVED * 0.4 > 1.0
    with pytest.raises(BudgetExhausted, match="deadline"):
        _StartedAt(oracle, np.array([2.0]), stop).evaluate([1.0])
    stop.slowest = 0.2  # 3 x 0.2 s fits in the second left
    view = _StartedAt(oracle, np.array([2.0]), stop)
    assert view.evaluate([1.0])["f"] == oracle.f([1.0])
    assert 0.0 < stop.slowest == 0.2  # the call was fast: the slowest seen stays


def test_run_deadline_set_and_cleared(monkeypatch):
    monkeypatch.delenv(DEADLINE_ENV, raising=False)
    assert run_deadline() is None
    set_run_deadline(10.0)
    assert 9.0 < run_deadline() - time.time() <= 10.0
    for none in (None, 0.0, math.inf):
        set_run_deadline(10.0)
        set_run_deadline(none)
        assert run_deadline() is None
    monkeypatch.setenv(DEADLINE_ENV, "not a number")
    assert run_deadline() is None
