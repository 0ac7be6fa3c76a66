"""The SciPy facade: a thesis solver driven by scipy.optimize.minimize."""

import numpy as np
from scipy.optimize import minimize, rosen, rosen_der

from solvers.scipy_compat import _to_problem, method


def test_sqsd_through_scipy_minimize():
    res = minimize(rosen, [-1.2, 1.0], jac=rosen_der, method=method("sqsd"), options={"rho": 0.3})
    assert res.success and np.allclose(res.x, [1.0, 1.0], atol=1e-4)
    assert res.nfg >= 2 and res.njev >= res.nfg - 1


def test_constraint_sign_convention_round_trip():
    # SciPy: c(x) = x0 - 1 >= 0  ->  ours: g(x) = 1 - x0 <= 0
    p = _to_problem(lambda x: x @ x, [2.0, 0.0], constraints=[{"type": "ineq", "fun": lambda x: x[0] - 1.0}])
    assert p.ineq(np.array([2.0, 0.0]))[0] == -1.0
    assert p.max_violation(np.array([0.5, 0.0])) == 0.5


def test_readme_example_converges_as_printed():
    """The README's SciPy example, verbatim."""
    from scipy.optimize import minimize, rosen, rosen_der

    from solvers.scipy_compat import method

    res = minimize(rosen, [-1.2, 1], jac=rosen_der, method=method("sqsd"), options={"rho": 0.3})
    assert res.success and res.fun < 1e-12 and res.nit < 200 and res.nfg == res.nit + 1
