"""Bad poses of the 3-RPR get errors that name them (not NumPy's, not a kappa^-1 of 0)."""

import numpy as np
import pytest

from manipulators import RPR3


def test_rpr3_nan_pose_is_refused_not_read_as_a_singularity():
    m = RPR3(-1, 0, 1, 2, 1)
    with pytest.raises(ValueError, match=r"NaN or inf at row\(s\) \[0\]"):
        m.inverse_condition([np.nan, 1.0], 0.0)
    with pytest.raises(ValueError, match=r"row\(s\) \[1\].*phi = nan"):
        m.jacobian([[1.0, 1.37], [1.05, 1.42]], [0.0, np.nan])


def test_rpr3_orientations_must_match_the_positions():
    m = RPR3(-1, 0, 1, 2, 1)
    with pytest.raises(ValueError, match=r"one per position \(2,\)"):
        m.inverse_condition(np.zeros((2, 2)), [0.0, 0.1, 0.2])
    np.testing.assert_allclose(m.inverse_condition([[1.0, 1.37], [1.05, 1.42]], [0.0, 0.0]),
                               m.inverse_condition([[1.0, 1.37], [1.05, 1.42]], 0.0))


def test_every_planar_robot_names_at_most_five_bad_rows():
    """The 3-RPR and the cable robots share one pose check (`manipulators._checks`)."""
    from manipulators import CableRobot

    U = np.full((7, 2), np.nan)
    with pytest.raises(ValueError, match=r"poses contain NaN or inf at row\(s\) \[0, 1, 2, 3, 4\] \.\.\.: u = \[nan"):
        RPR3(-1, 0, 1, 2, 1).inverse_condition(U, 0.0)
    robot = CableRobot([[1, 0.15], [-1, 0.15], [-1, -0.15], [1, -0.15]], [[0.1, 0], [-0.1, 0], [-0.1, 0], [0.1, 0]])
    with pytest.raises(ValueError, match=r"poses contain NaN or inf at row\(s\) \[0, 1, 2, 3, 4\] \.\.\."):
        robot.kinematics(U, 0.0)


# ---------------------------------------------------------------- the design and its limits
@pytest.mark.parametrize("bad", ["a", None, [1.0], True])
def test_rpr3_coordinates_must_be_numbers(bad):
    with pytest.raises(ValueError, match=r"RPR3: xD must be a number"):
        RPR3(-1, 0, bad, 2, 1)


def test_rpr3_leg_limits_of_the_wrong_length_are_named():
    with pytest.raises(ValueError, match=r"l_min must be a number or three numbers \(one per leg\)"):
        RPR3(-1, 0, 1, 2, 1, l_min=(1.0, 1.0))
    assert RPR3(-1, 0, 1, 2, 1, l_min=1.2).l_min == (1.2, 1.2, 1.2)


# ---------------------------------------------------------------- orientation sets
def test_orientation_sets_refuse_nan_points_instead_of_dropping_them():
    """A NaN boundary point used to vanish from the intersection: W_p 'enclosed' without it."""
    m = RPR3.named("M1")
    B = np.array([[1.0, 1.5], [np.nan, 1.5]])
    with pytest.raises(ValueError, match=r"positions contain NaN or inf at row\(s\) \[1\]"):
        m.enclosing_orientations(B)
    with pytest.raises(ValueError, match=r"positions contain NaN or inf"):
        m.orientation_range(B)
    with pytest.raises(ValueError, match=r"positions contain NaN or inf"):
        m.orientation_intervals([np.inf, 1.0])
    assert m.enclosing_orientations(B[:1])  # the finite point alone has a set


@pytest.mark.parametrize("tol", [float("nan"), float("inf"), "0", None])
def test_enclosing_orientations_needs_a_finite_tolerance(tol):
    with pytest.raises(ValueError, match="tol must be a finite leg-length slack"):
        RPR3.named("M1").enclosing_orientations([[1.0, 1.5]], tol=tol)


