"""Spatial cable robot: tensions against an independent LP, equilibrium, workspaces."""

from __future__ import annotations

import itertools
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog

from manipulators import SpatialCableRobot
from manipulators.spatial import distribute6

CORNERS = np.array(list(itertools.product((-1.0, 1.0), repeat=3)))
W = np.array([0.0, 0.0, -10.0, 0.5, -0.3, 0.2])


def random_robot(rng: np.random.Generator, m: int) -> SpatialCableRobot:
    """Frame points near the corners of a 4 m cube, platform points near a 0.4 m cube (generic)."""
    idx = rng.permutation(np.arange(m) % 8)
    frame = 2.0 * CORNERS[idx] + rng.normal(0, 0.15, (m, 3))
    plat = 0.2 * CORNERS[rng.permutation(np.arange(m) % 8)] + rng.normal(0, 0.03, (m, 3))
    return SpatialCableRobot(frame, plat, t_min=1.0, t_max=rng.uniform(80, 200))


def lp_l1(S, w, t_min, t_max):
    """Independent reference: SciPy HiGHS LP min sum t s.t. S t = -w, bounds."""
    res = linprog(np.ones(S.shape[1]), A_eq=S, b_eq=-w, bounds=(t_min, t_max), method="highs")
    return (res.status == 0), (res.fun if res.status == 0 else None)


