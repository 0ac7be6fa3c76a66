"""A user-defined constrained problem from plain Python callables, through every constrained solver.

This is the example of docs/user_problems.md: minimize (x1 - 2)^2 + (x2 - 1)^2 subject to
x1^2 - x2 <= 0 and x1 + x2 = 2 (HS problem 6 style), x >= -5. Optimum x* = (1, 1), f* = 1.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pytest

from problems import Problem
from solvers import NotApplicable, Status, get_solver_class, solve, solver_names

X_STAR, F_STAR = np.array([1.0, 1.0]), 1.0


def make_problem(with_derivatives: bool) -> Problem:
    kw = {}
    if with_derivatives:
        kw = dict(gradient=lambda x: np.array([2 * (x[0] - 2), 2 * (x[1] - 1)]),
                  ineq_jacobian=lambda x: np.array([[2 * x[0], -1.0]]),
                  eq_jacobian=lambda x: np.array([[1.0, 1.0]]))
    return Problem(
        name="my-problem" + ("" if with_derivatives else "-fd"),
        x0=[-2.0, 3.0],
        objective=lambda x: (x[0] - 2) ** 2 + (x[1] - 1) ** 2,
        ineq=lambda x: np.array([x[0] ** 2 - x[1]]),
        eq=lambda x: np.array([x[0] + x[1] - 2]),
        lower=[-5.0, -5.0],
        f_ref=F_STAR, x_ref=X_STAR,
        fd="central",
        **kw,
    )


def constrained_solvers() -> list[str]:
    """Every registered solver that handles bounds, inequalities and equalities."""
    out = []
    for name in solver_names():
        try:
            cls = get_solver_class(name)
        except Exception:  # noqa: BLE001  (a solver module another helper is still writing)
            continue
        if {"bounds", "ineq", "eq"} <= cls.handles:
            out.append(name)
    return out


ESTABLISHED = ["scipy-slsqp", "scipy-trust-constr", "scipy-cobyla", "ipopt", "nlopt-mma", "nlopt-slsqp"]
RELIABLE = ["scipy-slsqp", "scipy-cobyla", "ipopt", "nlopt-slsqp"]  # solve this problem to E^r <= 1e-5


def test_every_established_constrained_solver_is_listed():
    assert set(ESTABLISHED) <= set(constrained_solvers())


@pytest.mark.parametrize("with_derivatives", [True, False], ids=["exact", "finite-differences"])
@pytest.mark.parametrize("name", constrained_solvers())
def test_user_problem_through_every_constrained_solver(name, with_derivatives):
    p = make_problem(with_derivatives)
    r = solve(p, name, max_nfg=20_000)
    assert r.nfg > 0 and np.isfinite(r.max_violation)
    assert r.status is not Status.ERROR, f"{name}: {r.message}"
    if name in RELIABLE:
        assert r.success, f"{name}: {r.status} {r.message}"
        assert abs(r.f - F_STAR) <= 1e-5 * (1 + F_STAR)
        assert np.allclose(r.x, X_STAR, atol=1e-3)
    elif name == "scipy-trust-constr":  # stops early with the barrier parameter ~1e-4 (measured)
        assert r.max_violation <= 1e-6 and abs(r.f - F_STAR) <= 1e-3
    # nlopt-mma ends infeasible from this infeasible start (measured); the thesis's own methods are
    # judged in their helpers' tests. Both still have to run and be recorded.
    if not with_derivatives and name != "scipy-cobyla":
        assert r.nf > r.nfg  # finite-difference evaluations are counted in nf


def test_unconstrained_only_solver_refuses_clearly():
    with pytest.raises(NotApplicable, match="my-problem"):
        solve(make_problem(True), "sqsd")


def test_command_line_suite_file(tmp_path):
    """`python -m harness run --suite-file my_problems.py` with PROBLEMS (docs/user_problems.md)."""
    f = tmp_path / "my_problems.py"
    f.write_text(textwrap.dedent('''
        import numpy as np
        from problems import Problem

        PROBLEMS = [Problem(
            name="my-problem", x0=[-2.0, 3.0],
            objective=lambda x: (x[0] - 2) ** 2 + (x[1] - 1) ** 2,
            ineq=lambda x: np.array([x[0] ** 2 - x[1]]),
            eq=lambda x: np.array([x[0] + x[1] - 2]),
            lower=[-5.0, -5.0], f_ref=1.0)]
    '''))
    out = tmp_path / "results"
    cmd = [sys.executable, "-m", "harness", "run", "--suite-file", str(f), "--solvers", "scipy-slsqp,ipopt",
           "--out", str(out), "--jobs", "1", "--quiet"]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    import pandas as pd

    files = list(out.rglob("runs.parquet"))
    assert files, f"no runs.parquet under {out}: {proc.stdout[-500:]}"
    runs = pd.concat([pd.read_parquet(x) for x in files])
    assert set(runs["solver"]) == {"scipy-slsqp", "ipopt"}
    assert runs["success"].all() and (runs["rel_error"] <= 1e-5).all()
