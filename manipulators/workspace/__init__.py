"""Planar workspaces: the `Workspace` type, the chord method and polygon helpers.

Shared by every manipulator of the project (2-RPR, 3-RPR, cable-driven robots):

>>> ws = chord_boundary(constraints, interior=(0.0, 3.0), chord=0.1)
>>> ws.boundary, ws.area, ws.bifurcations, ws.contains([[0.0, 3.0]])
"""

from ._chord import ChordError as ChordError
from ._chord import InfeasibleInterior as InfeasibleInterior
from ._chord import OpenBoundary as OpenBoundary
from ._chord import OpenBoundaryWarning as OpenBoundaryWarning
from ._chord import check_closed as check_closed
from ._chord import chord_boundary as chord_boundary
from ._chord import open_policy as open_policy
from ._polygon import is_ccw as is_ccw
from ._polygon import polygon_area as polygon_area
from ._polygon import signed_area as signed_area
from ._polygon import to_shapely as to_shapely
from ._workspace import Workspace as Workspace
