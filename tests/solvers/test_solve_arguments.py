"""solve()'s arguments, option checks and specs, malformed solver outputs, NLopt callbacks, multistart ends."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from problems import Problem
from solvers import AbstractSolver, SolverOutput, Status, make_solver, option, solve
from solvers._base import _type_ok, nonneg
from solvers._registry import parse_spec
from solvers.multistart import Multistart


def quad() -> Problem:
    return Problem(name="quad", x0=[3.0, 3.0], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x)


def half_line() -> Problem:
    """min x^2 subject to 1 - x <= 0: the minimum is x = 1 on the constraint."""
    return Problem(name="half-line", x0=[2.0], objective=lambda x: float(x[0] ** 2), gradient=lambda x: 2 * x,
                   ineq=lambda x: np.array([1.0 - x[0]]), ineq_jacobian=lambda x: np.array([[-1.0]]))


@dataclasses.dataclass(frozen=True)
class FixedEnd(AbstractSolver):
    """Evaluates x0 once and returns the point ``at`` as converged (a local solver for multistart)."""

    name = "test-fixed-end"
    summary = "returns a fixed point"
    handles = frozenset({"bounds", "ineq", "eq"})
    at: float = option(1.0, "the returned point")

    def minimize(self, oracle):
        oracle.f(oracle.x0)
        return SolverOutput(np.array([self.at]), Status.CONVERGED, "fixed end")


@dataclasses.dataclass(frozen=True)
class Malformed(AbstractSolver):
    """Returns what ``what`` says: a tuple, None, or a SolverOutput whose x is one too short."""

    name = "test-malformed"
    summary = "returns a malformed output"
    what: str = option("tuple", "what minimize returns")

    def minimize(self, oracle):
        x = oracle.x0
        oracle.f(x)
        if self.what == "tuple":
            return x, Status.CONVERGED
        if self.what == "none":
            return None
        return SolverOutput(x[:-1], Status.CONVERGED, "short x")


@dataclasses.dataclass(frozen=True)
class Raises(AbstractSolver):
    """Evaluates x0, then raises (a local solver for multistart)."""

    name = "test-raises"
    summary = "raises"
    handles = frozenset({"bounds", "ineq", "eq"})

    def minimize(self, oracle):
        oracle.f(oracle.x0)
        raise RuntimeError(f"no luck from {oracle.x0[0]:.3g}")


# ---------------------------------------------------------------- 1. solve(): max_nfg, feas_tol, _finish
@pytest.mark.parametrize("bad", [0, -3, True, 2.5, 10.0, "10", math.inf])
def test_max_nfg_must_be_none_or_a_positive_integer(bad) -> None:
    with pytest.raises(ValueError, match=r"max_nfg=.*invalid; valid: None or an integer >= 1"):
        solve(quad(), "sqsd", max_nfg=bad)


@pytest.mark.parametrize("bad", [-1e-6, math.nan, math.inf, True, "1e-6", None])
def test_feas_tol_must_be_a_finite_number_at_least_zero(bad) -> None:
    with pytest.raises(ValueError, match=r"feas_tol=.*invalid; valid: a finite number >= 0"):
        solve(quad(), "sqsd", feas_tol=bad)


def test_valid_budget_and_tolerance_run() -> None:
    assert solve(quad(), "sqsd", max_nfg=np.int64(5)).status is Status.MAX_ITER
    assert solve(quad(), "sqsd", feas_tol=0).success
    assert solve(quad(), "multistart[max_starts=1]", feas_tol=0).options["feas_tol"] == 0.0  # multistart takes 0


def test_multistart_left_at_its_default_takes_solves_feas_tol() -> None:
    ms = Multistart(local=FixedEnd(at=1.0 - 1e-5), confidence=0.5, max_starts=3)  # every end violates by 1e-5
    loose = solve(half_line(), ms, feas_tol=1e-4)
    assert loose.options["feas_tol"] == 1e-4
    assert loose.status is Status.CONVERGED and loose.success and loose.extra["converged_starts"] == 1
    strict = solve(half_line(), ms)  # solve's default 1e-6 = multistart's: the end is infeasible to both
    assert strict.options["feas_tol"] == 1e-6 and strict.status is Status.FAILED and not strict.success
    # a feas_tol the user gave is kept
    assert solve(quad(), "multistart[max_starts=1,feas_tol=1e-3]", feas_tol=1e-4).options["feas_tol"] == 1e-3
    # given in the spec, even at its default value
    assert solve(quad(), "multistart[max_starts=1,feas_tol=1e-6]", feas_tol=1e-4).options["feas_tol"] == 1e-6
    ms = Multistart(local=FixedEnd(at=1.0 - 1e-5), confidence=0.5, max_starts=3, feas_tol=1e-3)
    r = solve(half_line(), ms, feas_tol=1e-4)
    assert r.options["feas_tol"] == 1e-3 and r.status is Status.CONVERGED


@pytest.mark.parametrize("what, says", [("tuple", "returned tuple, not a SolverOutput"),
                                        ("none", "returned NoneType, not a SolverOutput"),
                                        ("short", "returned x of length 1, the problem has n = 2")])
def test_a_malformed_solver_output_is_recorded_as_an_error(what, says) -> None:
    r = solve(quad(), Malformed(what=what))
    assert r.status is Status.ERROR and says in r.message and not r.success
    assert r.nfg == 1 and r.solver == "test-malformed"  # the run is kept, with its counts


# ---------------------------------------------------------------- 2. option checks and their messages
def test_nonneg_refuses_inf_unless_told() -> None:
    assert not nonneg()(math.inf) and nonneg(finite=False)(math.inf)
    assert nonneg()(0.0) and not nonneg()(-1.0) and not nonneg()(math.nan)
    for name, opt in [("lfopc", "eps_g"), ("sqsd", "eps_x"), ("dynamic-q", "eps_c"), ("ipopt", "bound_relax_factor")]:
        with pytest.raises(ValueError, match=rf"{name}: option {opt}=inf is invalid; valid: a finite number >= 0"):
            make_solver(name, **{opt: math.inf})


@pytest.mark.parametrize("spec, message", [
    ("lfopc[mu1=abc]", "lfopc: option mu1='abc' is invalid (not a number); valid: a finite number > 0"),
    ("lfopc[m=2.5]", "lfopc: option m=2.5 is invalid (not an integer); valid: an integer >= 1"),
    ("lfopc[dt_mode=3]", "lfopc: option dt_mode=3 is invalid (not a string); valid: one of 'fixed', 'auto'"),
    ("etopc[eta=abc]", "etopc: option eta='abc' is invalid (not a number); valid: a number in (0, 1)"),
    ("multistart[max_time=x]", "multistart: option max_time='x' is invalid (not a number); valid: a number > 0 or "
                               "None"),
])
def test_invalid_option_messages_read_cleanly(spec, message) -> None:
    with pytest.raises(ValueError) as exc:
        make_solver(spec)
    assert str(exc.value) == message
    assert " and " not in str(exc.value)


def test_bool_options_and_number_types() -> None:
    with pytest.raises(ValueError) as exc:
        make_solver("dynamic-q[step_stop_feasible=1]")
    assert str(exc.value) == "dynamic-q: option step_stop_feasible=1 is invalid; valid: a bool"
    with pytest.raises(ValueError) as exc:
        make_solver("lfopc[mu1=-1]")
    assert str(exc.value) == "lfopc: option mu1=-1 is invalid; valid: a finite number > 0"
    assert _type_ok("float", np.float64(2.0))[0] and not _type_ok("float", True)[0]
    assert not _type_ok("float", np.True_)[0] and not _type_ok("float", "1.0")[0]
    assert _type_ok("int", 1e4)[0] and _type_ok("int", np.int64(3))[0] and not _type_ok("int", 2.5)[0]
    # a NaN is never a setting, also for a float option without a check of its own
    with pytest.raises(ValueError, match=r"scipy-bfgs: option norm=nan is invalid; valid: a number other than NaN"):
        make_solver("scipy-bfgs[norm=nan]")


@pytest.mark.parametrize("bad", [0, -1])
def test_dynamic_q_plus_memory_is_at_least_one(bad) -> None:
    with pytest.raises(ValueError, match=rf"dynamic-q-plus: option memory={bad} is invalid; valid: an integer >= 1"):
        make_solver("dynamic-q-plus", memory=bad)


# ---------------------------------------------------------------- 3. specs
def test_an_option_given_twice_is_refused() -> None:
    with pytest.raises(ValueError, match=r"option mu1 given more than once in solver specification"):
        parse_spec("lfopc[mu1=1,mu1=2]")
    with pytest.raises(ValueError, match=r"mu1 given more than once: in the solver specification 'lfopc\[mu1=1\]' "
                                         r"and as keyword"):
        make_solver("lfopc[mu1=1]", mu1=2)
    with pytest.raises(ValueError, match="given more than once"):
        solve(quad(), "sqsd[rho=1]", rho=2)


def test_spec_values_parse_as_before_and_inf_nan_are_floats() -> None:
    name, opts = parse_spec("x[a=inf,b=-inf,c=nan,d=+inf]")
    assert name == "x" and opts["a"] == math.inf and opts["b"] == -math.inf and math.isnan(opts["c"])
    assert opts["d"] == math.inf and all(type(v) is float for v in opts.values())
    assert make_solver("dynamic-q-plus[eps_kkt=inf]").eps_kkt == math.inf  # an option whose doc gives inf a meaning
    # every other value as before (the parsed options key stored runs)
    cases = {
        "lfopc[delta_t=0.5,mu1=1e4]": ("lfopc", {"delta_t": 0.5, "mu1": 1e4}),
        "sqsd[]": ("sqsd", {}),
        "sqsd": ("sqsd", {}),
        " sqsd [ rho = 2 ] ": ("sqsd", {"rho": 2}),
        "etopc[max_line=3,eta=0.5]": ("etopc", {"max_line": 3, "eta": 0.5}),
        "multistart[local='scipy-slsqp']": ("multistart", {"local": "scipy-slsqp"}),
        "x[flag=True,s=abc,t='inf',u=None,v=-2]": ("x", {"flag": True, "s": "abc", "t": "inf", "u": None, "v": -2}),
    }
    for spec, want in cases.items():
        got = parse_spec(spec)
        assert got == want, spec
        assert [type(v) for v in got[1].values()] == [type(v) for v in want[1].values()], spec


@pytest.mark.parametrize("spec, says", [
    ("lfopc[=1]", "empty option name"),
    ("lfopc[mu1=1, =2]", "empty option name"),
    ("lfopc[mu", "cannot parse solver specification 'lfopc[mu'"),
    ("lfopc]", "cannot parse solver specification 'lfopc]'"),
    ("lfopc[mu1]", "is not key=value"),
])
def test_a_malformed_spec_shows_the_syntax(spec, says) -> None:
    with pytest.raises(ValueError) as exc:
        parse_spec(spec)
    assert says in str(exc.value) and "expected name[key=value,...]" in str(exc.value)


# ---------------------------------------------------------------- 4. NLopt: the problem's exception
def raising_after(k: int, exc: type[Exception]):
    calls = [0]

    def f(x):
        calls[0] += 1
        if calls[0] > k:
            raise exc(f"the model broke at call {calls[0]}")
        return float(x @ x)

    return f


@pytest.mark.parametrize("solver", ["nlopt-mma", "nlopt-slsqp"])
@pytest.mark.parametrize("exc", [RuntimeError, ValueError])
def test_nlopt_reraises_the_problems_exception(solver, exc) -> None:
    p = Problem(name="breaks", x0=[3.0, 3.0], objective=raising_after(1, exc), gradient=lambda x: 2 * x)
    r = solve(p, solver)
    assert r.status is Status.ERROR, r.message
    assert r.message.startswith(f"{exc.__name__}: the model broke at call 2 (at test_solve_arguments.py:")
    with pytest.raises(exc, match="the model broke"):
        solve(Problem(name="breaks", x0=[3.0, 3.0], objective=raising_after(1, exc), gradient=lambda x: 2 * x),
              solver, throw=True)


def test_nlopt_reraises_an_exception_of_a_constraint() -> None:
    def g(x):
        if x[0] != 2.0:  # defined at x0 only
            raise RuntimeError("constraint undefined here")
        return np.array([1.0 - x[0]])

    p = Problem(name="bad-g", x0=[2.0], objective=lambda x: float(x[0] ** 2), gradient=lambda x: 2 * x,
                ineq=g, ineq_jacobian=lambda x: np.array([[-1.0]]))
    for solver in ("nlopt-mma", "nlopt-slsqp"):
        r = solve(p, solver)
        assert r.status is Status.ERROR and "RuntimeError: constraint undefined here" in r.message
    # nothing raised, or the budget: as before
    assert solve(quad(), "nlopt-slsqp").status is Status.CONVERGED
    budget = solve(half_line(), "nlopt-mma", max_nfg=3)
    assert budget.status is Status.MAX_ITER and budget.nfg == 3


# ---------------------------------------------------------------- 5. multistart ends
def test_multistart_whose_every_start_raised_is_an_error() -> None:
    r = solve(quad(), Multistart(local=Raises(), max_starts=4))
    assert r.status is Status.ERROR and not r.success
    assert "every local run of 4 raised" in r.message and "RuntimeError: no luck from 3" in r.message
    assert r.extra["starts"] == 4 and r.nit == 4
    # one start that ended is enough for a normal end
    fine = solve(half_line(), Multistart(local=FixedEnd(at=1.0), confidence=0.5))
    assert fine.status is Status.CONVERGED and fine.success


def test_multistart_never_takes_a_nan_violation_as_feasible() -> None:
    p = Problem(name="nan-g", x0=[2.0], objective=lambda x: float(x[0] ** 2), gradient=lambda x: 2 * x,
                ineq=lambda x: np.array([math.nan if x[0] < 1.5 else 1.0 - x[0]]),
                ineq_jacobian=lambda x: np.array([[-1.0]]))
    ms = Multistart(local=FixedEnd(at=1.0), confidence=0.5, max_starts=3)  # ends where g is NaN
    r = solve(p, ms)
    assert r.status is not Status.CONVERGED and not r.success
    assert r.extra["converged_starts"] == 0
    assert ms._feasible(dataclasses.replace(_end(), violation=math.nan)) is False


def _end():
    from solvers.multistart import _End

    return _End(np.zeros(1), 0.0, 0.0, Status.CONVERGED, "")
