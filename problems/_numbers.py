"""What counts as a number in an input: one test for the problems and solvers layers.

A bool is not a number here (``True`` as a tolerance is a slip, not 1.0), nor is a
string that looks like one (``"1e-6"`` from a config file must be converted by the caller,
visibly). NumPy scalars are numbers.
"""

from __future__ import annotations

import math
import numbers
from typing import Any

__all__ = ["is_number", "is_integer", "is_finite_number"]


def is_number(value: Any) -> bool:
    """A real number: int, float or a NumPy real scalar; not bool, not str, not None."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool) and type(value).__name__ != "bool_"


def is_finite_number(value: Any) -> bool:
    """A real number that is neither NaN nor infinite."""
    return is_number(value) and math.isfinite(value)


def is_integer(value: Any) -> bool:
    """An integral number (``3``, ``np.int64(3)``); a float such as ``3.0`` is not one."""
    return isinstance(value, numbers.Integral) and not isinstance(value, bool) and type(value).__name__ != "bool_"
