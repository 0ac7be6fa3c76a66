"""Bad user definitions are refused with a `ProblemError` naming the problem; NaN constraints count as violated."""

import numpy as np
import pytest

from problems import Oracle, Problem, ProblemError, get_suite

X0 = [1.0, 2.0]


def problem(**kw):
    args = {"name": "bad", "x0": X0, "objective": lambda x: float(x @ x), **kw}
    return Problem(**args)


# ------------------------------------------------------------------ NaN constraints
@pytest.mark.parametrize("which", ["ineq", "eq"])
def test_nan_constraint_is_violated_in_max_violation_and_history(which):
    p = problem(**{which: lambda x: np.array([np.nan if x[0] > 1.5 else -1.0 if which == "ineq" else 0.0, 0.0])})
    x = np.array([2.0, 2.0])
    assert np.isnan(p.max_violation(x))
    assert p.max_violation(np.array([1.0, 2.0])) == 0.0
    o = Oracle(p)
    o.f(x)
    getattr(o, which)(x)
    assert np.isnan(o.history()[-1, 2])
    assert np.isnan(o.complete_history()[-1, 2])


def test_nan_constraint_is_violated_with_bounds():
    p = problem(ineq=lambda x: np.array([np.nan]), eq=lambda x: np.array([0.0]), lower=[0.0, 0.0], upper=[3.0, 3.0])
    x = np.array([5.0, 1.0])  # violates a bound by 2 as well
    assert np.isnan(p.max_violation(x))
    o = Oracle(p)
    pt = o.at(x)
    pt.ineq()
    pt.eq()
    assert np.isnan(o.history()[-1, 2])


def test_finite_violations_are_unchanged():
    g = lambda x: np.array([x[0] - 1.0, -x[1]])
    h = lambda x: np.array([x[0] + x[1] - 2.0])
    p = problem(ineq=g, eq=h, lower=[-1.0, -1.0], upper=[4.0, 4.0])
    o = Oracle(p)
    for x in ([1.0, 2.0], [3.0, -0.5], [0.0, 0.0], [5.0, 1.0], [-0.0, 2.0], [1.0, 1.0]):
        x = np.array(x)
        want = max(0.0, *g(x), *np.abs(h(x)), *(p.lower - x), *(x - p.upper))
        assert p.max_violation(x) == want
        o.ineq(x)
        o.eq(x)
        assert o.history()[-1, 2] == want


# ------------------------------------------------------------------ objective
@pytest.mark.parametrize("value", [np.array([1.0, 2.0]), np.array([1.0]), None, "1.5", b"1.5", np.array(["1.5"]), True])
def test_objective_that_is_not_one_number_is_refused(value):
    o = Oracle(problem(objective=lambda x: value))
    with pytest.raises(ProblemError, match="bad: objective returned .*expected one number"):
        o.f(X0)


@pytest.mark.parametrize("value", [np.float32(4.0), 4, np.int64(4), np.array(4.0)])
def test_objective_of_one_number_is_accepted(value):
    assert Oracle(problem(objective=lambda x: value)).f(X0) == 4.0


@pytest.mark.parametrize("fd", ["forward", "central"])
def test_objective_vector_in_finite_difference_gradient_is_refused(fd):
    o = Oracle(problem(objective=lambda x: x * 1.0, fd=fd))
    with pytest.raises(ProblemError, match="bad: objective returned"):
        o.grad(X0)


# ------------------------------------------------------------------ derivatives and constraints
@pytest.mark.parametrize("value", [None, "abc", ["1.0", "2.0"], [1.0, None]])
@pytest.mark.parametrize("which", ["gradient", "ineq", "eq"])
def test_non_numeric_values_are_refused_naming_the_function(which, value):
    kw = {which: lambda x: value}
    if which != "gradient":
        kw[f"n_{which}"] = 2
    o = Oracle(problem(**kw))
    with pytest.raises(ProblemError, match=f"bad: {which} returned .*expected numbers"):
        getattr(o, "grad" if which == "gradient" else which)(X0)


@pytest.mark.parametrize("value", [None, "abc", [[1.0, None]]])
@pytest.mark.parametrize("which", ["ineq", "eq"])
def test_non_numeric_jacobian_is_refused(which, value):
    o = Oracle(problem(**{which: lambda x: np.array([x[0]]), f"{which}_jacobian": lambda x: value}))
    with pytest.raises(ProblemError, match=f"bad: {which}_jacobian returned .*expected numbers"):
        getattr(o, f"{which}_jac")(X0)


