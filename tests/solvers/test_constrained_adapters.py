"""Established constrained adapters: status maps, counting through the oracle, options."""

from __future__ import annotations

import numpy as np
import pytest

from problems import Problem
from problems.hs import problem
from solvers import Status, get_solver_class, solve
from solvers.ipopt import Ipopt
from solvers.nlopt_adapters import STATUS_MAP as NLOPT_STATUS_MAP
from solvers.nlopt_adapters import NloptMMA, NloptSLSQP
from solvers.scipy_constrained import ScipyCOBYLA, ScipySLSQP, ScipyTrustConstr

ADAPTERS = ["scipy-slsqp", "scipy-trust-constr", "scipy-cobyla", "ipopt", "nlopt-mma", "nlopt-slsqp"]


def _rel(f, f_ref):
    return abs(f - f_ref) / (1 + abs(f_ref))


# --------------------------------------------------------------------------- status maps
def test_slsqp_status_map():
    m = ScipySLSQP.STATUS_MAP
    assert m[0] is Status.CONVERGED and m[9] is Status.MAX_ITER
    assert all(m[k] is Status.FAILED for k in (2, 3, 4, 5, 6, 7, 8))
    assert set(m) == set(range(-1, 10))


def test_trust_constr_status_map():
    m = ScipyTrustConstr.STATUS_MAP
    assert (m[0], m[1], m[2], m[3]) == (Status.MAX_ITER, Status.CONVERGED, Status.CONVERGED, Status.FAILED)


def test_cobyla_status_map_covers_prima_codes():
    from scipy._lib.pyprima.common import infos

    codes = {v for k, v in vars(infos).items() if k.isupper() and k != "INFO_DEFAULT"}
    assert codes <= set(ScipyCOBYLA.STATUS_MAP)
    assert ScipyCOBYLA.STATUS_MAP[infos.SMALL_TR_RADIUS] is Status.CONVERGED
    assert ScipyCOBYLA.STATUS_MAP[infos.MAXFUN_REACHED] is Status.MAX_ITER


def test_ipopt_status_map():
    m = Ipopt.STATUS_MAP
    assert m["Solve_Succeeded"] is Status.CONVERGED
    assert m["Maximum_Iterations_Exceeded"] is Status.MAX_ITER
    assert m["Infeasible_Problem_Detected"] is Status.FAILED
    assert m["Invalid_Number_Detected"] is Status.ERROR
    assert m["Maximum_CpuTime_Exceeded"] is Status.TIMEOUT


def test_nlopt_status_map():
    import nlopt

    assert NloptMMA.STATUS_MAP is NLOPT_STATUS_MAP is NloptSLSQP.STATUS_MAP
    for code in (nlopt.SUCCESS, nlopt.FTOL_REACHED, nlopt.XTOL_REACHED, nlopt.STOPVAL_REACHED):
        assert NLOPT_STATUS_MAP[code] is Status.CONVERGED
    assert NLOPT_STATUS_MAP[nlopt.MAXEVAL_REACHED] is Status.MAX_ITER
    assert NLOPT_STATUS_MAP[nlopt.ROUNDOFF_LIMITED] is Status.FAILED
    assert NLOPT_STATUS_MAP[nlopt.INVALID_ARGS] is Status.ERROR


# ------------------------------------------------------------------------- behaviour
@pytest.mark.parametrize("name", ADAPTERS)
def test_adapter_solves_and_counts_through_the_oracle(name):
    """HS71 has bounds, an inequality and an equality: every adapter must handle all three.

    NLopt's MMA stalls on HS71 (f = 17.45 vs 17.01, measured), so it is checked on HS76
    (bounds + inequalities) here and on an equality problem below.
    """
    p = problem("hs076" if name == "nlopt-mma" else "hs071")
    calls = {"n": 0}

    def f(x):
        calls["n"] += 1
        return p.objective(x)

    counted = p.replace(objective=f)
    r = solve(counted, name)
    assert r.status is Status.CONVERGED, r.message
    assert r.max_violation <= 1e-6
    assert _rel(r.f, p.f_ref) <= 1e-5
    # every objective execution went through the oracle (f at the final point is extra, uncounted)
    assert calls["n"] == r.nf + 1
    assert r.nfg > 0 and (r.ng > 0 or name == "scipy-cobyla")


