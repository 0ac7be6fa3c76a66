"""SciPy adapters: status maps, option mapping, bounds, counting by the oracle."""

import numpy as np
import pytest

from problems import Problem
from problems.appendix_a import make_case
from solvers import NotApplicable, Status, solve
from solvers.scipy_adapters import ScipyBFGS, ScipyCG, ScipyLBFGSB

ADAPTERS = (ScipyCG, ScipyBFGS, ScipyLBFGSB)


@pytest.mark.parametrize("cls", [ScipyCG, ScipyBFGS])
def test_status_map_of_the_gradient_methods(cls):
    assert cls.map_status(0) is Status.CONVERGED
    assert cls.map_status(1) is Status.MAX_ITER
    assert cls.map_status(2) is Status.FAILED  # precision loss
    assert cls.map_status(3) is Status.ERROR  # NaN
    assert cls.map_status(42) is Status.FAILED  # unknown codes are not successes


def test_status_map_of_lbfgsb():
    assert ScipyLBFGSB.map_status(0) is Status.CONVERGED
    assert ScipyLBFGSB.map_status(1) is Status.MAX_ITER
    assert ScipyLBFGSB.map_status(2) is Status.FAILED


@pytest.mark.parametrize("cls", ADAPTERS)
def test_rosenbrock_converges_and_counts_value_and_gradient_together(cls):
    p = make_case("a04").problem
    r = solve(p, cls.name, eps_g=1e-6)
    assert r.status is Status.CONVERGED and r.f < 1e-9
    assert r.nf == r.ng  # jac=True: one call gives both
    assert r.nfg <= r.nf


@pytest.mark.parametrize("cls", ADAPTERS)
def test_iteration_and_evaluation_caps_map_to_max_iter(cls):
    p = make_case("a13", 10).problem
    assert solve(p, cls.name, max_iter=3).status is Status.MAX_ITER
    r = solve(p, cls.name, max_fg=20)
    assert r.status is Status.MAX_ITER and 20 <= r.nfg < 60


def test_option_names_are_mapped_to_scipy():
    assert ScipyCG(eps_g=1e-7, max_iter=9)._options() == {"gtol": 1e-7, "maxiter": 9, "norm": 2.0}
    o = ScipyLBFGSB(eps_g=1e-7, max_iter=9)._options()
    assert (o["gtol"], o["maxiter"], o["maxfun"]) == (1e-7, 9, 9)
    with pytest.raises(ValueError, match="scipy-cg"):
        ScipyCG(max_iter=0)


def test_lbfgsb_passes_bounds_and_others_refuse_them():
    p = Problem(name="boxed", x0=[2.0, 2.0], objective=lambda x: float((x[0] + 1) ** 2 + (x[1] - 3) ** 2),
                gradient=lambda x: np.array([2 * (x[0] + 1), 2 * (x[1] - 3)]), lower=[0.0, -np.inf],
                upper=[np.inf, 2.5])
    r = solve(p, "scipy-lbfgsb")
    np.testing.assert_allclose(r.x, [0.0, 2.5], atol=1e-8)
    assert r.max_violation == 0.0
    with pytest.raises(NotApplicable):
        solve(p, "scipy-cg")


def test_bfgs_skips_large_problems_with_a_reason():
    assert "max_n" in ScipyBFGS().can_solve(make_case("a13", 300).problem)
    assert ScipyBFGS().can_solve(make_case("a13", 100).problem) is None