@pytest.mark.parametrize("shape", [(3, 2), (6,), (1, 6), (2, 3, 1), ()])
def test_jacobian_of_the_wrong_shape_is_refused(shape):
    p = Problem(name="bad", x0=[1.0, 2.0, 3.0], objective=lambda x: 0.0, ineq=lambda x: x[:2],
                ineq_jacobian=lambda x: np.zeros(shape))
    with pytest.raises(ProblemError, match=r"bad: ineq_jacobian returned shape .*expected \(m, n\) = \(2, 3\)"):
        Oracle(p).ineq_jac(p.x0)


def test_jacobian_flat_vector_only_for_one_constraint():
    p = problem(eq=lambda x: np.array([x[0] + x[1]]), eq_jacobian=lambda x: [1.0, 1.0])
    assert Oracle(p).eq_jac(X0).tolist() == [[1.0, 1.0]]
    p = problem(eq=lambda x: np.array([x[0] + x[1]]), eq_jacobian=lambda x: [[1.0], [1.0]])
    with pytest.raises(ProblemError, match=r"eq_jacobian returned shape \(2, 1\); expected \(m, n\) = \(1, 2\)"):
        Oracle(p).eq_jac(X0)


@pytest.mark.parametrize("fd", ["forward", "central"])
def test_finite_difference_jacobian_of_a_changing_size_is_refused(fd):
    # two constraints at x0, one next to it: forward differences used to broadcast, central to reshape
    p = problem(ineq=lambda x: np.array([1.0, 2.0]) if x[0] == 1.0 else np.array([0.0]), fd=fd)
    with pytest.raises(ProblemError, match="bad: ineq returned .*expected 2 numbers"):
        Oracle(p).ineq_jac(X0)


def test_finite_difference_jacobian_of_none_is_refused():
    p = problem(ineq=lambda x: np.array([1.0]) if x[0] == 1.0 else None, fd="central")
    with pytest.raises(ProblemError, match="bad: ineq returned None"):
        Oracle(p).ineq_jac(X0)


# ------------------------------------------------------------------ the definition itself
@pytest.mark.parametrize("field", ["x0", "lower", "upper"])
@pytest.mark.parametrize("value", ["1.5", ["1.5", "2.0"], [1.0, "2.0"], b"1.5", [None, 1.0]])
def test_vectors_of_strings_are_refused(field, value):
    kw = {"lower": [-9.0, -9.0], "upper": [9.0, 9.0], field: value}
    with pytest.raises(ProblemError, match=f"bad: {field} must be a vector of numbers"):
        problem(**kw)


@pytest.mark.parametrize("f_ref", ["1.0", np.nan, np.inf, -np.inf, True, np.array([1.0])])
def test_bad_f_ref_is_refused(f_ref):
    with pytest.raises(ProblemError, match="bad: f_ref must be a finite number"):
        problem(f_ref=f_ref)


def test_good_f_ref_and_x_ref_are_kept():
    p = problem(f_ref=np.float64(1.5), x_ref=[0, 1])
    assert p.f_ref == 1.5 and type(p.f_ref) is float and p.x_ref.tolist() == [0.0, 1.0]


@pytest.mark.parametrize("x_ref", [[np.nan, 0.0], [0.0, np.inf]])
def test_non_finite_x_ref_is_refused(x_ref):
    with pytest.raises(ProblemError, match="bad: x_ref contains NaN or inf"):
        problem(x_ref=x_ref)


@pytest.mark.parametrize("value", [None, "abc", [1.0, None]])
@pytest.mark.parametrize("which", ["ineq", "eq"])
def test_constraint_count_from_non_numeric_value_is_refused(which, value):
    with pytest.raises(ProblemError, match=rf"bad: {which}\(x0\) returned .*expected a vector of numbers"):
        problem(**{which: lambda x: value})


@pytest.mark.parametrize("count", [-1, 1.0, 1.5, "2", True])
@pytest.mark.parametrize("which", ["ineq", "eq"])
def test_bad_constraint_count_is_refused(which, count):
    with pytest.raises(ProblemError, match=f"bad: n_{which} must be a non-negative integer"):
        problem(**{which: lambda x: np.zeros(2), f"n_{which}": count})


def test_constraint_count_without_the_function_is_refused():
    with pytest.raises(ProblemError, match="bad: n_ineq = 2 given without ineq"):
        problem(n_ineq=2)
    assert problem(n_ineq=0, n_eq=np.int64(0)).n_eq == 0


def test_given_constraint_count_is_not_checked_by_a_call():
    calls = []
    p = problem(ineq=lambda x: calls.append(x) or np.zeros(3), n_ineq=np.int64(3))
    assert p.n_ineq == 3 and type(p.n_ineq) is int and not calls


# ------------------------------------------------------------------ suites
def test_suite_without_selections_names_no_command_line_option():
    with pytest.raises(ValueError, match="does not support selection expressions") as err:
        get_suite("appendix-a").select("type=u")
    assert "--" not in str(err.value) and "case id" in str(err.value)
