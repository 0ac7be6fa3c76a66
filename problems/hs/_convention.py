"""The one place where the Hock–Schittkowski sign convention meets ours.

Hock & Schittkowski (and the vendored JSON) write inequality constraints as
g_HS(x) >= 0; this project (thesis eq. 3.3) writes g(x) <= 0. The conversion is a
negation, g = -g_HS, and it is done here and nowhere else.
"""

from __future__ import annotations

from typing import Any

__all__ = ["hs_to_ours", "ours_to_hs"]


def hs_to_ours(g_hs: Any) -> Any:
    """HS inequality values/expressions (feasible when >= 0) -> ours (feasible when <= 0)."""
    return -g_hs


def ours_to_hs(g: Any) -> Any:
    """Inverse of `hs_to_ours` (used by tests and for reporting in the HS convention)."""
    return -g
