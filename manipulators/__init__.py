"""Planar parallel manipulators, their workspaces and synthesis problems (thesis Ch. 4-6)."""

from .rpr2 import RPR2 as RPR2
from .rpr3 import RPR3 as RPR3
from .prescribed import P1 as P1
from .prescribed import P2 as P2
from .prescribed import P3 as P3
from .prescribed import Prescribed as Prescribed
from .prescribed import get_prescribed as get_prescribed
from .workspace import Workspace as Workspace
from .workspace import chord_boundary as chord_boundary
from .cable import CableRobot as CableRobot
from .spatial import SpatialCableRobot as SpatialCableRobot
from .spatial import GoughStewart as GoughStewart
