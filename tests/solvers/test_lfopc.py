"""LFOPC: three-phase penalty scheme (thesis Appendix B.4; algorithms.md section 2)."""

import numpy as np
import pytest
from scipy.optimize import minimize as sp_minimize

from problems import Problem
from solvers import Status, solve
from solvers.lfopc import LFOPC, PenaltyForm


def halfplane_form():
    # min x1^2 + x2^2 s.t. 1 - x1 - x2 <= 0  -> (0.5, 0.5)
    return PenaltyForm(2, lambda x: 2 * x, ineq=lambda x: np.array([1 - x[0] - x[1]]),
                       ineq_jac=lambda x: np.array([[-1.0, -1.0]]))


def test_phase1_flags_active_and_phase2_lands_on_the_constraint():
    # algorithms.md section 6
    res = LFOPC().solve_form(halfplane_form(), np.array([3.0, -1.0]))
    assert res.active.ineq.tolist() == [True]
    assert [ph.phase for ph in res.phases] == [0, 1, 2]
    assert abs(res.x.sum() - 1.0) < 1e-8
    np.testing.assert_allclose(res.x, [0.5, 0.5], atol=1e-5)
    assert res.converged and res.ng == sum(ph.ng for ph in res.phases)


def test_inactive_constraint_skips_phase2():
    form = PenaltyForm(2, lambda x: 2 * (x - 3), ineq=lambda x: np.array([1 - x[0] - x[1]]),
                       ineq_jac=lambda x: np.array([[-1.0, -1.0]]))
    res = LFOPC().solve_form(form, np.zeros(2))
    assert [ph.phase for ph in res.phases] == [0, 1]
    np.testing.assert_allclose(res.x, [3.0, 3.0], atol=1e-5)


def test_literal_phase2_option_runs():
    res = LFOPC(phase2_exterior=False).solve_form(halfplane_form(), np.array([3.0, -1.0]))
    assert abs(res.x.sum() - 1.0) < 1e-8


def test_cable_tension_qp_via_penalty_form():
    # thesis eq. (6.17): min ||t||^2 s.t. S t = -w, t_min <= t <= t_max (4 cables, planar wrench)
    S = np.array([[1.0, 0.0, -1.0, 0.3], [0.0, 1.0, 0.2, -1.0], [0.5, -0.4, 0.3, 0.2]])
    w = np.array([-0.7, -0.4, -0.1])
    t_min, t_max = 0.1, 2.0
    form = PenaltyForm(4, lambda t: 2 * t, eq=lambda t: S @ t + w, eq_jac=lambda t: S, lower=t_min, upper=t_max)
    res = LFOPC().solve_form(form, np.full(4, t_min))
    ref = sp_minimize(lambda t: t @ t, np.full(4, 1.0), jac=lambda t: 2 * t, method="SLSQP",
                      bounds=[(t_min, t_max)] * 4, constraints=[{"type": "eq", "fun": lambda t: S @ t + w}],
                      options={"ftol": 1e-14})
    assert ref.success
    assert res.max_violation < 1e-6
    np.testing.assert_allclose(res.x, ref.x, atol=1e-4)


def test_through_the_oracle_counts_gradients_only():
    p = Problem(name="hp", x0=[3.0, -1.0], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                ineq=lambda x: np.array([1 - x[0] - x[1]]), ineq_jacobian=lambda x: np.array([[-1.0, -1.0]]),
                f_ref=0.5)
    r = solve(p, "lfopc")
    assert r.status is Status.CONVERGED and r.success
    assert r.nf == 0  # gradient-only: f is never evaluated by the solver
    # every gradient point is one oracle point; a phase restarts at the point where the
    # previous one ended, which the oracle has already counted
    n_phases = len(r.extra["phases"])
    assert r.extra["ng"] - (n_phases - 1) <= r.nfg <= r.extra["ng"]
    assert abs(r.f - 0.5) < 1e-8 and r.max_violation < 1e-8


def test_bounds_and_equalities_hs071_like():
    from _hs_inline import hs071
    r = solve(hs071(), "lfopc")
    assert r.max_violation < 1e-6
    assert abs(r.f - 17.0140172891563) / 18 < 1e-4


def test_deterministic():
    a = LFOPC().solve_form(halfplane_form(), np.array([3.0, -1.0]))
    b = LFOPC().solve_form(halfplane_form(), np.array([3.0, -1.0]))
    assert a.ng == b.ng and np.array_equal(a.x, b.x)


@pytest.mark.parametrize("bad", [dict(mu0=1e5, mu1=1e4), dict(mu0=0.0), dict(delta=-1.0), dict(active_tol=-1),
                                 dict(dt_mode="x")])
def test_invalid_options(bad):
    with pytest.raises(ValueError):
        LFOPC(**bad)


def test_penalty_form_validation():
    with pytest.raises(ValueError, match="Jacobian"):
        PenaltyForm(2, lambda x: x, ineq=lambda x: x)
    with pytest.raises(ValueError, match="n must"):
        PenaltyForm(0, lambda x: x)
    with pytest.raises(ValueError, match="lower <= upper"):
        PenaltyForm(2, lambda x: x, lower=1.0, upper=0.0)