def check_random_poses(n_poses: int, seed: int) -> int:
    """Random robots (m = 7..12), 50 random poses and loads each: the vectorized l1 path
    (all 50 poses in one call) against one independent LP per pose."""
    rng = np.random.default_rng(seed)
    n_feasible = 0
    for _ in range(n_poses // 50):
        m = int(rng.integers(7, 13))
        robot = random_robot(rng, m)
        P = rng.uniform(-0.8, 0.8, (50, 3))
        A = rng.uniform(-0.3, 0.3, (50, 3))
        Wk = W * rng.uniform(0.2, 3.0, (50, 1))
        S = np.stack([robot.structure_matrix(p, a) for p, a in zip(P, A)])
        feas, T = distribute6(S, Wk, robot.t_min, robot.t_max)
        for Si, wi, fi, ti in zip(S, Wk, feas, T):
            ok_lp, f_lp = lp_l1(Si, wi, robot.t_min, robot.t_max)
            assert fi == ok_lp, m
            if fi:
                n_feasible += 1
                assert np.abs(Si @ ti + wi).max() <= 1e-9
                assert np.all(ti >= robot.t_min) and np.all(ti <= robot.t_max)
                assert abs(ti.sum() - f_lp) <= 1e-8 * max(1.0, abs(f_lp))
    return n_feasible


def test_public_tensions_is_the_vector_path():
    rng = np.random.default_rng(4)
    robot = random_robot(rng, 9)
    for _ in range(10):
        p, a = rng.uniform(-0.5, 0.5, 3), rng.uniform(-0.2, 0.2, 3)
        t = robot.tensions(p, a, W)
        feas, T = distribute6(robot.structure_matrix(p, a)[None], W, robot.t_min, robot.t_max)
        assert (t is not None) == feas[0]
        if t is not None:
            np.testing.assert_array_equal(t, T[0])


def test_l1_tensions_match_lp_small_sample():
    assert check_random_poses(300, seed=3) > 30  # a meaningful share of feasible poses


@pytest.mark.slow
def test_l1_tensions_match_lp_10000_poses():
    assert check_random_poses(10_000, seed=14) > 1000


def test_lp_and_qp_backends_agree_with_vector_path():
    rng = np.random.default_rng(5)
    robot = random_robot(rng, 8)
    for _ in range(20):
        p = rng.uniform(-0.5, 0.5, 3)
        t = robot.tensions(p, np.zeros(3), W)
        t_lp = robot.tensions(p, np.zeros(3), W, backend="highs")
        assert (t is None) == (t_lp is None)
        if t is not None:
            assert abs(t.sum() - t_lp.sum()) <= 1e-6 * t.sum()
            t2 = robot.tensions(p, np.zeros(3), W, method="l2")
            S = robot.structure_matrix(p, np.zeros(3))
            assert np.abs(S @ t2 + W).max() <= 1e-6
            assert t2 @ t2 <= t @ t + 1e-6  # the l2 minimizer has the smallest 2-norm


def test_grid_mask_equals_per_point_lp():
    rng = np.random.default_rng(7)
    robot = random_robot(rng, 8)
    ws = robot.workspace([0.05, -0.05, 0.1], W, [[-1.5] * 3, [1.5] * 3], resolution=8)
    lp_mask = np.array([lp_l1(robot.structure_matrix(p, [0.05, -0.05, 0.1]), W, robot.t_min, robot.t_max)[0]
                        for p in ws.points])
    assert 0 < ws.mask.sum() < ws.mask.size
    np.testing.assert_array_equal(ws.mask.ravel(), lp_mask)
    assert ws.volume == pytest.approx(ws.mask.mean() * 27.0)


def test_ray_boundary_points_lie_on_feasibility_boundary():
    rng = np.random.default_rng(7)
    robot = random_robot(rng, 8)
    ws = robot.workspace(np.zeros(3), W, [[-1.5] * 3, [1.5] * 3], resolution=8)
    centre = ws.feasible_points.mean(axis=0)
    assert robot.feasible(centre[None], np.zeros(3), W)[0]
    D = rng.normal(size=(20, 3))
    D /= np.linalg.norm(D, axis=1, keepdims=True)
    B = robot.boundary_points(np.zeros(3), W, centre, D, reach=3.0)
    s = np.linalg.norm(B - centre, axis=1)
    inner = [lp_l1(robot.structure_matrix(b - 1e-6 * d, np.zeros(3)), W, robot.t_min, robot.t_max)[0]
             for b, d in zip(B, D)]
    outer = [lp_l1(robot.structure_matrix(b + 1e-6 * d, np.zeros(3)), W, robot.t_min, robot.t_max)[0]
             for b, d, r in zip(B, D, s) if r < 3.0]
    assert all(inner) and not any(outer) and len(outer) > 0


def test_dextrous_is_intersection():
    rng = np.random.default_rng(7)
    robot = random_robot(rng, 8)
    box = [[-1.2] * 3, [1.2] * 3]
    rots = [np.zeros(3), [0.1, 0, 0], [0, -0.1, 0.05]]
    dex = robot.dextrous_workspace(rots, W, box, resolution=6)
    masks = [robot.workspace(R, W, box, resolution=6).mask for R in rots]
    np.testing.assert_array_equal(dex.mask, np.logical_and.reduce(masks))


def test_rotation_convention_and_bad_input():
    from manipulators.spatial import rotation_matrix

    Rz = rotation_matrix([0, 0, np.pi / 2])
    np.testing.assert_allclose(Rz @ [1, 0, 0], [0, 1, 0], atol=1e-15)
    R = rotation_matrix([0.3, 0, 0]) @ rotation_matrix([0, 0, 0])
    np.testing.assert_allclose(rotation_matrix(R), R)
    with pytest.raises(ValueError, match="m >= 7"):
        SpatialCableRobot(np.zeros((6, 3)), np.zeros((6, 3)))
    robot = random_robot(np.random.default_rng(0), 7)
    with pytest.raises(ValueError, match="unknown tension method"):
        robot.tensions(np.zeros(3), np.zeros(3), W, method="l3")
    with pytest.raises(ValueError, match="wrench"):
        robot.tensions(np.zeros(3), np.zeros(3), [1.0, np.nan, 0, 0, 0, 0])


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**31), m=st.integers(7, 9), scale=st.floats(0.1, 5.0))
def test_equilibrium_property(seed, m, scale):
    rng = np.random.default_rng(seed)
    robot = random_robot(rng, m)
    P = rng.uniform(-0.8, 0.8, (20, 3))
    ang = rng.uniform(-0.3, 0.3, 3)
    S = robot.structure_matrices(P, ang)
    feas, T = distribute6(S, W * scale, robot.t_min, robot.t_max)
    for Si, ti in zip(S[feas], T[feas]):
        assert np.abs(Si @ ti + W * scale).max() <= 1e-9
        assert np.all((ti >= robot.t_min) & (ti <= robot.t_max))


def test_min_norm_tensions():
    """-S^+ w (6.14), returned only when it meets the bounds."""
    rng = np.random.default_rng(11)
    robot = random_robot(rng, 8)
    for _ in range(20):
        p = rng.uniform(-0.8, 0.8, 3)
        S = robot.structure_matrix(p, np.zeros(3))
        w = -S @ rng.uniform(20, 60, 8)
        t_ref = -np.linalg.pinv(S) @ w
        t = robot.tensions(p, np.zeros(3), w, method="min-norm")
        inside = bool(np.all((t_ref >= robot.t_min - 1e-10) & (t_ref <= robot.t_max + 1e-10)))
        assert (t is not None) == inside
    # a structure whose row space holds the all-ones vector: S^T 1 = 1, so t^mn = 30 * 1
    S = np.hstack([np.eye(6), np.zeros((6, 2))])
    S[0, 6] = S[1, 7] = 1.0  # cables 7 and 8 repeat the directions of cables 1 and 2
    w = -S @ np.full(8, 30.0)
    feas, T = distribute6(S[None], w, 1.0, 100.0, method="min-norm")
    assert feas[0]
    np.testing.assert_allclose(T[0], -np.linalg.pinv(S) @ w, atol=1e-12)
    np.testing.assert_allclose(T[0], 30.0, atol=1e-12)


