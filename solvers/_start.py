"""The start point every established adapter hands its library (one small module, so that the
adapters that share it do not import each other: a change to one adapter's module then leaves
the other adapters' stored runs current)."""

from __future__ import annotations

import numpy as np

from problems import Oracle

__all__ = ["start_in_bounds"]


def start_in_bounds(oracle: Oracle) -> np.ndarray:
    """x0 projected onto the simple bounds.

    SciPy's SLSQP and NLopt clip x0 themselves, but SLSQP first evaluates the
    constraints at the *unclipped* x0 (to count them), which would cost one extra,
    meaningless N^fg; projecting first avoids it and treats every adapter alike.
    """
    return np.clip(oracle.x0, oracle.lower, oracle.upper)
