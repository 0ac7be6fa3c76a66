"""One number test for every manipulator: `manipulators._checks.is_number` / `is_integer`.

A bool is neither (Python counts True as the int 1; a True tolerance or chord is a mistake),
nor is a string; NumPy's integer and floating scalars are numbers.  The robots refuse a bool
or a string where a number belongs, with the messages they always gave.
"""

from __future__ import annotations

import fractions
import re

import numpy as np
import pytest

from manipulators import RPR3, CableRobot, SpatialCableRobot, _checks
from manipulators._checks import is_integer, is_number
from manipulators.cable import thesis_robot
from manipulators.spatial import ray_reach

#: value -> (is_number, is_integer)
TABLE = [
    (0, True, True),
    (-3, True, True),
    (2**80, True, True),
    (1.5, True, False),
    (2.0, True, False),  # an integral float is a number, not an integer
    (float("nan"), True, False),  # finiteness is the callers' check
    (float("inf"), True, False),
    (np.int8(3), True, True),
    (np.int64(-7), True, True),
    (np.uint16(5), True, True),
    (np.float16(0.5), True, False),
    (np.float32(0.5), True, False),
    (np.float64(0.5), True, False),
    (np.longdouble(0.5), True, False),
    (True, False, False),
    (False, False, False),
    (np.True_, False, False),
    (np.False_, False, False),
    ("1", False, False),
    ("1.5", False, False),
    (b"1", False, False),
    (None, False, False),
    (1 + 0j, False, False),
    (np.complex128(1.0), False, False),
    (np.array(1.0), False, False),  # a 0-d array is not a scalar
    (np.array([1.0]), False, False),
    ([1.0], False, False),
    (fractions.Fraction(1, 2), False, False),
]


@pytest.mark.parametrize("value,number,integer", TABLE, ids=[repr(v) for v, _, _ in TABLE])
def test_truth_table(value, number, integer):
    assert is_number(value) is number
    assert is_integer(value) is integer


def test_both_are_exported():
    assert {"is_number", "is_integer"} <= set(_checks.__all__)


def test_the_private_copies_are_gone():
    """rpr3 and the spatial cable robot had their own ``_is_number``; now there is one test."""
    from manipulators import rpr3
    from manipulators.spatial import _cable, _gough_stewart

    for mod in (rpr3, _cable, _gough_stewart):
        assert not hasattr(mod, "_is_number"), mod.__name__
        assert mod.is_number is is_number


# ---------------------------------------------------------------- 3-RPR: same refusals as before
@pytest.mark.parametrize("bad", [True, np.True_, "1.0", None])
@pytest.mark.parametrize("name", ["xC", "yC", "xD", "xE", "r"])
def test_rpr3_design_refuses_a_bool_or_a_string(name, bad):
    d = {"xC": -1.0, "yC": 0.0, "xD": 1.0, "xE": 2.0, "r": 1.0, name: bad}
    with pytest.raises(ValueError, match=rf"^RPR3: {name} must be a number, got {re.escape(repr(bad))}$"):
        RPR3(**d)


def test_rpr3_design_takes_numpy_numbers():
    m = RPR3(np.float32(-1.0), np.int64(0), 1, np.float64(2.0), 1)
    assert m.r == 1


@pytest.mark.parametrize("tol", [True, "0.1", None])
def test_rpr3_enclosing_orientations_refuses_a_bool_or_a_string_tol(tol):
    with pytest.raises(ValueError, match=r"^enclosing_orientations: tol must be a finite leg-length slack, got "):
        RPR3.named("M1").enclosing_orientations([[1.0, 1.5]], tol=tol)


@pytest.mark.parametrize("kw", [{"n_grid": True}, {"n_grid": np.True_}, {"n_refine": False}, {"n_grid": "36"},
                                {"n_grid": 36.0}])
def test_rpr3_maximal_constraints_refuses_a_bool_or_a_string(kw):
    name, v = next(iter(kw.items()))
    least = 1 if name == "n_grid" else 0
    with pytest.raises(ValueError, match=rf"^maximal_constraints: {name} must be an integer >= {least}, got "):
        RPR3.named("M1").maximal_constraints([[1.0, 1.5]], **kw)


def test_rpr3_maximal_constraints_takes_a_numpy_integer():
    m = RPR3.named("M1")
    np.testing.assert_array_equal(m.maximal_constraints([[1.0, 1.5]], n_grid=np.int64(36), n_refine=np.int32(5)),
                                  m.maximal_constraints([[1.0, 1.5]], n_grid=36, n_refine=5))


def test_rpr3_workspace_refuses_a_numpy_bool_orientation():
    """A bool phi was refused but NumPy's bool was read as 1 rad (now refused as bool is)."""
    with pytest.raises(ValueError, match="phi must be one finite orientation"):
        RPR3.named("M1").workspace(np.True_)


# ---------------------------------------------------------------- spatial cable robot
def _box_corners() -> np.ndarray:
    return np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (0, 3)], float)


@pytest.mark.parametrize("kw", [{"t_min": True}, {"t_max": np.True_}, {"t_min": "1"}, {"t_max": "100"},
                                {"t_min": False}])
