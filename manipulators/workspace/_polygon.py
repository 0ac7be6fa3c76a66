"""Polygon helpers: exact (shoelace) area, orientation, shapely conversion."""

from __future__ import annotations

import numpy as np
import shapely

__all__ = ["polygon_area", "signed_area", "is_ccw", "to_shapely", "as_points"]


def as_points(points, name: str = "points") -> np.ndarray:
    """``points`` as a float array of shape (k, 2); a single point (2,) becomes (1, 2)."""
    arr = np.asarray(points, dtype=float)
    if arr.ndim == 1 and arr.shape[0] == 2:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (k, 2), got {arr.shape}")
    return arr


def signed_area(boundary) -> float:
    """Signed area of a closed polygon (first vertex not repeated); > 0 if counterclockwise.

    Shoelace formula: the sum of the triangle areas (eq. 4.9) of consecutive vertices with
    the origin, taken with sign, so it is exact for the polygon.
    """
    b = as_points(boundary, "boundary")
    if b.shape[0] < 3:
        return 0.0
    x, y = b[:, 0], b[:, 1]
    # shift to the centroid of the vertices to reduce cancellation
    x = x - x.mean()
    y = y - y.mean()
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def polygon_area(boundary) -> float:
    """Area enclosed by a closed polygon (absolute value of the shoelace sum)."""
    return abs(signed_area(boundary))


def is_ccw(boundary) -> bool:
    """True if the polygon's vertices run counterclockwise."""
    return signed_area(boundary) > 0.0


def to_shapely(boundary) -> shapely.Polygon:
    """A shapely Polygon through the boundary points (empty polygon for < 3 points).

    Self-touching outlines (a region pinched at the base line, say) are repaired with
    ``shapely.make_valid`` so that set operations never fail.
    """
    b = as_points(boundary, "boundary")
    if b.shape[0] < 3:
        return shapely.Polygon()
    poly = shapely.Polygon(b)
    if not poly.is_valid:
        poly = shapely.make_valid(poly)
    return poly
