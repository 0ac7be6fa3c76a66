"""Spatial (6-dof) cable robots and the Gough-Stewart platform, the thesis's recommendation of Section 7.4.

`SpatialCableRobot` carries the planar tension distributions of Chapter 6 (minimum-norm
(6.14), l2 (6.17), l1 (6.19) by basic solutions as in Algorithm 6.1) and the grid and
bisection workspaces of Chapter 5 to six dimensions. Conventions: docs/spatial.md.
"""

from ._cable import SpatialCableRobot as SpatialCableRobot
from ._cable import SpatialWorkspace as SpatialWorkspace
from ._cable import ray_boundary as ray_boundary
from ._cable import ray_reach as ray_reach
from ._cable import rotation_matrix as rotation_matrix
from ._distribution6 import basic_solutions as basic_solutions
from ._distribution6 import distribute6 as distribute6
from ._gough_stewart import GoughStewart as GoughStewart

__all__ = ["SpatialCableRobot", "GoughStewart", "SpatialWorkspace", "ray_boundary", "ray_reach", "rotation_matrix",
           "basic_solutions", "distribute6"]