def test_spatial_cable_robot_refuses_a_bool_or_a_string_limit(kw):
    c = _box_corners()
    with pytest.raises(ValueError, match=r"^need finite 0 <= t_min < t_max; got t_min="):
        SpatialCableRobot(c, 0.1 * np.sign(c - [0, 0, 1.5]), **kw)


def test_spatial_cable_robot_takes_numpy_numbers():
    c = _box_corners()
    robot = SpatialCableRobot(c, 0.1 * np.sign(c - [0, 0, 1.5]), t_min=np.int64(1), t_max=np.float32(150.0))
    assert robot.t_max == 150.0


@pytest.mark.parametrize("resolution", [True, np.True_, "10", 10.0, 0])
def test_spatial_workspace_resolution_must_be_an_integer(resolution):
    c = _box_corners()
    robot = SpatialCableRobot(c, 0.1 * np.sign(c - [0, 0, 1.5]))
    with pytest.raises(ValueError, match=r"^resolution must be an integer >= 1 \(cells per axis\); got "):
        robot.workspace([0.0, 0.0, 0.0], [0, 0, -10, 0, 0, 0], [[-0.5, -0.5, 1.0], [0.5, 0.5, 2.0]],
                        resolution=resolution)


BALL = lambda P: np.linalg.norm(P, axis=1) <= 1.0


@pytest.mark.parametrize("reach", [True, "2.0"])
def test_ray_reach_refuses_a_bool_or_a_string_reach(reach):
    with pytest.raises(ValueError, match=r"^reach must be a positive length; got "):
        ray_reach(BALL, [0.0, 0.0, 0.0], [[1.0, 0.0, 0.0]], reach)


@pytest.mark.parametrize("tol", [True, np.True_, "1e-9"])
def test_ray_reach_refuses_a_bool_or_a_string_tol(tol):
    with pytest.raises(ValueError, match=r"^tol must be a finite length > 0 \(the bisection's interval\); got "):
        ray_reach(BALL, [0.0, 0.0, 0.0], [[1.0, 0.0, 0.0]], 2.0, tol=tol)


# ---------------------------------------------------------------- inline tests made consistent
@pytest.mark.parametrize("tol", [True, False, np.True_])
def test_planar_cable_tensions_refuse_a_bool_tol(tol):
    """``isinstance(tol, (int, float))`` took True as tol = 1 (widening every tension limit by 1 N)."""
    robot = thesis_robot(4)
    with pytest.raises(ValueError, match=r"^tol must be a finite number >= 0 \(the tolerance on the tension limits\)"):
        robot.tensions_batch([[0.0, 0.0]], 0.0, [0.0, -10.0, 0.0], "l1", tol=tol)


def test_planar_cable_tensions_take_a_numpy_tol():
    """... and refused NumPy's float32 and integers, which every other check takes."""
    robot = thesis_robot(4)
    assert isinstance(robot, CableRobot)
    ref = robot.tensions_batch([[0.0, 0.0]], 0.0, [0.0, -10.0, 0.0], "l1", tol=1e-10)
    got = robot.tensions_batch([[0.0, 0.0]], 0.0, [0.0, -10.0, 0.0], "l1", tol=np.float32(1e-10))
    np.testing.assert_array_equal(got[0], ref[0])
    got0 = robot.tensions_batch([[0.0, 0.0]], 0.0, [0.0, -10.0, 0.0], "l1", tol=np.int64(0))
    np.testing.assert_array_equal(got0[0], robot.tensions_batch([[0.0, 0.0]], 0.0, [0.0, -10.0, 0.0], "l1", tol=0)[0])


@pytest.mark.parametrize("k", [True, False, np.True_])
def test_perturbed_starts_refuse_a_bool_k(k):
    """``isinstance(k, (int, np.integer))`` took False as start 0 and True as start 1."""
    from manipulators.synthesis import _spread

    with pytest.raises(ValueError, match=r"^k must be an integer >= 0, got "):
        _spread.perturbed([1.0, 2.0], (0, 0), k, 1e-6)


@pytest.mark.parametrize("eps", [True, np.True_, "1e-6"])
def test_perturbed_starts_refuse_a_bool_eps(eps):
    from manipulators.synthesis import _spread

    with pytest.raises(ValueError, match=r"^eps must be a number > 0, got "):
        _spread.perturbed([1.0, 2.0], (0, 0), 1, eps)


def test_perturbed_starts_take_a_numpy_eps():
    from manipulators.synthesis import _spread

    np.testing.assert_array_equal(_spread.perturbed([1.0, 2.0], (0, 0), 2, np.float32(0.5)),
                                  _spread.perturbed([1.0, 2.0], (0, 0), 2, float(np.float32(0.5))))


@pytest.mark.parametrize("k", [True, np.True_, 3.0, "96"])
def test_exact_suites_refuse_a_bool_k(k):
    from manipulators.synthesis import rpr2_exact_suite, rpr3_exact_suite

    with pytest.raises(ValueError, match=r"^k \(boundary points\) must be an integer >= 3, got "):
        rpr2_exact_suite.e_exact_problem(k=k)
    with pytest.raises(ValueError, match=r"^k \(boundary points\) must be an integer >= 3, got "):
        rpr2_exact_suite.p_exact_problem(k=k)
    with pytest.raises(ValueError, match=r"^k \(boundary points per slice\) must be an integer >= 3, got "):
        rpr3_exact_suite.exact_problem("d", "P1", k=k)