def test_ipopt_reports_exact_hessian_evaluations():
    r = solve(problem("hs071"), "ipopt")
    assert r.extra["hessian"] == "exact" and r.nh > 0


def test_ipopt_limited_memory_without_symbolic():
    p = problem("hs071").replace(symbolic=None)
    r = solve(p, "ipopt")
    assert r.extra["hessian"] == "limited-memory" and r.nh == 0
    assert r.success and _rel(r.f, p.f_ref) <= 1e-5


def test_ipopt_exact_without_symbolic_is_a_clear_error():
    p = problem("hs071").replace(symbolic=None)
    with pytest.raises(ValueError, match="symbolic"):
        solve(p, "ipopt", hessian="exact", throw=True)


@pytest.mark.parametrize("name", ["scipy-slsqp", "ipopt", "nlopt-mma", "nlopt-slsqp"])
def test_budget_exhaustion_is_max_iter(name):
    r = solve(problem("hs100"), name, max_nfg=3)
    assert r.status is Status.MAX_ITER and r.nfg <= 3


def test_mma_equalities_become_a_band_below_the_feasibility_tolerance():
    assert NloptMMA().eq_band < 1e-6
    r = solve(problem("hs028"), "nlopt-mma")  # linear equality only
    assert r.status is Status.CONVERGED and r.success
    assert r.max_violation <= 1e-6 and abs(r.f) <= 1e-8


def test_infeasible_end_is_never_success():
    """x1 <= -1 and x1 >= 1 cannot both hold: no adapter may report success."""
    p = Problem(name="infeasible", x0=[0.0, 0.0], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                ineq=lambda x: np.array([x[0] + 1.0, 1.0 - x[0]]),
                ineq_jacobian=lambda x: np.array([[1.0, 0.0], [-1.0, 0.0]]))
    for name in ["scipy-slsqp", "ipopt", "nlopt-mma", "nlopt-slsqp"]:
        r = solve(p, name)
        assert not r.success and r.max_violation > 1e-6, name


@pytest.mark.parametrize("name,bad", [
    ("scipy-slsqp", {"ftol": -1}), ("scipy-slsqp", {"maxiter": 0}), ("scipy-trust-constr", {"gtol": 0}),
    ("scipy-cobyla", {"tol": 10.0}), ("ipopt", {"hessian": "bfgs"}), ("ipopt", {"tol": float("nan")}),
    ("nlopt-mma", {"maxeval": 0}), ("nlopt-slsqp", {"xtol_rel": -1}),
])
def test_invalid_options_raise_clear_errors(name, bad):
    with pytest.raises(ValueError, match=name):
        get_solver_class(name)(**bad)


@pytest.mark.parametrize("name", ADAPTERS)
def test_options_are_documented(name):
    cls = get_solver_class(name)
    assert cls.family == "established" and {"bounds", "ineq", "eq"} <= cls.handles
    for row in cls.options():
        assert row["doc"], f"{name}.{row['name']} has no doc"


def test_slsqp_with_more_equalities_than_variables_fails_without_calling_scipy():
    """SciPy's SLSQP corrupts the heap when meq > n and inequalities are present
    (scipy/scipy#25665): the adapter answers SLSQP's mode 2 itself, and the process lives on."""
    p = Problem(name="overdetermined", x0=[0.5, 0.5], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                eq=lambda x: np.array([x[0] - 1.0, x[1] - 1.0, x[0] + x[1] - 2.0]),
                eq_jacobian=lambda x: np.array([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]),
                ineq=lambda x: np.array([x[0] - 3.0]), ineq_jacobian=lambda x: np.array([[1.0, 0.0]]))
    for _ in range(3):
        r = solve(p, "scipy-slsqp")
        assert r.status is Status.FAILED and "mode 2" in r.message and "3 > n = 2" in r.message
        assert r.nfg == 0
    r = solve(p, "scipy-cobyla")  # a SciPy run after it, the kind that aborted the process (trust-constr,
    assert r.nfg > 0               # which now also answers meq > n itself)


