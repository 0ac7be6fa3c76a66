"""The thesis's cable-robot configurations, read from the vendored Tables 6.1-6.4."""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from ._robot import CableRobot

__all__ = ["platform_points", "frame_points", "loads", "limits", "thesis_robot", "design_robot",
           "BETA_MIN"]

#: Minimum angular separation of consecutive frame points in (6.29). The thesis gives no
#: value; every optimized design in Tables 6.5-6.10 with an active separation has
#: |beta^{i+1} - beta^i| = 0.174-0.175, i.e. 10 degrees, which we adopt.
BETA_MIN = np.pi / 18


def _table(stem: str):
    from problems.reference import thesis_table

    return thesis_table(stem)


def _config(cables: int) -> str:
    if cables not in (3, 4):
        raise ValueError(f"the thesis's configurations have 3 or 4 cables, got {cables!r}")
    return f"{cables}-cable"


@functools.cache
def platform_points(cables: int) -> np.ndarray:
    """Platform attachment points abar^i of Table 6.1 (prefactor 1/sqrt(2) applied)."""
    t = _table("table_6_1_tdpm_platform_attachment")
    t = t[(t.config == _config(cables)) & (t.x != "")].sort_values("point")
    pre = np.where(t.prefactor == "1/sqrt(2)", 1 / np.sqrt(2), 1.0)
    pts = np.column_stack([t.x.astype(float) * pre, t.y.astype(float) * pre])
    pts.setflags(write=False)
    return pts


@functools.cache
def frame_points(cables: int) -> np.ndarray:
    """Frame attachment points c^i of Table 6.2."""
    t = _table("table_6_2_tdpm_frame_attachment")
    t = t[(t.config == _config(cables)) & (t.x != "")].sort_values("point")
    pts = np.column_stack([t.x.astype(float), t.y.astype(float)])
    pts.setflags(write=False)
    return pts


@functools.cache
def _loads() -> dict[str, np.ndarray]:
    t = _table("table_6_3_tdpm_loads")
    out = {r.load: np.array([float(r.f_x), float(r.f_y), float(r.tau)]) for r in t.itertuples()}
    for w in out.values():
        w.setflags(write=False)  # read once and shared: an in-place change would reach every later caller
    return out


def loads() -> dict[str, np.ndarray]:
    """Load cases L1-L3 of Table 6.3: name -> [f_x, f_y, tau] (applied at the platform origin).
    A new dict of read-only arrays: scale a copy (``2 * loads()["L1"]``)."""
    return dict(_loads())


@functools.cache
def limits(cables: int) -> dict[str, Any]:
    """Limits of Table 6.4 as CableRobot keywords (D_min applies to the 3-cable robot only)."""
    t = _table("table_6_4_tdpm_limits")
    v = {r.limit: float(r.value) for r in t.itertuples()}
    return {"t_min": v["t_min"], "t_max": v["t_max"], "l_min": v["l_min"],
            "det_min": v["D_min"] if cables == 3 else None}


def thesis_robot(cables: int) -> CableRobot:
    """The 3- or 4-cable robot of Tables 6.1, 6.2 and 6.4 (Figs. 6.4, 6.5, 6.8, 6.9)."""
    return CableRobot(frame_points(cables), platform_points(cables), **limits(cables))


def design_robot(betas: Any) -> CableRobot:
    """The robot of design d = [beta^1 ... beta^n] (Section 6.6.1), n = 3 or 4."""
    b = np.asarray(betas, dtype=float).reshape(-1)
    return CableRobot.from_angles(b, platform_points(b.size), **limits(b.size))
