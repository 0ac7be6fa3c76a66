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
