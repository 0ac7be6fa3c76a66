"""Planar parallel manipulators, their workspaces and synthesis problems (thesis Ch. 4-6),
and the spatial successors the thesis recommends (Sec. 7.4; docs/spatial.md)."""

from .cable import CableRobot as CableRobot
from .prescribed import P1 as P1
from .prescribed import P2 as P2
from .prescribed import P3 as P3
from .prescribed import Prescribed as Prescribed
from .prescribed import get_prescribed as get_prescribed
from .rpr2 import RPR2 as RPR2
from .rpr3 import RPR3 as RPR3
from .spatial import GoughStewart as GoughStewart
from .spatial import SpatialCableRobot as SpatialCableRobot
from .workspace import Workspace as Workspace
from .workspace import chord_boundary as chord_boundary