def test_orientation_range_reference_must_fit_the_points():
    m = RPR3.named("M1")
    U = [[1.0, 1.5], [1.1, 1.6]]
    with pytest.raises(ValueError, match=r"w_ref must be a number or one per point \(2,\), got shape \(3,\)"):
        m.orientation_range(U, w_ref=[0.0, 0.1, 0.2])
    with pytest.raises(ValueError, match="w_ref must be finite"):
        m.orientation_range(U, w_ref=np.nan)
    lo, hi = m.orientation_range(U, w_ref=[0.0, 0.0])
    np.testing.assert_array_equal(lo, m.orientation_range(U)[0])


def test_orientation_intervals_takes_one_point():
    with pytest.raises(ValueError, match="takes one point .* got 2 points"):
        RPR3.named("M1").orientation_intervals([[1.0, 1.5], [1.1, 1.6]])


@pytest.mark.parametrize("kw", [{"n_grid": 0}, {"n_grid": 2.5}, {"n_refine": -1}, {"n_refine": True}])
def test_maximal_constraints_grid_sizes_are_checked(kw):
    with pytest.raises(ValueError, match=r"maximal_constraints: n_(grid|refine) must be an integer >="):
        RPR3.named("M1").maximal_constraints([[1.0, 1.5]], **kw)


@pytest.mark.parametrize("phi", ["x", None, [0.0, 0.1], float("nan"), True])
def test_constant_orientation_workspace_needs_one_finite_phi(phi):
    with pytest.raises(ValueError, match="phi must be one finite orientation"):
        RPR3.named("M1").workspace(phi)


# ---------------------------------------------------------------- synthesis problems' arguments
@pytest.mark.parametrize("chord", [0, -0.02, float("nan"), True, "0.02"])
def test_synthesis_problem_refuses_a_bad_chord(chord):
    """chord=0 silently became the thesis's 0.02; a negative one emptied every workspace."""
    from manipulators.synthesis import rpr3_suite

    with pytest.raises(ValueError, match="3-RPR SO synthesis: chord must be a finite length > 0"):
        rpr3_suite.synthesis_problem("so", "P1", chord=chord)


def test_synthesis_arguments_name_what_is_valid():
    from manipulators.synthesis import rpr3_suite as r3

    with pytest.raises(ValueError, match="unknown synthesis kind 'xo'; valid: so, mo, d"):
        r3.synthesis_problem("xo")
    with pytest.raises(ValueError, match="unknown synthesis kind 3; valid"):
        r3.synthesis_problem(3)
    with pytest.raises(ValueError, match="unknown prescribed workspace 'P4'; valid: P1, P2, P3"):
        r3.synthesis_problem("mo", "P4")
    with pytest.raises(ValueError, match="exact_enclosure: unknown prescribed workspace 'p1'"):
        r3.exact_enclosure("so", r3.START_SO, "p1")
    with pytest.raises(ValueError, match="enclosing_window: unknown prescribed workspace 'P9'"):
        r3.enclosing_window(r3.START_SO, "P9")
    with pytest.raises(ValueError, match="window_covers: unknown synthesis kind 'dd'"):
        r3.window_covers("dd", [])
    assert r3.synthesis_problem("SO").name == "rpr3-so-p1"  # kind in any case, as before


def test_synthesis_problem_refuses_a_design_of_the_wrong_shape():
    """It used to read as an invalid design: f = 0 and a penalized g, silently."""
    from manipulators.synthesis import rpr3_suite as r3

    p = r3.synthesis_problem("so", "P1")
    with pytest.raises(ValueError, match=r"rpr3-so-p1: design d must have 5 entries .* got shape \(4,\)"):
        p.objective([-1.0, 0.0, 1.0, 2.0])
    with pytest.raises(ValueError, match=r"got shape \(1, 5\)"):
        p.ineq([r3.START_SO])
    g = float(p.ineq(np.array([np.nan, 0.0, 1.0, 2.0, 1.0]))[0])  # NaN: an invalid design, penalized
    assert g > float(r3.PRESCRIBED3["P1"].area())
    assert r3.design([1.0, 2.0]) is None  # the tables' reader keeps returning None for stored x
