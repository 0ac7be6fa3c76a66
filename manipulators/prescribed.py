"""Prescribed workspaces P1-P3 (thesis Sections 4.5.2 and 4.7.3) as polar curves r_p(beta).

Each is star-shaped about its centre O' = (0, 3): the boundary point at polar angle beta is
O' + r_p(beta) (cos beta, sin beta). P1 and P3 are piecewise circular arcs,

    r_p(beta) = -b + s sqrt(b^2 - dx^2 - dy^2 + R^2),  b = dx cos beta + dy sin beta   (4.25)

(the ray from O' meeting the circle of radius R centred at O' - (dx, dy); s = +1 or -1).

* P1: eq. (4.11) with Table 4.1 as corrected in ERRATA.md: four arcs of radius R = 2.867
  whose centres sit D = 1.687 on the opposite side of O' (the printed cos^2 must be sin^2
  in [pi/4, 3pi/4) and [5pi/4, 7pi/4)); corners at (+-1, 3 +- 1).
* P2: ellipse with half-axes a = 1.75 (x) and b = 1.00 (y).
* P3: eq. (4.25) with Table 4.8 and the signs +, +, -, +, - (ERRATA.md: continuity).

Chapter 5 reuses them for the 3-RPR centred at (1, 1.5) with radii divided by 5 (P1, P2)
or 7 (P3): ``P1.scaled(1 / 5).moved(to=(1.0, 1.5))`` or `chapter5_workspaces()`.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import shapely

from .workspace._polygon import polygon_area

__all__ = ["Prescribed", "P1", "P2", "P3", "PRESCRIBED", "get_prescribed", "chapter5_workspaces",
           "arc_radius", "R_P1", "D_P1", "P3_ARCS"]

PI = math.pi
CENTRE = (0.0, 3.0)  # O' (Sections 4.5.2, 4.7.3)
R_P1, D_P1 = 2.867, 1.687  # eq. (4.11)
# Table 4.8: (beta_min, beta_max, dx, dy, R, sign); signs of arcs 3-5 from ERRATA.md
P3_ARCS = (
    (0.0, PI / 2, 0.0, 0.0, 2.0, +1),
    (PI / 2, PI, -1.5, 0.0, 2.5, +1),
    (PI, 1.444 * PI, 2.75, 2.25, 2.8504, -1),
    (1.444 * PI, 1.555 * PI, -0.07005, 0.86647, 0.29206, +1),
    (1.555 * PI, 2 * PI, -2.3125, 2.5, 2.5195, -1),
)
# eq. (4.11) as circle arcs: alpha = -D cos -> circle centred at O' - (D, 0), etc.
P1_ARCS = (
    (-PI / 4, PI / 4, D_P1, 0.0, R_P1, +1),
    (PI / 4, 3 * PI / 4, 0.0, D_P1, R_P1, +1),
    (3 * PI / 4, 5 * PI / 4, -D_P1, 0.0, R_P1, +1),
    (5 * PI / 4, 7 * PI / 4, 0.0, -D_P1, R_P1, +1),
)


def arc_radius(beta, dx: float, dy: float, R: float, sign: int = 1) -> np.ndarray:
    """Eq. (4.25): distance from O' along angle beta to the circle of radius R centred at
    O' - (dx, dy) (sign +1: far intersection, -1: near one)."""
    beta = np.asarray(beta, dtype=float)
    b = dx * np.cos(beta) + dy * np.sin(beta)
    disc = b * b - dx * dx - dy * dy + R * R
    return -b + sign * np.sqrt(np.maximum(disc, 0.0))


def _piecewise_arcs(arcs) -> Callable[[np.ndarray], np.ndarray]:
    start = arcs[0][0]

    def radius(beta: np.ndarray) -> np.ndarray:
        bb = start + np.mod(np.asarray(beta, dtype=float) - start, 2 * PI)
        out = np.empty_like(bb)
        for k, (lo, hi, dx, dy, R, sg) in enumerate(arcs):
            sel = (bb >= lo) & (bb < hi) if k < len(arcs) - 1 else (bb >= lo)
            out[sel] = arc_radius(bb[sel], dx, dy, R, sg)
        return out

    return radius


def _ellipse(a: float, b: float) -> Callable[[np.ndarray], np.ndarray]:
    def radius(beta: np.ndarray) -> np.ndarray:
        beta = np.asarray(beta, dtype=float)
        return a * b / np.sqrt((b * np.cos(beta)) ** 2 + (a * np.sin(beta)) ** 2)

    return radius


