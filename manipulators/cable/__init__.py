"""Planar cable (tendon-driven) parallel manipulators, thesis Chapter 6.

`CableRobot` (kinematics, structure matrix, tension distribution, workspaces) and the
thesis's configurations (`thesis_robot`, `design_robot`, `loads`).
"""

from ._configs import BETA_MIN as BETA_MIN
from ._configs import design_robot as design_robot
from ._configs import loads as loads
from ._configs import thesis_robot as thesis_robot
from ._distribution import METHODS as METHODS
from ._geometry import frame_point as frame_point
from ._robot import CableRobot as CableRobot

__all__ = ["CableRobot", "METHODS", "BETA_MIN", "frame_point", "thesis_robot", "design_robot", "loads"]
