"""Planar parallel manipulators, their workspaces and synthesis problems (thesis Ch. 4-6),
and the spatial successors the thesis recommends (Sec. 7.4; docs/spatial.md).

The names below are imported from their submodules on first use (PEP 562), not when the
package is: a synthesis suite's code version (`harness._codeversion`) then covers only the
manipulator modules the suite imports, so editing the spatial robots leaves the planar
suites' stored runs valid.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

#: public name -> the submodule that defines it
_EXPORTS = {
    "CableRobot": ".cable",
    "P1": ".prescribed",
    "P2": ".prescribed",
    "P3": ".prescribed",
    "Prescribed": ".prescribed",
    "get_prescribed": ".prescribed",
    "RPR2": ".rpr2",
    "RPR3": ".rpr3",
    "GoughStewart": ".spatial",
    "SpatialCableRobot": ".spatial",
    "Workspace": ".workspace",
    "chord_boundary": ".workspace",
}

__all__ = list(_EXPORTS)

if TYPE_CHECKING:  # for type checkers only (the code version skips this block: it never runs)
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


def __getattr__(name: str) -> Any:
    if name not in _EXPORTS:
        raise AttributeError(f"module 'manipulators' has no attribute {name!r}; public names: "
                             f"{', '.join(sorted(_EXPORTS))}")
    value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
    globals()[name] = value  # later lookups skip this hook
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_EXPORTS})
