"""The counting wrapper: N^fg counts distinct points; raw calls and finite differences counted."""

import numpy as np
import pytest

from problems import BudgetExhausted, Oracle, Problem, ProblemError


def quad(**kw):
    return Problem(name="quad", x0=[3.0, -1.0], objective=lambda x: float(x @ x),
                   gradient=lambda x: 2 * x, **kw)


def test_value_and_gradient_at_one_point_count_once():
    o = Oracle(quad())
    x = np.array([1.0, 2.0])
    o.f(x)
    o.grad(x)
    o.f(x.copy())
    assert (o.nfg, o.nf, o.ng) == (1, 1, 1)
    o.grad([0.5, 0.5])
    assert o.nfg == 2 and o.ng == 2


def test_returning_to_a_point_is_not_a_new_point():
    o = Oracle(quad())
    o.f([1.0, 1.0])
    o.f([2.0, 2.0])
    o.f([1.0, 1.0])
    assert o.nfg == 2
    assert o.nf == 3  # raw executions are all kept


def test_forward_difference_gradient_counts_function_evaluations():
    p = Problem(name="q", x0=[1.0, 2.0, 3.0], objective=lambda x: float(x @ x), fd_step=1e-7)
    o = Oracle(p)
    g = o.grad(p.x0)
    assert np.allclose(g, 2 * p.x0, atol=1e-5)
    assert o.nfg == 1 and o.ng == 1 and o.nf == 1 + 3


def test_central_difference_gradient_counts_2n():
    p = Problem(name="q", x0=[1.0, 2.0], objective=lambda x: float(x @ x), fd="central", fd_step=1e-4)
    o = Oracle(p)
    g = o.grad(p.x0)
    assert np.allclose(g, 2 * p.x0, atol=1e-8)
    assert o.nf == 4


def test_constraint_jacobian_by_finite_differences_counted():
    p = Problem(name="c", x0=[1.0, 1.0], objective=lambda x: x[0], ineq=lambda x: np.array([x @ x - 1.0]))
    o = Oracle(p)
    J = o.ineq_jac(p.x0)
    assert J.shape == (1, 2) and np.allclose(J, [[2, 2]], atol=1e-4)
    assert o.nc == 1 + 2 and o.nj == 1 and o.nfg == 1


def test_history_records_f_and_violation():
    p = Problem(name="c", x0=[1.0, 1.0], objective=lambda x: x[0], ineq=lambda x: np.array([x @ x - 1.0]))
    o = Oracle(p)
    o.f([2.0, 0.0])
    o.ineq([2.0, 0.0])
    h = o.history()
    assert h.shape == (1, 3) and h[0, 1] == 2.0 and h[0, 2] == pytest.approx(3.0)


def test_budget():
    o = Oracle(quad(), max_nfg=2)
    o.f([0.0, 1.0])
    o.f([0.0, 2.0])
    with pytest.raises(BudgetExhausted):
        o.f([0.0, 3.0])


def test_bad_inputs_are_clear_errors():
    with pytest.raises(ProblemError, match="NaN"):
        Problem(name="bad", x0=[np.nan, 1.0], objective=lambda x: 0.0)
    with pytest.raises(ProblemError, match="lower > upper"):
        Problem(name="bad", x0=[0.0], objective=lambda x: 0.0, lower=[1.0], upper=[0.0])
    with pytest.raises(ProblemError, match="expected n = 2"):
        Oracle(quad()).f([1.0, 2.0, 3.0])