@dataclasses.dataclass(frozen=True)
class Prescribed:
    """A prescribed workspace: a star-shaped region given by its polar boundary r_p(beta).

    Parameters
    ----------
    name : "P1", "P2", "P3" (or any label).
    shape : callable ``r(beta)`` of the unscaled curve (vectorized).
    centre : O', the polar origin.
    scale : factor applied to every radius.
    """

    name: str
    shape: Callable[[np.ndarray], np.ndarray]
    centre: tuple[float, float] = CENTRE
    scale: float = 1.0

    def __post_init__(self) -> None:
        c = tuple(float(v) for v in np.asarray(self.centre, dtype=float).reshape(2))
        object.__setattr__(self, "centre", c)
        if not (self.scale > 0 and math.isfinite(self.scale)):
            raise ValueError(f"{self.name}: scale must be a positive number, got {self.scale}")

    def radius(self, beta) -> np.ndarray:
        """r_p(beta): distance from the centre to the boundary at polar angle beta."""
        return self.scale * self.shape(np.asarray(beta, dtype=float))

    def points_at(self, beta) -> np.ndarray:
        """Boundary points b_p at the polar angles beta: shape (k, 2)."""
        beta = np.atleast_1d(np.asarray(beta, dtype=float))
        r = self.radius(beta)
        return np.column_stack((self.centre[0] + r * np.cos(beta), self.centre[1] + r * np.sin(beta)))

    def points(self, k: int = 720) -> np.ndarray:
        """k boundary points at equally spaced angles, counterclockwise from beta = 0."""
        if k < 3:
            raise ValueError(f"points(k) needs k >= 3, got {k}")
        return self.points_at(2 * PI * np.arange(k) / k)

    def polygon(self, k: int = 4096) -> shapely.Polygon:
        """The region as a shapely polygon through k boundary points."""
        return shapely.Polygon(self.points(k))

    def area(self, k: int = 4096) -> float:
        return polygon_area(self.points(k))

    def scaled(self, factor: float, about=None) -> Prescribed:
        """Radii multiplied by ``factor``; the centre moves away from ``about`` by the same
        factor (``about=None``: about the centre itself, which then stays put)."""
        if about is None:
            return dataclasses.replace(self, scale=self.scale * factor)
        about = np.asarray(about, dtype=float).reshape(2)
        c = about + factor * (np.asarray(self.centre) - about)
        return dataclasses.replace(self, scale=self.scale * factor, centre=tuple(c))

    def moved(self, offset=None, *, to=None) -> Prescribed:
        """Translated by ``offset`` (dx, dy), or with its centre placed at ``to``."""
        if (offset is None) == (to is None):
            raise ValueError("moved() needs exactly one of offset=(dx, dy) or to=(x, y)")
        c = (
            np.asarray(to, dtype=float).reshape(2)
            if to is not None
            else np.asarray(self.centre) + np.asarray(offset, dtype=float).reshape(2)
        )
        return dataclasses.replace(self, centre=tuple(c))

    def __repr__(self) -> str:
        return f"Prescribed({self.name!r}, centre={self.centre}, scale={self.scale:g})"


P1 = Prescribed("P1", _piecewise_arcs(P1_ARCS))
P2 = Prescribed("P2", _ellipse(1.75, 1.0))
P3 = Prescribed("P3", _piecewise_arcs(P3_ARCS))
PRESCRIBED = {"P1": P1, "P2": P2, "P3": P3}


def get_prescribed(name: str) -> Prescribed:
    """P1, P2 or P3 by name."""
    try:
        return PRESCRIBED[name.upper()]
    except (KeyError, AttributeError):
        raise KeyError(f"unknown prescribed workspace {name!r}; valid: {', '.join(PRESCRIBED)}") from None


def chapter5_workspaces(centre=(1.0, 1.5)) -> dict[str, Prescribed]:
    """P1-P3 as used for the 3-RPR (Sections 5.6-5.8, ERRATA.md): centred at (1, 1.5),
    radii divided by 5 (P1, P2) and 7 (P3)."""
    return {
        "P1": P1.scaled(1 / 5).moved(to=centre),
        "P2": P2.scaled(1 / 5).moved(to=centre),
        "P3": P3.scaled(1 / 7).moved(to=centre),
    }
