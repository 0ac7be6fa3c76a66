"""Gough-Stewart platform: kinematics, Jacobian vs finite differences, workspace vs exact shells."""

from __future__ import annotations

import numpy as np
import pytest

from manipulators import GoughStewart
from manipulators.spatial import rotation_matrix

ROT = np.array([0.1, -0.05, 0.2])
BOX = [[-1.2, -1.2, -1.7], [1.2, 1.2, 1.7]]  # holds both mirror-image workspace pieces


@pytest.fixture(scope="module")
def hexapod() -> GoughStewart:
    """Base radius 1 m, platform radius 0.5 m, joints paired 20 degrees apart, legs 1.0-1.6 m."""
    ab = (np.deg2rad([0, 120, 240])[:, None] + np.deg2rad([-10, 10])[None]).ravel()
    ap = np.roll((np.deg2rad([60, 180, 300])[:, None] + np.deg2rad([-10, 10])[None]).ravel(), 1)
    a = np.column_stack([np.cos(ab), np.sin(ab), np.zeros(6)])
    b = np.column_stack([0.5 * np.cos(ap), 0.5 * np.sin(ap), np.zeros(6)])
    return GoughStewart(a, b, 1.0, 1.6)


def test_inverse_kinematics(hexapod):
    p = np.array([0.05, -0.1, 1.2])
    L = hexapod.inverse_kinematics(p, ROT)
    R = rotation_matrix(ROT)
    np.testing.assert_allclose(L, [np.linalg.norm(p + R @ b - a) for a, b in
                                   zip(hexapod.base_points, hexapod.platform_points)], rtol=1e-14)


def test_jacobian_against_finite_differences(hexapod):
    p, h = np.array([0.05, -0.1, 1.2]), 1e-6
    J = hexapod.jacobian(p, ROT)
    R = rotation_matrix(ROT)
    for j in range(6):
        v = np.zeros(6)
        v[j] = h
        # small rotation about a world axis: R(t) = exp([omega] t) R
        Rp = rotation_matrix(v[3:]) @ R
        Rm = rotation_matrix(-v[3:]) @ R
        fd = (hexapod.inverse_kinematics(p + v[:3], Rp) - hexapod.inverse_kinematics(p - v[:3], Rm)) / (2 * h)
        np.testing.assert_allclose(J[:, j], fd, atol=1e-8)


def test_inverse_condition_number(hexapod):
    P = np.array([[0, 0, 1.2], [0.2, 0.1, 1.3], [0, 0, 1.0]])
    ic = hexapod.inverse_condition(P, ROT)
    assert np.all((ic > 0) & (ic <= 1))
    J = hexapod.jacobian(P[1], ROT) @ np.diag([1, 1, 1] + [1 / hexapod.char_length] * 3)
    assert ic[1] == pytest.approx(1 / np.linalg.cond(J), rel=1e-10)
    assert hexapod.char_length == pytest.approx(0.5)


def test_grid_volume_within_one_percent_of_exact_shells(hexapod):
    exact = hexapod.exact_volume(ROT, [0, 0, 1.2], n_theta=100, n_phi=200)
    finer = hexapod.exact_volume(ROT, [0, 0, 1.2], n_theta=60, n_phi=120)
    assert abs(exact - finer) < 1e-3 * exact  # the angular quadrature has converged
    ws = hexapod.workspace(ROT, BOX, resolution=40)  # the documented resolution
    assert ws.volume == pytest.approx(exact, rel=0.01)


def test_ray_boundary_points_on_exact_shell_boundary(hexapod):
    rng = np.random.default_rng(2)
    D = rng.normal(size=(200, 3))
    centre = np.array([0.0, 0.0, 1.2])
    B = hexapod.boundary_points(ROT, centre, D, reach=4.0, tol=1e-10)
    L = np.linalg.norm(hexapod.legs(B, ROT), axis=2)
    # on the boundary: every leg within its limits, one at a limit, to 1e-6
    assert np.all((L >= 1.0 - 1e-6) & (L <= 1.6 + 1e-6))
    gap = np.minimum(np.abs(L - 1.0), np.abs(L - 1.6)).min(axis=1)
    assert gap.max() <= 1e-6
    # and it is a crossing of the exact radial pieces
    br, feas = hexapod.ray_segments(ROT, centre, D)
    s = np.linalg.norm(B - centre, axis=1)
    change = feas[:, :-1] != feas[:, 1:]
    ends = np.where(change, br[:, 1:-1], np.inf)
    assert np.abs(ends - s[:, None]).min(axis=1).max() <= 1e-6


def test_bad_input():
    with pytest.raises(ValueError, match="6 base and 6 platform"):
        GoughStewart(np.zeros((5, 3)), np.zeros((5, 3)), 1, 2)
    with pytest.raises(ValueError, match="l_min < l_max"):
        GoughStewart(np.eye(6, 3), np.eye(6, 3), 2, 1)


def test_nan_positions_are_refused_with_the_row_named(hexapod):
    with pytest.raises(ValueError, match=r"NaN or inf at row\(s\) \[0\]"):
        hexapod.inverse_condition([[np.nan, 0.0, 1.2]], ROT)
    with pytest.raises(ValueError, match=r"row\(s\) \[1\]"):
        hexapod.feasible([[0.0, 0.0, 1.2], [0.0, 0.0, np.inf]], ROT)
