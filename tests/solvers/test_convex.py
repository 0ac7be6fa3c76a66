"""Convex-solver adapters (solvers/convex.py): status maps and real solves per backend."""

from __future__ import annotations

import cvxpy as cp
import numpy as np
import pytest

from solvers._result import Status
from solvers.convex import LINPROG_STATUS_MAP, LP_BACKENDS, QP_BACKENDS, STATUS_MAPS, map_status, solve_lp, solve_qp

CVXPY_STATUSES = [cp.OPTIMAL, cp.OPTIMAL_INACCURATE, cp.INFEASIBLE, cp.INFEASIBLE_INACCURATE,
                  cp.UNBOUNDED, cp.UNBOUNDED_INACCURATE, cp.SOLVER_ERROR, cp.USER_LIMIT]


@pytest.mark.parametrize("backend", sorted(STATUS_MAPS))
def test_status_map_covers_every_cvxpy_status(backend):
    table = STATUS_MAPS[backend]
    for s in CVXPY_STATUSES:
        assert s in table, (backend, s)
    assert table[cp.OPTIMAL] == (Status.CONVERGED, True)
    assert table[cp.INFEASIBLE] == (Status.CONVERGED, False)
    assert table[cp.SOLVER_ERROR][0] is Status.ERROR
    assert table[cp.OPTIMAL_INACCURATE][0] is not Status.CONVERGED  # never a silent success


def test_status_map_backend_specific_and_unknown():
    assert map_status("osqp", cp.OPTIMAL_INACCURATE) == (Status.MAX_ITER, True)
    assert map_status("clarabel", cp.OPTIMAL_INACCURATE) == (Status.FAILED, True)
    assert map_status("highs", "no such status") == (Status.ERROR, None)
    assert map_status("linprog", 2) == (Status.CONVERGED, False)
    assert set(LINPROG_STATUS_MAP) == {0, 1, 2, 3, 4}
    with pytest.raises(ValueError, match="unknown convex backend"):
        map_status("gurobi", cp.OPTIMAL)


A = np.array([[1.0, 1.0, 1.0]])


@pytest.mark.parametrize("backend", LP_BACKENDS)
def test_lp_feasible_and_infeasible(backend):
    r = solve_lp([1.0, 2.0, 3.0], A, [2.0], 0.0, 1.0, backend=backend)
    assert r.feasible is True and r.status is Status.CONVERGED
    np.testing.assert_allclose(r.x, [1.0, 1.0, 0.0], atol=1e-6)
    r = solve_lp([1.0, 2.0, 3.0], A, [5.0], 0.0, 1.0, backend=backend)  # sum <= 3 < 5
    assert r.feasible is False and r.x is None


@pytest.mark.parametrize("backend", QP_BACKENDS)
def test_qp_feasible_and_infeasible(backend):
    r = solve_qp(A, [1.5], 0.0, 1.0, backend=backend)
    assert r.feasible is True
    np.testing.assert_allclose(r.x, [0.5, 0.5, 0.5], atol=1e-6)
    r = solve_qp(A, [1.5], [0.0, 0.0, 0.9], 1.0, backend=backend)  # bound active
    np.testing.assert_allclose(r.x, [0.3, 0.3, 0.9], atol=1e-6)
    r = solve_qp(A, [5.0], 0.0, 1.0, backend=backend)
    assert r.feasible is False and r.x is None


def test_input_validation():
    with pytest.raises(ValueError, match="unknown LP backend"):
        solve_lp([1, 1, 1], A, [1], 0, 1, backend="cplex")
    with pytest.raises(ValueError, match="unknown QP backend"):
        solve_qp(A, [1], 0, 1, backend="highs")
    with pytest.raises(ValueError, match="NaN"):
        solve_lp([np.nan, 1, 1], A, [1], 0, 1)
    with pytest.raises(ValueError, match="lower bounds exceed"):
        solve_qp(A, [1], 1.0, 0.0)
