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
    with pytest.raises(BudgetExhausted):  # asking again is no way around the budget
        o.grad([0.0, 3.0])
    assert (o.nfg, o.nf, o.ng) == (2, 2, 0)
    np.testing.assert_array_equal(o.last_x, [0.0, 2.0])  # the oracle stays at the last point


def test_bad_inputs_are_clear_errors():
    with pytest.raises(ProblemError, match="NaN"):
        Problem(name="bad", x0=[np.nan, 1.0], objective=lambda x: 0.0)
    with pytest.raises(ProblemError, match="lower > upper"):
        Problem(name="bad", x0=[0.0], objective=lambda x: 0.0, lower=[1.0], upper=[0.0])
    with pytest.raises(ProblemError, match="expected n = 2"):
        Oracle(quad()).f([1.0, 2.0, 3.0])


def constrained():
    return Problem(name="c2", x0=[1.0, 2.0], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                   ineq=lambda x: np.array([x[0] - 0.5, x @ x - 4.0]),
                   ineq_jacobian=lambda x: np.array([[1.0, 0.0], 2 * x]),
                   eq=lambda x: np.array([x[0] + x[1] - 1.0]), eq_jacobian=lambda x: np.array([[1.0, 1.0]]),
                   lower=[-3.0, -3.0], upper=[3.0, 3.0])


def test_a_point_reads_everything_with_the_counts_of_separate_calls():
    xs = [np.array([0.3, 0.9]), np.array([1.5, -0.5]), np.array([0.3, 0.9])]
    a, b = Oracle(constrained()), Oracle(constrained())
    for x in xs:
        pt = a.at(x)
        got = (pt.f(), pt.grad(), pt.ineq(), pt.ineq_jac(), pt.eq(), pt.eq_jac())
        want = (b.f(x), b.grad(x), b.ineq(x), b.ineq_jac(x), b.eq(x), b.eq_jac(x))
        for u, v in zip(got, want):
            np.testing.assert_array_equal(u, v)
    assert a.counts() == b.counts() and a.counts()["nfg"] == 2
    np.testing.assert_array_equal(a.history(), b.history())


def test_a_point_counts_nothing_until_read_and_survives_moving_away():
    o = Oracle(constrained())
    pt = o.at([0.3, 0.9])
    assert o.nfg == 0  # nothing read yet
    g = pt.grad()
    o.f([1.0, 1.0])  # the solver moves on ...
    np.testing.assert_array_equal(pt.grad(), g)  # ... and comes back: not a new point
    assert (o.nfg, o.ng, o.nf) == (2, 2, 1)  # (only the last point's values are cached)
    pt.ineq()
    pt.ineq()
    assert (o.nfg, o.nc) == (2, 1)


def test_values_read_from_a_point_cannot_be_written_and_copies_can():
    o = Oracle(constrained())
    pt = o.at([0.3, 0.9])
    with pytest.raises(ValueError):
        pt.grad()[0] = 1.0
    with pytest.raises(ValueError):
        pt.ineq_jac()[0, 0] = 1.0
    g = o.grad([0.3, 0.9])  # the public methods return copies the caller owns
    g[0] = 99.0
    assert pt.grad()[0] == 0.6
    x = o.last_x
    x[0] = 99.0
    assert o.last_x[0] == 0.3


@pytest.mark.parametrize("n", [3, 16, 17, 40])
def test_points_are_told_apart_by_their_bytes_at_every_size(n):
    """Short points are keyed by their bytes, long ones by a digest: the same counts either way."""
    p = Problem(name="q", x0=np.ones(n), objective=lambda x: float(x @ x), gradient=lambda x: 2 * x)
    o = Oracle(p)
    x = np.linspace(0.0, 1.0, n)
    y = x.copy()
    y[-1] = np.nextafter(y[-1], 2.0)  # one ulp apart in the last component
    z = x.copy()
    z[0] = -0.0  # +0.0 and -0.0 differ in their bytes, so they are two points
    for pt in (x, y, x.copy(), z, list(x)):
        o.grad(pt)
    assert o.nfg == 3 and o.ng == 5  # x, y and z; each move re-evaluates
