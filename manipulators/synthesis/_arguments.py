"""Argument checks shared by the synthesis problems' builders (2-RPR and 3-RPR suites)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from .._checks import is_number

__all__ = ["chord_length", "lookup"]


def chord_length(chord: Any, default: float, where: str) -> float:
    """The chord length d of a synthesis problem: None is the thesis's ``default``.  Any other
    value must be a finite length > 0: a bad one makes the chord method fail at every design,
    which the problems count as an empty workspace, so the objective would be silently flat."""
    if chord is None:
        return float(default)
    if not (is_number(chord) and math.isfinite(chord) and chord > 0):
        raise ValueError(f"{where}: chord must be a finite length > 0 (None: the thesis's {default}), got {chord!r}")
    return float(chord)


def lookup(table: Mapping[str, Any], key: Any, what: str, where: str) -> Any:
    """``table[key]``, or a ValueError naming ``what`` and the valid keys."""
    if not isinstance(key, str) or key not in table:
        raise ValueError(f"{where}: unknown {what} {key!r}; valid: {', '.join(table)}")
    return table[key]
