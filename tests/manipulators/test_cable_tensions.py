"""Cable tensions (thesis Section 6.3): equilibrium, bounds, feasibility against an
independent LP, l1 norms of Algorithm 6.1 / basic solutions against LP, l2 against QP."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog

from manipulators import CableRobot
from manipulators.cable import METHODS, design_robot, frame_point, loads, thesis_robot
from manipulators.cable._distribution import distribute, interval_4, min_norm, vertices

T_MIN, T_MAX = 5.0, 100.0
EQ_TOL = 1e-9      # equilibrium residual |S t + w| (acceptance)
L1_TOL = 1e-8      # l1 norm: closed form vs LP (acceptance)
MARGIN = 1e-6      # LP bounds shifted by this to decide feasibility robustly


def random_cases(rng: np.random.Generator, count: int):
    """Random robots (n = 3..6), poses and loads; yields (robot, u, phi, w)."""
    for _ in range(count):
        n = int(rng.integers(3, 7))
        c = rng.uniform(-1, 1, (n, 2))
        a = rng.uniform(-0.15, 0.15, (n, 2))
        robot = CableRobot(c, a, t_min=T_MIN, t_max=T_MAX, l_min=0.0)
        u = rng.uniform(-0.6, 0.6, 2)
        phi = float(rng.uniform(-0.4, 0.4))
        w = np.concatenate([rng.uniform(-25, 25, 2), rng.uniform(-2, 2, 1)])
        yield robot, u, phi, w


def lp_verdict(S: np.ndarray, w: np.ndarray, shift: float) -> bool:
    """Independent feasibility test: linprog on t_min + shift <= t <= t_max - shift."""
    n = S.shape[1]
    res = linprog(np.zeros(n), A_eq=S, b_eq=-w, bounds=[(T_MIN + shift, T_MAX - shift)] * n, method="highs")
    assert res.status in (0, 2), res.message
    return res.status == 0


def lp_l1(S: np.ndarray, w: np.ndarray, sign: float = 1.0) -> float:
    n = S.shape[1]
    res = linprog(sign * np.ones(n), A_eq=S, b_eq=-w, bounds=[(T_MIN, T_MAX)] * n, method="highs")
    return float(res.x.sum())


def check_lfopc(robot, u, phi, w):
    """l2 tensions (6.17) from LFOPC agree with Clarabel and OSQP to 1e-4 (acceptance)."""
    t_l = robot.tensions(u, phi, w, "l2", backend="lfopc")
    assert t_l is not None
    for b in ("clarabel", "osqp"):
        np.testing.assert_allclose(t_l, robot.tensions(u, phi, w, "l2", backend=b), atol=1e-4)


def check_case(robot, u, phi, w, *, compare_norms: bool = True):
    """All the acceptance checks for one robot, pose and load; returns feasibility."""
    S = robot.structure_matrix(u, phi)[0]
    results = {m: robot.tensions(u, phi, w, m) for m in METHODS if m != "l2" or robot.n <= 4}
    feasible = results["l1"] is not None
    for m, t in results.items():
        if t is None:
            continue
        assert np.max(np.abs(S @ t + w)) <= EQ_TOL, (m, S @ t + w)
        assert np.all(t >= T_MIN - 1e-9) and np.all(t <= T_MAX + 1e-9), (m, t)
        assert feasible, f"{m} returned tensions where l1 found none"
    for m in ("l1-max", "l2-max") + (("l2",) if robot.n <= 4 else ()):
        assert (results[m] is not None) == feasible, m
    # feasibility against the LP, decided away from the boundary
    if lp_verdict(S, w, +MARGIN):
        assert feasible
    if not lp_verdict(S, w, -MARGIN):
        assert not feasible
    if feasible and compare_norms:
        assert abs(results["l1"].sum() - lp_l1(S, w)) <= L1_TOL * max(1.0, results["l1"].sum())
        assert abs(results["l1-max"].sum() - lp_l1(S, w, -1.0)) <= L1_TOL * max(1.0, results["l1-max"].sum())
    return feasible


def test_random_robots_poses_loads():
    """600 random cases (the 10 000 of the acceptance: test_random_robots_10000, slow)."""
    rng = np.random.default_rng(20030601)
    n_feas = sum(check_case(*case) for case in random_cases(rng, 600))
    assert n_feas > 60  # the sample exercises feasible cases, not only infeasible ones


@pytest.mark.slow
def test_random_robots_10000():
    rng = np.random.default_rng(7)
    n_feas = 0
    for case in random_cases(rng, 10_000):
        if check_case(*case):
            n_feas += 1
            if n_feas % 10 == 0 and case[0].n >= 4:  # LFOPC on every tenth feasible case
                check_lfopc(*case)
    assert n_feas > 1000


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_property_hypothesis(seed):
    for case in random_cases(np.random.default_rng(seed), 2):
        check_case(*case)


def test_algorithm_6_1_matches_basic_solutions_n4():
    """Closed-form interval (Algorithm 6.1) = enumeration of basic solutions, many poses."""
    rng = np.random.default_rng(1)
    robot = thesis_robot(4)
    U = rng.uniform(-1, 1, (4000, 2))
    phi = rng.uniform(-0.3, 0.3, 4000)
    S = robot.structure_matrix(U, phi)
    w = loads()["L3"]
    tp, z, lo, hi = interval_4(S, w, T_MIN, T_MAX)
    T, valid = vertices(S, np.broadcast_to(w, (4000, 3)), T_MIN, T_MAX)
    feas = lo <= hi
    assert feas.sum() > 300
    np.testing.assert_array_equal(feas, valid.any(1))
    for m in ("l1", "l1-max", "l2-max"):
        f1, t1 = distribute(S, w, T_MIN, T_MAX, m)
        sc = t1.sum(1) if m.startswith("l1") else (t1**2).sum(1)
        Tv = np.where(valid[..., None], T, np.nan)
        sv = Tv.sum(2) if m.startswith("l1") else (Tv**2).sum(2)
        ref = np.nanmin(sv[feas], axis=1) if m == "l1" else np.nanmax(sv[feas], axis=1)
        np.testing.assert_allclose(sc[feas], ref, rtol=1e-10)


def test_min_norm_and_l2_n4():
    """l2 (6.17) is the minimum-norm solution (6.14) where that is feasible (Appendix E)."""
    # the Fig. 6.3 robot (c = [+-1, +-0.15]); its minimum-norm workspace is not empty
    robot = CableRobot([[1, 0.15], [-1, 0.15], [-1, -0.15], [1, -0.15]], thesis_robot(4).platform_points)
    w = loads()["L1"]
    ws = robot.workspace(0.0, w, tensions="min-norm")
    X, Y = np.meshgrid(*ws.grid)
    U = np.vstack([np.column_stack([X[ws.mask], Y[ws.mask]])[:20], [[0.0, 0.0], [0.3, -0.1]]])
    S = robot.structure_matrix(U, 0.0)
    tmn = min_norm(S, w)
    f, t2 = distribute(S, w, T_MIN, T_MAX, "l2")
    inside = np.all((tmn >= T_MIN) & (tmn <= T_MAX), axis=1)
    assert inside.any()
    np.testing.assert_allclose(t2[inside], tmn[inside], rtol=1e-12)
    # the l2 tensions are the least-norm feasible ones: no basic solution is smaller
    T, valid = vertices(S, np.broadcast_to(w, (len(U), 3)), T_MIN, T_MAX)
    for i in np.flatnonzero(f):
        assert (t2[i] ** 2).sum() <= np.min((T[i][valid[i]] ** 2).sum(1)) + 1e-9


def test_three_cables_unique_solution_and_det():
    robot = thesis_robot(3)
    w = loads()["L1"]
    ws = robot.workspace(0.05, w)
    iy, ix = np.argwhere(ws.mask)[len(np.argwhere(ws.mask)) // 2]
    u = np.array([ws.grid[0][ix], ws.grid[1][iy]])
    kin = robot.kinematics(u, 0.05)
    S = kin["S"][0]
    t = robot.tensions(u, 0.05, w, "l1")
    np.testing.assert_allclose(t, np.linalg.solve(S, -w), rtol=1e-12)
    np.testing.assert_allclose(kin["det"][0], np.linalg.det(S), rtol=1e-12)
    # all constrained methods give the unique solution
    for m in ("l2", "l1-max", "l2-max", "min-norm"):
        np.testing.assert_allclose(robot.tensions(u, 0.05, w, m), t, rtol=1e-12)


@pytest.mark.parametrize("backend,method", [("linprog", "l1"), ("highs", "l1"), ("clarabel", "l1"),
                                            ("linprog", "l1-max"), ("clarabel", "l2"), ("osqp", "l2")])
def test_backends_match_closed_form(backend, method):
    """Per-pose LP/QP backends (cvxpy, SciPy) agree with the exact vectorized tensions."""
    rng = np.random.default_rng(3)
    for n in (4, 5, 6):
        robot = CableRobot(frame_point(np.sort(rng.uniform(0, 2 * np.pi, n))),
                           rng.uniform(-0.1, 0.1, (n, 2)), l_min=0.0)
        U = rng.uniform(-0.5, 0.5, (12, 2))
        w = np.array([3.0, -10.0, 0.5])
        f_ref, T_ref = robot.tensions_batch(U, 0.1, w, "l1")  # exact feasibility
        f, T = robot.tensions_batch(U, 0.1, w, method, backend=backend)
        assert np.array_equal(f, f_ref)
        if method == "l2" and n > 4:
            Tq = robot.tensions_batch(U, 0.1, w, "l2", backend="clarabel")[1]
            np.testing.assert_allclose(T[f], Tq[f], atol=1e-4)
            continue
        if method != "l2":
            ref = robot.tensions_batch(U, 0.1, w, method)[1]
            np.testing.assert_allclose(T[f].sum(1), ref[f].sum(1), rtol=1e-7)
        else:
            ref = robot.tensions_batch(U, 0.1, w, "l2")[1]
            np.testing.assert_allclose(T[f], ref[f], atol=1e-4)


def test_lfopc_l2_matches_qp():
    """l2 tensions (6.17) from the in-house LFOPC (as in the thesis) vs Clarabel and OSQP."""
    pytest.importorskip("solvers.lfopc")
    robot = design_robot([0.7572, 2.922, 3.097, 5.449])
    w = loads()["L3"]
    rng = np.random.default_rng(11)
    U = rng.uniform(-0.6, 0.6, (40, 2))
    f, T = robot.tensions_batch(U, 0.1, w, "l2")
    idx = np.flatnonzero(f)[:10]
    assert idx.size >= 5
    for i in idx:
        t_l = robot.tensions(U[i], 0.1, w, "l2", backend="lfopc")
        assert t_l is not None
        np.testing.assert_allclose(t_l, T[i], atol=1e-4)  # the exact (clamped) l2 tensions
        for b in ("clarabel", "osqp"):
            np.testing.assert_allclose(t_l, robot.tensions(U[i], 0.1, w, "l2", backend=b), atol=1e-4)
    # random robots with two and three redundant cables (no closed form: QP backends only)
    checked = 0
    for case in random_cases(np.random.default_rng(5), 300):
        robot, u, phi, w = case
        if robot.n < 5 or robot.tensions(u, phi, w, "l1") is None:
            continue
        check_lfopc(robot, u, phi, w)
        checked += 1
        if checked == 6:
            break
    assert checked == 6


# ----------------------------------------------------------------- validation
def test_robot_validation_errors():
    c, a = np.zeros((4, 2)) + [[1, 0], [0, 1], [-1, 0], [0, -1]], np.zeros((4, 2))
    with pytest.raises(ValueError, match="n >= 3"):
        CableRobot(c[:2], a[:2])
    with pytest.raises(ValueError, match="same shape"):
        CableRobot(c, a[:3])
    with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
        CableRobot(np.zeros((4, 3)), np.zeros((4, 3)))
    with pytest.raises(ValueError, match="t_min < t_max"):
        CableRobot(c, a, t_min=10, t_max=5)
    with pytest.raises(ValueError, match="NaN"):
        CableRobot(c * np.nan, a)
    with pytest.raises(ValueError, match="n = 3"):
        CableRobot(c, a, det_min=1e-3)
    with pytest.raises(ValueError, match=">= 0"):
        CableRobot(c, a, l_min=-1)
    r = CableRobot(c, a)
    with pytest.raises(ValueError, match="unknown tension method"):
        r.tensions([0, 0], 0.0, [0, -10, 0], "l3")
    with pytest.raises(ValueError, match="unknown tension backend"):
        r.tensions([0, 0], 0.0, [0, -10, 0], "l1", backend="cplex")
    with pytest.raises(ValueError, match="wrench"):
        r.tensions([0, 0], 0.0, [0, -10], "l1")
    with pytest.raises(ValueError, match="not a convex problem"):
        r.tensions([0, 0], 0.0, [0, -10, 0], "l2-max", backend="clarabel")
    with pytest.raises(ValueError, match="shape"):
        r.tensions([[0, 0]], 0.0, [0, -10, 0])


def test_frame_point_mapping():
    """ERRATA: c = (cos b, sin b) / max(|cos b|, |sin b|) on the 2 x 2 frame."""
    np.testing.assert_allclose(frame_point(0.0), [1, 0])
    np.testing.assert_allclose(frame_point(np.pi / 4), [1, 1])
    np.testing.assert_allclose(frame_point(np.pi), [-1, 0], atol=1e-15)
    b = np.linspace(-3, 9, 200)
    c = frame_point(b)
    np.testing.assert_allclose(np.max(np.abs(c), axis=1), 1.0)
    np.testing.assert_allclose(np.arctan2(c[:, 1], c[:, 0]), np.angle(np.exp(1j * b)), atol=1e-12)


def test_structure_matrix_is_jacobian_transpose_and_derivative():
    """S = J^T (6.11) and J is the derivative of the lengths: l_dot = -(-J) ... (6.7)."""
    robot = thesis_robot(4)
    u, phi, h = np.array([0.2, -0.1]), 0.07, 1e-6
    J = robot.jacobian(u, phi)[0]
    np.testing.assert_array_equal(J, robot.structure_matrix(u, phi)[0].T)
    # (6.7): v_dot = -J [u_dot, w_dot]
    for j, d in enumerate(np.eye(3)):
        lp = robot.lengths(u + h * d[:2], phi + h * d[2])[0]
        lm = robot.lengths(u - h * d[:2], phi - h * d[2])[0]
        np.testing.assert_allclose((lp - lm) / (2 * h), -J[:, j], atol=1e-8)


@pytest.mark.parametrize("tol", [-1.0, float("nan"), float("inf")])
def test_a_negative_or_non_finite_tolerance_is_refused(tol):
    robot = thesis_robot(4)
    with pytest.raises(ValueError, match="tol must be a finite number >= 0"):
        robot.tensions([0.2, -0.1], 0.0, loads()["L1"], "l1", tol=tol)


def test_nan_poses_are_refused_with_the_row_named():
    robot = thesis_robot(4)
    with pytest.raises(ValueError, match=r"NaN or inf at row\(s\) \[0\]"):
        robot.tensions([np.nan, -0.1], 0.0, loads()["L1"])
    with pytest.raises(ValueError, match=r"row\(s\) \[1\].*phi = nan"):
        robot.tensions_batch([[0.2, -0.1], [0.1, 0.0]], [0.0, np.nan], loads()["L1"])
