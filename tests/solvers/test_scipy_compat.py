"""The SciPy facade: a thesis solver driven by scipy.optimize.minimize."""

import numpy as np
import pytest
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


def _dist(x):
    return (x[0] - 3.0) ** 2 + (x[1] - 3.0) ** 2


def test_each_constraint_gets_its_own_args():
    import numpy as np
    from scipy.optimize import minimize

    cons = [{"type": "ineq", "fun": lambda x, a: a - x[0], "args": (1.0,)},
            {"type": "ineq", "fun": lambda x, b: b - x[1], "jac": lambda x, b: np.array([0.0, -1.0]), "args": (2.0,)}]
    for name in ("scipy-slsqp", "dynamic-q-plus"):
        res = minimize(_dist, [0.0, 0.0], method=method(name), constraints=cons)
        np.testing.assert_allclose(res.x, [1.0, 2.0], atol=1e-5)


def test_new_style_constraints_are_converted():
    import numpy as np
    from scipy.optimize import LinearConstraint, NonlinearConstraint, minimize

    # x0 + x1 <= 2 (one-sided), x0 - x1 = 0.5 (lb == ub), 0 <= x1 <= 10 (two-sided, inactive)
    nl = NonlinearConstraint(lambda x: x[0] + x[1], -np.inf, 2.0, jac=lambda x: np.array([[1.0, 1.0]]))
    lin = [LinearConstraint([[1.0, -1.0]], 0.5, 0.5), LinearConstraint([[0.0, 1.0]], 0.0, 10.0)]
    res = minimize(_dist, [0.0, 0.0], method=method("scipy-slsqp"), constraints=[nl, *lin])
    ref = minimize(_dist, [0.0, 0.0], method="SLSQP", constraints=[nl, *lin])
    np.testing.assert_allclose(res.x, ref.x, atol=1e-6)
    np.testing.assert_allclose(res.x, [1.25, 0.75], atol=1e-6)
    with pytest.raises(ValueError, match="lb <= ub"):
        minimize(_dist, [0.0, 0.0], method=method("scipy-slsqp"), constraints=NonlinearConstraint(sum, 1.0, 0.0))


def test_a_malformed_constraint_is_named():
    from scipy.optimize import minimize

    with pytest.raises(TypeError, match="each constraint must be a dict"):
        minimize(_dist, [0.0, 0.0], method=method("scipy-slsqp"), constraints=[lambda x: x[0]])
    with pytest.raises(ValueError, match="'ineq' or 'eq'"):
        minimize(_dist, [0.0, 0.0], method=method("scipy-slsqp"), constraints={"type": "le", "fun": sum})


def test_tol_and_callback_are_refused_and_hess_is_warned_about():
    from scipy.optimize import minimize, rosen, rosen_der

    with pytest.raises(ValueError, match="eps_g"):  # SQSD's own tolerance is named
        minimize(rosen, [-1.2, 1.0], jac=rosen_der, method=method("sqsd"), tol=0.1)
    with pytest.raises(ValueError, match="callback"):
        minimize(rosen, [-1.2, 1.0], jac=rosen_der, method=method("sqsd"), callback=print)
    with pytest.warns(RuntimeWarning, match="Hessian"):
        res = minimize(rosen, [-1.2, 1.0], jac=rosen_der, hess=lambda x: None, method=method("sqsd"),
                       options={"rho": 0.3})
    assert res.success


def test_a_two_sided_constraint_splits_into_equalities_and_both_inequalities():
    from scipy.optimize import LinearConstraint

    p = _to_problem(_dist, [0.0, 0.0], constraints=LinearConstraint([[1.0, -1.0], [0.0, 1.0]], [0.5, 0.0], [0.5, 10.0]))
    x = np.array([2.0, 1.0])
    np.testing.assert_allclose(p.eq(x), [0.5])  # x0 - x1 - 0.5
    np.testing.assert_allclose(p.ineq(x), [-1.0, -9.0])  # -(x1 - 0), -(10 - x1): g <= 0 form
    np.testing.assert_allclose(p.eq_jacobian(x), [[1.0, -1.0]])
    np.testing.assert_allclose(p.ineq_jacobian(x), [[0.0, -1.0], [0.0, 1.0]])
