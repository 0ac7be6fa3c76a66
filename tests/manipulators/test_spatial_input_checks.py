"""Bad arguments of the spatial robots get errors that name them, and the robots are values."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from manipulators import SpatialCableRobot
from manipulators.spatial import GoughStewart, ray_reach
from manipulators.spatial import _cable as cable


def _hexapod() -> GoughStewart:
    ang = np.deg2rad(np.array([0, 120, 240]))
    base = np.array([[np.cos(a + s), np.sin(a + s), 0.0] for a in ang for s in (-0.2, 0.2)])
    plat = 0.5 * np.array([[np.cos(a + s), np.sin(a + s), 0.0] for a in ang + np.pi / 3 for s in (-0.3, 0.3)])
    return GoughStewart(base, plat, 1.0, 1.6)


def _box_corners() -> np.ndarray:
    """The eight corners of a 2 x 2 x 3 m frame, (8, 3), a fresh array each call."""
    return np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (0, 3)], float)


def _cable_robot() -> SpatialCableRobot:
    corners = _box_corners()
    return SpatialCableRobot(corners, 0.1 * np.sign(corners - [0, 0, 1.5]), t_min=1.0, t_max=200.0)


BALL = lambda P: np.linalg.norm(P, axis=1) <= 1.0


@pytest.mark.parametrize("tol", [0.0, -1e-9, float("nan"), float("inf"), None, "1e-9"])
def test_ray_reach_needs_a_positive_tolerance(tol):
    """tol <= 0 used to hang: the bisection's interval stops shrinking at one ulp."""
    with pytest.raises(ValueError, match="tol must be a finite length > 0"):
        ray_reach(BALL, [0.0, 0.0, 0.0], [[1.0, 0.0, 0.0]], 2.0, tol=tol)
    with pytest.raises(ValueError, match="reach must be a positive length"):
        ray_reach(BALL, [0.0, 0.0, 0.0], [[1.0, 0.0, 0.0]], "2")
    assert ray_reach(BALL, [0.0, 0.0, 0.0], [[1.0, 0.0, 0.0]], 2.0, tol=1e-6)[0] == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize("res", [0, -3, 2.5, True, "4", None])
def test_grid_resolution_must_be_a_positive_integer(res):
    """2.5 used to become 2 silently."""
    with pytest.raises(ValueError, match=r"resolution must be an integer >= 1"):
        cable.grid_points([[0, 0, 0], [1, 1, 1]], res)
    _, pts = cable.grid_points([[0, 0, 0], [1, 1, 1]], np.int64(3))
    assert pts.shape == (27, 3)


def test_a_grid_too_large_for_memory_is_refused_before_it_is_allocated():
    with pytest.raises(ValueError, match=r"resolution 1000 means 1,000,000,000 grid points \(24.0 GB.*resolution 271"):
        cable.grid_points([[0, 0, 0], [1, 1, 1]], 1000)
    with pytest.raises(ValueError, match="resolution 272 means"):
        _hexapod().workspace(np.eye(3), [[-1, -1, 0], [1, 1, 2]], resolution=272)


def test_workspaces_do_not_depend_on_the_feasibility_chunk(monkeypatch):
    """Feasibility is tested in chunks to bound memory; the chunks change nothing else."""
    from manipulators.synthesis import spatial_suite as sp

    robot = sp.cable_design(sp.cable_problem(9).x0)
    w, rots, box = np.array(sp.CABLE["loads"][0]), sp.CABLE["orientations"], [[-1, -1, 0.5], [1, 1, 2.5]]
    hexapod, hbox = _hexapod(), [[-0.6, -0.6, 0.8], [0.6, 0.6, 1.6]]

    def masks():
        return (hexapod.workspace(np.eye(3), hbox, 9).mask, robot.workspace(np.eye(3), w, box, 7).mask,
                robot.dextrous_workspace(rots, w, box, 7).mask)

    whole = masks()
    monkeypatch.setattr(cable, "FEASIBILITY_CHUNK", 10)
    parts = masks()
    assert all(m.any() and not m.all() for m in whole)
    for a, b in zip(whole, parts):
        np.testing.assert_array_equal(a, b)


def test_dextrous_workspace_refuses_one_bare_orientation():
    """One rotation matrix used to be read as three angle triples (its rows), silently."""
    robot, w, box = _cable_robot(), np.zeros(6), [[-0.5, -0.5, 1.0], [0.5, 0.5, 2.0]]
    with pytest.raises(ValueError, match=r"one 3 x 3 rotation matrix; pass \[R\]"):
        robot.dextrous_workspace(np.eye(3), w, box, 3)
    with pytest.raises(ValueError, match=r"looks like one angle triple .*pass \[\(alpha, beta, gamma\)\]"):
        robot.dextrous_workspace((0.1, 0.0, 0.0), w, box, 3)
    with pytest.raises(ValueError, match="at least one orientation"):
        robot.dextrous_workspace([], w, box, 3)
    one = robot.dextrous_workspace([np.eye(3)], w, box, 3).mask
    np.testing.assert_array_equal(one, robot.workspace(np.eye(3), w, box, 3).mask)


def test_the_robots_are_immutable_values():
    """A limit changed after construction used to skip its check (t_min = -5 was accepted)."""
    robot, hexapod = _cable_robot(), _hexapod()
    with pytest.raises(dataclasses.FrozenInstanceError):
        robot.t_min = -5.0  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        hexapod.l_max = 0.5  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        robot.frame_points[0, 0] = 9.0
    with pytest.raises(ValueError, match="need finite 0 <= t_min < t_max"):
        dataclasses.replace(robot, t_min=-5.0)
    assert dataclasses.replace(robot, t_max=150.0).t_max == 150.0


def test_the_callers_arrays_are_copied_not_frozen():
    corners = _box_corners()
    robot = SpatialCableRobot(corners, 0.1 * np.sign(corners - [0, 0, 1.5]))
    corners[0, 0] = 5.0  # still the caller's to change, and the robot does not see it
    assert robot.frame_points[0, 0] == -1.0


@pytest.mark.parametrize("kw", [{"t_min": "1"}, {"t_max": None}, {"t_min": True}])
def test_tension_limits_must_be_numbers(kw):
    corners = _box_corners()
    with pytest.raises(ValueError, match="need finite 0 <= t_min < t_max"):
        SpatialCableRobot(corners, 0.1 * corners, **kw)


def test_hexapod_limits_must_be_numbers():
    h = _hexapod()
    with pytest.raises(ValueError, match="need finite 0 <= l_min < l_max"):
        GoughStewart(h.base_points, h.platform_points, "1", 1.6)
    with pytest.raises(ValueError, match="char_length must be a positive length"):
        GoughStewart(h.base_points, h.platform_points, 1.0, 1.6, char_length=-1.0)