@pytest.mark.parametrize("r", [1, 2, 3])
def test_singular_bound_subsets_give_finite_values_without_warnings(r):
    """A singular r x r bound subset (a degenerate pose) is masked by its det: the solve must give
    finite values and no RuntimeWarning, and the nonsingular systems their exact solution."""
    from manipulators.spatial._distribution6 import SINGULAR_TOL, _solve_small

    rng = np.random.default_rng(r)
    A = rng.normal(size=(3, r, r))
    A[1] = 0.0  # singular
    b = rng.normal(size=(3, 4, r))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        x, det = _solve_small(A, b)
    assert np.all(np.isfinite(x))
    assert abs(det[1]) <= SINGULAR_TOL < np.abs(det[[0, 2]]).min()
    for i in (0, 2):
        np.testing.assert_allclose(np.einsum("ij,pj->pi", A[i], x[i]), b[i], atol=1e-10)


def test_nan_positions_are_refused_with_the_row_named():
    robot = random_robot(np.random.default_rng(0), 7)
    with pytest.raises(ValueError, match=r"NaN or inf at row\(s\) \[0\]"):
        robot.tensions([np.nan, 0.0, 1.5], np.zeros(3), W)
    with pytest.raises(ValueError, match=r"row\(s\) \[1\]"):
        robot.feasible([[0.0, 0.0, 0.0], [0.0, np.inf, 0.0]], np.zeros(3), W)
    with pytest.raises(ValueError, match=r"\(3,\) or \(k, 3\)"):
        robot.structure_matrices(np.zeros((2, 2)), np.zeros(3))


@pytest.mark.parametrize("backend", ["highs", "linprog", "clarabel"])
def test_a_singular_pose_is_infeasible_for_every_backend(backend):
    """A symmetric 8-cable robot whose structure matrix loses rank at a level pose: the
    enumeration returns None (documented), and so does every LP backend, so that feasibility
    does not depend on the backend chosen."""
    frame = [(x, y, z) for x in (-2, 2) for y in (-2, 2) for z in (0, 3)]
    plat = [(x, y, -z) for x in (-0.2, 0.2) for y in (-0.2, 0.2) for z in (-0.2, 0.2)]
    robot = SpatialCableRobot(frame, plat, t_min=10, t_max=1000)
    pose, w = [0.1, 0.05, 1.4], [0, 0, -100.0, 0, 0, 0]
    assert np.linalg.svd(robot.structure_matrix(pose, np.zeros(3)), compute_uv=False)[-1] < 1e-12
    assert robot.tensions(pose, np.zeros(3), w) is None
    assert robot.tensions(pose, np.zeros(3), w, backend=backend) is None
    # a generic pose of a generic robot: the backends agree on the l1 tensions
    gen = random_robot(np.random.default_rng(3), 8)
    t_vec, t_lp = gen.tensions([0.1, 0.0, 0.2], np.zeros(3), W), gen.tensions([0.1, 0.0, 0.2], np.zeros(3), W,
                                                                              backend=backend)
    assert (t_vec is None) == (t_lp is None)
    if t_vec is not None:
        assert abs(t_vec.sum() - t_lp.sum()) <= 1e-6 * t_vec.sum()


def test_the_highs_backend_prints_no_banner():
    """HiGHS prints a banner when a process makes its first solver object; a user's tension
    query must not put it in their output (solvers.convex._swallow_highs_banner)."""
    import subprocess
    import sys

    code = ("import numpy as np; from tests.manipulators.test_spatial_cable import random_robot, W; "
            "r = random_robot(np.random.default_rng(3), 8); "
            "print('T', r.tensions([0.1, 0.0, 0.2], np.zeros(3), W, backend='highs') is not None)")
    import pathlib

    root = pathlib.Path(__file__).resolve().parents[2]
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=root)
    assert "HiGHS" not in out.stdout and out.stdout.strip() in ("T True", "T False")
