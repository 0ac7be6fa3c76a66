"""ETOP / ETOPC-recon (algorithms.md section 5: a documented reconstruction)."""

import numpy as np
import pytest

from problems import Problem
from solvers import Status, solve
from solvers._penalty import PenaltyForm
from solvers.etop import EtopParams, etop
from solvers.etopc import ETOPC


def rosen_grad(x):
    return np.array([-400 * x[0] * (x[1] - x[0] ** 2) - 2 * (1 - x[0]), 200 * (x[1] - x[0] ** 2)])


def test_quadratic_converges_in_few_line_searches():
    d = np.array([1.0, 10.0, 100.0])
    r = etop(lambda x: d * x, np.array([3.0, 3.0, 3.0]))
    assert r.reason == "eps_g" and r.grad_norm <= 1e-5
    assert r.nit <= 30


@pytest.mark.parametrize("beta", ["PR", "FR"])
def test_rosenbrock(beta):
    r = etop(rosen_grad, np.array([-1.2, 1.0]), EtopParams(beta=beta, max_steps=20_000))
    np.testing.assert_allclose(r.x, [1.0, 1.0], atol=1e-4)


def test_counts_every_gradient():
    calls = []

    def grad(x):
        calls.append(1)
        return 2 * x

    r = etop(grad, np.array([1.0, -2.0]))
    assert r.ng == len(calls)


def test_halfplane_three_phases():
    form = PenaltyForm(2, lambda x: 2 * x, ineq=lambda x: np.array([1 - x[0] - x[1]]),
                       ineq_jac=lambda x: np.array([[-1.0, -1.0]]))
    res = ETOPC().solve_form(form, np.array([3.0, -1.0]))
    assert res.active.ineq.tolist() == [True]
    assert abs(res.x.sum() - 1.0) < 1e-8
    np.testing.assert_allclose(res.x, [0.5, 0.5], atol=1e-5)


def test_through_solve_is_gradient_only_and_labelled():
    p = Problem(name="hp", x0=[3.0, -1.0], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                ineq=lambda x: np.array([1 - x[0] - x[1]]), ineq_jacobian=lambda x: np.array([[-1.0, -1.0]]))
    r = solve(p, "etopc")
    assert r.status is Status.CONVERGED and r.success and r.nf == 0
    assert "recon" in r.extra["reconstruction"]
    assert "reconstruction" in ETOPC.summary.lower() or "recon" in ETOPC.summary


def test_hs076_inline():
    from _hs_inline import hs076
    r = solve(hs076(), "etopc")
    assert r.max_violation < 1e-6 and abs(r.f + 4.681818181818182) < 1e-5


def test_deterministic():
    a = etop(rosen_grad, np.array([-1.2, 1.0]))
    b = etop(rosen_grad, np.array([-1.2, 1.0]))
    assert a.ng == b.ng and np.array_equal(a.x, b.x)


@pytest.mark.parametrize("bad", [dict(beta="HS"), dict(eta=1.5), dict(gamma=0.5), dict(h0=0.0), dict(max_line=1)])
def test_invalid(bad):
    with pytest.raises(ValueError, match="etop"):
        EtopParams(**bad)
    with pytest.raises(ValueError):
        ETOPC(**bad)