def test_nlopt_slsqp_more_equalities_than_variables_is_a_named_failure():
    """Three equalities in two variables (S2MPJ HS25NE, LEWISPOL): NLopt's SLSQP rejects them as
    an invalid argument; the adapter answers first, with the counts."""
    p = Problem(name="overdetermined", x0=[0.5, 0.5], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                eq=lambda x: np.array([x[0] - 1.0, x[1] - 1.0, x[0] - x[1]]),
                eq_jacobian=lambda x: np.array([[1.0, 0.0], [0.0, 1.0], [1.0, -1.0]]))
    r = solve(p, "nlopt-slsqp")
    assert r.status is Status.FAILED and r.nfg == 0
    assert "INVALID_ARGS" in r.message and "3 > n = 2" in r.message


def test_nlopt_failure_result_is_recorded_with_nlopts_reason(monkeypatch):
    """NLopt's wheels raise nlopt.runtime_error (not a Python RuntimeError) with an empty text
    for its FAILURE result; the run is a failure whose message carries opt.get_errmsg()."""
    import nlopt

    if not hasattr(nlopt, "exception"):
        pytest.skip("this NLopt build raises Python's own exceptions")

    def optimize(self, x0):
        raise nlopt.runtime_error("")

    monkeypatch.setattr(nlopt.opt, "optimize", optimize)
    monkeypatch.setattr(nlopt.opt, "last_optimize_result", lambda self: nlopt.FAILURE)
    monkeypatch.setattr(nlopt.opt, "get_errmsg", lambda self: "bug: more than iter SQP iterations")
    r = solve(problem("hs071"), "nlopt-slsqp")
    assert r.status is Status.FAILED
    assert r.message == "NLopt result -1 (FAILURE): bug: more than iter SQP iterations"


def test_trust_constr_more_equalities_than_variables_is_a_named_failure():
    p = Problem(name="overdetermined", x0=[0.5, 0.5], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                eq=lambda x: np.array([x[0] - 1.0, x[1] - 1.0, x[0] - x[1]]),
                eq_jacobian=lambda x: np.array([[1.0, 0.0], [0.0, 1.0], [1.0, -1.0]]))
    r = solve(p, "scipy-trust-constr")
    assert r.status is Status.FAILED and r.nfg == 0 and "3 > n = 2" in r.message


def test_trust_constr_non_finite_values_end_the_run_with_a_clear_message():
    """A constraint that is NaN beyond x1 = 1.5 (as S2MPJ HS101 outside its domain): SciPy's
    linear algebra raises 'array must not contain infs or NaNs'; the run names the cause."""
    def g(x):
        return np.array([x[0] + x[1] - 10.0]) if x[0] < 1.5 else np.array([np.nan])

    def jac(x):
        return np.array([[1.0, 1.0]]) if x[0] < 1.5 else np.full((1, 2), np.nan)

    p = Problem(name="nan-beyond", x0=[1.0, 0.0], objective=lambda x: float(-x[0] + x[1] ** 2),
                gradient=lambda x: np.array([-1.0, 2 * x[1]]), ineq=g, ineq_jacobian=jac)
    r = solve(p, "scipy-trust-constr")
    assert not r.success
    assert "trust-constr stopped: a non-finite f, gradient or constraint value" in r.message


def test_more_equalities_than_variables_helper():
    """One helper answers m_eq > n for the three SQP adapters: None when the problem is not
    over-determined, else a failed run at the start point (clipped to the bounds) with the
    library's verdict, the counts and the reason."""
    from problems import Oracle
    from solvers._start import more_equalities_than_variables

    square = Problem(name="square", x0=[0.5, 0.5], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                     eq=lambda x: x - 1.0, eq_jacobian=lambda x: np.eye(2))
    assert more_equalities_than_variables(Oracle(square), "native", "why") is None
    over = Problem(name="over", x0=[5.0, 0.5], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                   eq=lambda x: np.array([x[0] - 1.0, x[1] - 1.0, x[0] - x[1]]),
                   eq_jacobian=lambda x: np.array([[1.0, 0.0], [0.0, 1.0], [1.0, -1.0]]),
                   lower=[-1.0, -1.0], upper=[2.0, 2.0])
    out = more_equalities_than_variables(Oracle(over), "LIB verdict", "the reason", native_status=7)
    assert out is not None and out.status is Status.FAILED
    assert out.message == ("LIB verdict: more equality constraints than variables (3 > n = 2; "
                           "answered before calling the library: the reason)")
    assert np.array_equal(out.x, [2.0, 0.5]) and out.extra == {"native_status": 7}
