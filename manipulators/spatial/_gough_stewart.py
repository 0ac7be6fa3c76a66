"""The Gough-Stewart platform (6-UPS hexapod): inverse kinematics, Jacobian, workspace.

Conventions as for `SpatialCableRobot` (docs/spatial.md): base points a_i in the world
frame, platform points b_i in the platform frame, rotation a 3 x 3 matrix or extrinsic
x-y-z angles. Leg i is the vector l_i = p + R b_i - a_i and its length |l_i| must lie in
[l_min, l_max] (the spatial form of the leg limits (5.3) of the thesis's RPR platforms).

At a fixed orientation the position p is reachable iff |p - c_i| is in [l_min, l_max]
for the six centres c_i = a_i - R b_i: the constant-orientation workspace is exactly the
intersection of six spherical shells. `ray_segments` gives the exact radial pieces of
that intersection along any ray, and `exact_volume` integrates it over the sphere of
directions (Gauss-Legendre in cos(theta) x uniform in phi): the reference against which
the grid and bisection workspaces are checked.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from .._checks import is_number
from ._cable import (
    SpatialWorkspace,
    _points,
    feasible_in_chunks,
    grid_points,
    positions_array,
    ray_boundary,
    rotation_matrix,
)

__all__ = ["GoughStewart"]


@dataclasses.dataclass(frozen=True)
class GoughStewart:
    """Six legs between base points a_i and platform points b_i ((6, 3), metres), with
    leg-length limits l_min <= |l_i| <= l_max.  Immutable, as `SpatialCableRobot`.

    ``char_length`` (metres) makes the Jacobian dimensionally homogeneous for the
    condition number (the thesis's Section 1 discussion of mixed units): the rotational
    columns are divided by it. Default: the RMS platform radius sqrt(mean |b_i|^2).
    """

    base_points: Any
    platform_points: Any
    l_min: float
    l_max: float
    char_length: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "base_points", _points("base_points", self.base_points))
        object.__setattr__(self, "platform_points", _points("platform_points", self.platform_points))
        if self.base_points.shape[0] != 6 or self.platform_points.shape[0] != 6:
            raise ValueError("a Gough-Stewart platform has 6 base and 6 platform points; got "
                             f"{self.base_points.shape[0]} and {self.platform_points.shape[0]}")
        if not (is_number(self.l_min) and is_number(self.l_max) and np.isfinite(self.l_min)
                and np.isfinite(self.l_max) and 0 <= self.l_min < self.l_max):
            raise ValueError(f"need finite 0 <= l_min < l_max; got l_min={self.l_min!r}, l_max={self.l_max!r}")
        cl = self.char_length
        if cl is None:
            cl = float(np.sqrt(np.mean(np.sum(self.platform_points**2, axis=1))))
        if not (is_number(cl) and np.isfinite(cl) and cl > 0):
            raise ValueError(f"char_length must be a positive length; got {cl!r}")
        object.__setattr__(self, "char_length", cl)

    def legs(self, positions: Any, rotation: Any) -> np.ndarray:
        """Leg vectors l_i = p + R b_i - a_i, (k, 6, 3), at k positions for one orientation."""
        p = positions_array(positions)
        R = rotation_matrix(rotation)
        return p[:, None, :] + (self.platform_points @ R.T)[None] - self.base_points[None]

    def inverse_kinematics(self, position: Any, rotation: Any) -> np.ndarray:
        """The six leg lengths |l_i| at one pose."""
        return np.linalg.norm(self.legs(position, rotation)[0], axis=1)

    def jacobian(self, position: Any, rotation: Any) -> np.ndarray:
        """Inverse Jacobian J (6 x 6): leg rates = J [v; omega], row i = [n_i, (R b_i) x n_i],
        n_i the unit leg vector, omega the angular velocity in the world frame."""
        L = self.legs(position, rotation)[0]
        n = L / np.linalg.norm(L, axis=1, keepdims=True)
        rb = self.platform_points @ rotation_matrix(rotation).T
        return np.hstack([n, np.cross(rb, n)])

    def inverse_condition(self, positions: Any, rotation: Any) -> np.ndarray:
        """1 / kappa(J diag(1, 1, 1, 1/L, 1/L, 1/L)) at k positions, L = ``char_length``;
        in [0, 1], 0 at a singularity. Vectorized."""
        L = self.legs(positions, rotation)
        n = L / np.linalg.norm(L, axis=2, keepdims=True)
        rb = self.platform_points @ rotation_matrix(rotation).T
        J = np.concatenate([n, np.cross(rb[None], n) / self.char_length], axis=2)
        s = np.linalg.svd(J, compute_uv=False)
        return s[:, -1] / s[:, 0]

    def feasible(self, positions: Any, rotation: Any) -> np.ndarray:
        """Leg-length feasibility (k,) bool at k positions for one orientation."""
        d = np.linalg.norm(self.legs(positions, rotation), axis=2)
        return np.all((d >= self.l_min) & (d <= self.l_max), axis=1)

    def workspace(self, rotation: Any, box: Any, resolution: int = 60) -> SpatialWorkspace:
        """The constant-orientation workspace on a resolution^3 grid of cell centres."""
        b, pts = grid_points(box, resolution)
        mask = feasible_in_chunks(lambda P: self.feasible(P, rotation), pts).reshape((int(resolution),) * 3)
        return SpatialWorkspace(mask, pts, b, int(resolution))

    def boundary_points(self, rotation: Any, centre: Any, directions: Any, reach: float,
                        tol: float = 1e-9) -> np.ndarray:
        """Boundary points by bisection along rays from a reachable centre (`ray_boundary`)."""
        return ray_boundary(lambda P: self.feasible(P, rotation), centre, directions, reach, tol)

    def ray_segments(self, rotation: Any, centre: Any, directions: Any) -> tuple[np.ndarray, np.ndarray]:
        """Exact reachable pieces of rays centre + s d (s >= 0) through the six-shell intersection.

        Each shell |p - c_i| in [l_min, l_max] meets the ray where s^2 + 2 b s + |e|^2 = l^2
        (e = centre - c_i, b = d . e): at most 4 roots per leg. Between consecutive roots
        feasibility is constant, so testing each piece's midpoint classifies the ray exactly.

        Returns (breaks (k, 26) sorted, ends included: 0 and the farthest root; feasible
        (k, 25) bool per piece [breaks[j], breaks[j+1]]).
        """
        c = np.asarray(centre, dtype=float)
        D = np.atleast_2d(np.asarray(directions, dtype=float))
        D = D / np.linalg.norm(D, axis=1, keepdims=True)
        C = self.base_points - self.platform_points @ rotation_matrix(rotation).T  # shell centres
        e = c[None] - C  # (6, 3)
        b = D @ e.T  # (k, 6)
        ee = np.sum(e * e, axis=1)
        roots = []
        for lim in (self.l_min, self.l_max):
            disc = b**2 - ee + lim**2
            with np.errstate(invalid="ignore"):
                r = np.sqrt(disc)
            for sgn in (-1.0, 1.0):
                s = -b + sgn * r
                roots.append(np.where((disc >= 0) & (s > 0), s, 0.0))
        R = np.concatenate(roots, axis=1)  # (k, 24); non-roots parked at 0
        far = R.max(axis=1, keepdims=True)
        breaks = np.sort(np.concatenate([np.zeros((len(D), 1)), R, far], axis=1), axis=1)
        mids = 0.5 * (breaks[:, 1:] + breaks[:, :-1])  # (k, 25)
        P = c[None, None, :] + mids[..., None] * D[:, None, :]
        dist = np.linalg.norm(P[:, :, None, :] - C[None, None], axis=3)  # (k, 25, 6)
        feas = np.all((dist >= self.l_min) & (dist <= self.l_max), axis=2) & (breaks[:, 1:] > breaks[:, :-1])
        return breaks, feas

    def exact_volume(self, rotation: Any, centre: Any, n_theta: int = 200, n_phi: int = 400) -> float:
        """Volume of the six-shell intersection: the integral over directions of
        sum over reachable ray pieces of (s_hi^3 - s_lo^3) / 3, with exact radial pieces
        (`ray_segments`) and Gauss-Legendre (cos theta) x midpoint (phi) quadrature.
        Exact radially for any shape (not only star-shaped ones); the angular quadrature is
        the only approximation (see tests for its convergence)."""
        x, wx = np.polynomial.legendre.leggauss(int(n_theta))
        phi = (np.arange(int(n_phi)) + 0.5) * 2 * np.pi / int(n_phi)
        st = np.sqrt(1 - x**2)
        D = np.column_stack([np.outer(st, np.cos(phi)).ravel(), np.outer(st, np.sin(phi)).ravel(),
                             np.repeat(x, len(phi))])
        vol = np.zeros(len(D))
        for s in range(0, len(D), 20000):  # bounded memory
            br, feas = self.ray_segments(rotation, centre, D[s:s + 20000])
            vol[s:s + 20000] = np.sum(np.where(feas, br[:, 1:] ** 3 - br[:, :-1] ** 3, 0.0), axis=1) / 3
        return float(np.sum(np.repeat(wx, len(phi)) * vol) * 2 * np.pi / int(n_phi))

    def __repr__(self) -> str:
        return f"GoughStewart(l_min={self.l_min}, l_max={self.l_max}, char_length={self.char_length:.4g})"
