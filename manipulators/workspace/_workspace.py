"""The `Workspace` result type shared by every manipulator (2-RPR, 3-RPR, cable robots)."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

import numpy as np
import shapely

from ._polygon import as_points, polygon_area, to_shapely

__all__ = ["Workspace"]


def _empty2() -> np.ndarray:
    return np.zeros((0, 2))


@dataclasses.dataclass(frozen=True, eq=False)
class Workspace:
    """A planar workspace: a traced boundary polygon and/or a feasibility grid.

    Parameters
    ----------
    boundary : ndarray, shape (k, 2)
        Boundary points ordered counterclockwise (thesis Section 4.3), first point not
        repeated. Bifurcation points are included in order. May be empty (k = 0).
    bifurcations : ndarray, shape (b, 2)
        The bifurcation points B^j (Appendix C.6), also present in ``boundary``.
    area : float
        Enclosed area. For chord workspaces the polygon area; for grid workspaces the number
        of feasible points times the cell area (Algorithm 6.2). ``None`` -> polygon area.
    active : ndarray of int, shape (k,)
        Index of the constraint active at each boundary point (the one that is violated
        just outside it), -1 at bifurcation points (two constraints active).
    method : str
        ``"chord"``, ``"grid"``, ...
    mask : ndarray of bool, shape (len(y), len(x)), optional
        Grid workspaces: ``mask[i, j]`` is True if the point ``(x[j], y[i])`` is feasible
        (the layout of ``numpy.meshgrid(x, y)``, so ``contourf(x, y, mask)`` works).
    grid : (x, y) tuple of 1-D arrays, optional
        Grid coordinates for ``mask``.
    info : mapping
        Diagnostics: ``n_evals`` (calls of the constraint function), ``n_points``
        (points evaluated), ``time`` (s), ``closed`` (closure test C.14 met), ...
    """

    boundary: np.ndarray = dataclasses.field(default_factory=_empty2)
    bifurcations: np.ndarray = dataclasses.field(default_factory=_empty2)
    area: float | None = None
    active: np.ndarray | None = None
    method: str = "chord"
    mask: np.ndarray | None = None
    grid: tuple[np.ndarray, np.ndarray] | None = None
    info: Mapping[str, Any] = dataclasses.field(default_factory=dict)

    def __post_init__(self) -> None:
        set_ = lambda k, v: object.__setattr__(self, k, v)  # the dataclass is frozen
        b = (
            np.zeros((0, 2))
            if self.boundary is None or np.size(self.boundary) == 0
            else as_points(self.boundary, "boundary")
        )
        set_("boundary", b)
        bif = self.bifurcations
        set_("bifurcations", np.zeros((0, 2)) if bif is None or np.size(bif) == 0 else as_points(bif, "bifurcations"))
        act = (
            np.full(b.shape[0], -1, dtype=int)
            if self.active is None
            else np.asarray(self.active, dtype=int).reshape(-1)
        )
        if act.shape[0] != b.shape[0]:
            raise ValueError(f"Workspace.active has length {act.shape[0]}, boundary has {b.shape[0]} points")
        set_("active", act)
        if self.mask is not None:
            if self.grid is None:
                raise ValueError("Workspace.mask given without grid=(x, y)")
            gx, gy = (np.asarray(g, dtype=float).reshape(-1) for g in self.grid)
            mask = np.asarray(self.mask, dtype=bool)
            if mask.shape != (gy.size, gx.size):
                raise ValueError(
                    f"Workspace.mask must have shape (len(y), len(x)) = {(gy.size, gx.size)}, got {mask.shape}"
                )
            set_("grid", (gx, gy))
            set_("mask", mask)
        if self.area is None:
            set_("area", polygon_area(b) if b.shape[0] >= 3 else 0.0)
        else:
            set_("area", float(self.area))
        set_("info", dict(self.info))

    # ------------------------------------------------------------------ queries
    @property
    def is_empty(self) -> bool:
        return self.boundary.shape[0] < 3 and (self.mask is None or not self.mask.any())

    @property
    def n_boundary(self) -> int:
        return int(self.boundary.shape[0])

    def polygon(self) -> shapely.Polygon:
        """The boundary as a shapely polygon (empty if there is no boundary)."""
        return to_shapely(self.boundary)

    def contains(self, points) -> np.ndarray:
        """Vectorized membership test for points of shape (k, 2) (or (2,)).

        Chord workspaces: inside or on the boundary polygon. Grid workspaces without a
        boundary: the value of the nearest grid point.
        """
        p = as_points(points)
        if self.boundary.shape[0] >= 3:
            poly = self.polygon()
            return np.asarray(shapely.intersects_xy(poly, p[:, 0], p[:, 1]), dtype=bool)
        if self.mask is not None and self.grid is not None:
            gx, gy = self.grid
            ix = _nearest(gx, p[:, 0])
            iy = _nearest(gy, p[:, 1])
            out = self.mask[iy, ix]
            # outside the grid's span: not in the workspace
            hx = (gx[-1] - gx[0]) / max(gx.size - 1, 1) / 2
            hy = (gy[-1] - gy[0]) / max(gy.size - 1, 1) / 2
            outside = (
                (p[:, 0] < gx[0] - hx) | (p[:, 0] > gx[-1] + hx) | (p[:, 1] < gy[0] - hy) | (p[:, 1] > gy[-1] + hy)
            )
            return out & ~outside
        return np.zeros(p.shape[0], dtype=bool)

    @classmethod
    def empty(cls, method: str = "chord", **info: Any) -> Workspace:
        """A workspace with no points (e.g. a design whose leg limits admit no position)."""
        return cls(method=method, area=0.0, info={"closed": False, **info})

    def __repr__(self) -> str:
        return (f"Workspace(method={self.method!r}, n_boundary={self.n_boundary}, "
                f"n_bifurcations={self.bifurcations.shape[0]}, area={self.area:.6g})")


def _nearest(g: np.ndarray, v: np.ndarray) -> np.ndarray:
    i = np.clip(np.searchsorted(g, v), 1, g.size - 1) if g.size > 1 else np.zeros(v.size, dtype=int)
    if g.size > 1:
        i = np.where(np.abs(v - g[i - 1]) <= np.abs(v - g[i]), i - 1, i)
    return i
