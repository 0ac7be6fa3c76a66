"""A user's problems are checked at x0 before any run (harness._preflight; docs/user_problems.md,
"Checked before the runs"): wrong shapes are bad input naming the problem, doubtful derivatives and
non-finite starts are warnings."""

import textwrap

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from harness import ProblemInputError, check_problem
from harness._store import Store
from harness.cli import main
from problems import Problem


def _quad(**kw):
    base = dict(name="p", x0=[1.0, 2.0, 3.0], objective=lambda x: float(x @ x))
    base.update(kw)
    return Problem(**base)


@pytest.mark.parametrize("kw, says", [
    (dict(objective=lambda x: 2 * x), "objective(x0) returned an array of shape (3,); it must return one number"),
    (dict(objective=lambda x: "a"), "objective(x0) returned str"),
    (dict(objective=lambda x: True), "objective(x0) returned bool"),  # the oracle refuses a bool too
    (dict(gradient=lambda x: np.ones(2)), "gradient(x0) has shape (2,); expected (3,)"),
    (dict(gradient=lambda x: np.ones((3, 3))), "gradient(x0) has shape (3, 3); expected (3,)"),
    (dict(ineq=lambda x: x[:2], n_ineq=3), "ineq(x0) has shape (2,); expected (3,) (n_ineq = 3)"),
    (dict(ineq=lambda x: x[:2], ineq_jacobian=lambda x: np.eye(3)[:2].T),
     "ineq_jacobian(x0) has shape (3, 2); expected (2, 3) = (n_ineq, n) (the transpose"),
    (dict(eq=lambda x: x[:2], eq_jacobian=lambda x: np.ones(6)), "eq_jacobian(x0) has shape (6,); expected (2, 3)"),
    (dict(gradient=lambda x: 1 / 0), "gradient(x0) raised ZeroDivisionError"),
])
def test_wrong_shapes_and_failures_at_x0_are_bad_input_naming_the_problem(kw, says):
    with pytest.raises(ProblemInputError, match="problem 'p': ") as info:
        check_problem(_quad(**kw))
    assert says in str(info.value)


def test_one_constraint_may_return_its_jacobian_as_a_vector():
    p = _quad(ineq=lambda x: np.array([x.sum() - 1]), ineq_jacobian=lambda x: np.ones(3))
    assert check_problem(p) == []


def test_wrong_derivatives_and_non_finite_starts_are_warnings():
    notes = check_problem(_quad(gradient=lambda x: 3 * x))
    assert len(notes) == 1 and "gradient at x0 differs from central differences by 3 at [2]" in notes[0]
    notes = check_problem(_quad(eq=lambda x: x[:1] ** 2, eq_jacobian=lambda x: np.array([[1.0, 0, 0]])))
    assert len(notes) == 1 and "eq_jacobian at x0 differs" in notes[0] and "[0, 0]" in notes[0]
    notes = check_problem(_quad(objective=lambda x: float("nan")))
    assert len(notes) == 1 and "objective not finite at x0" in notes[0]
    assert check_problem(_quad(gradient=lambda x: 3 * x), derivatives=False) == []


@settings(max_examples=30, deadline=None, derandomize=True)
@given(st.integers(1, 6), st.integers(1, 5), st.integers(0, 2 ** 31 - 1))
def test_exact_derivatives_pass_and_a_transposed_jacobian_never_does(n, m, seed):
    """Invariant: a smooth problem with its exact derivatives gives no note; the transpose of a
    non-square Jacobian is always refused (the oracle would have reshaped it silently)."""
    rng = np.random.default_rng(seed)
    A, Q, b = rng.normal(size=(m, n)), rng.normal(size=(n, n)), rng.normal(size=m)
    Q = Q @ Q.T
    x0 = rng.normal(size=n)
    ok = Problem(name="r", x0=x0, objective=lambda x: float(x @ Q @ x + np.sin(x).sum()),
                 gradient=lambda x: 2 * Q @ x + np.cos(x), ineq=lambda x: A @ x - b + 0.1 * (x @ x),
                 ineq_jacobian=lambda x: A + 0.2 * x)
    assert check_problem(ok) == []
    if m != n:
        bad = ok.replace(ineq_jacobian=lambda x: (A + 0.2 * x).T)
        with pytest.raises(ProblemInputError, match="the transpose"):
            check_problem(bad)


def test_run_refuses_a_suite_file_with_a_bad_problem_before_any_work(tmp_path, capsys):
    f = tmp_path / "bad_problems.py"
    f.write_text(textwrap.dedent("""
        import numpy as np
        from problems import Problem
        PROBLEMS = [Problem(name="fine", x0=[1.0], objective=lambda x: float(x @ x)),
                    Problem(name="vector-f", x0=[1.0, 2.0], objective=lambda x: 2 * x)]
    """))
    for extra in ([], ["--dry-run"]):
        code = main(["run", "--suite-file", str(f), "--solvers", "scipy-slsqp", "--out", str(tmp_path / "out"),
                     "--quiet", *extra])
        err = capsys.readouterr().err.strip().splitlines()
        assert code == 2 and err[-1] == ("error: problem 'vector-f': objective(x0) returned an array of shape (2,); "
                                         "it must return one number")
    assert not Store(tmp_path / "out", "bad-problems").exists()
    # the bad problem left out: the run goes on
    assert main(["run", "--suite-file", str(f), "--solvers", "scipy-slsqp", "--problems", "fine",
                 "--out", str(tmp_path / "out"), "--quiet"]) == 0


def test_run_warns_of_a_doubtful_gradient_and_still_runs(tmp_path, capsys):
    f = tmp_path / "doubtful.py"
    f.write_text(textwrap.dedent("""
        from problems import Problem
        PROBLEMS = [Problem(name="g3", x0=[1.0, 2.0], objective=lambda x: float(x @ x), gradient=lambda x: 3 * x)]
    """))
    code = main(["run", "--suite-file", str(f), "--solvers", "scipy-slsqp", "--out", str(tmp_path), "--quiet"])
    err = capsys.readouterr().err
    assert code == 0 and "warning: problem 'g3': gradient at x0 differs from central differences" in err
    assert Store(tmp_path, "doubtful").exists()
