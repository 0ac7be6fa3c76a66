"""The spatial cable robot: structure matrix, tensions and wrench-feasible workspaces.

Conventions (also in docs/spatial.md)
-------------------------------------
* Frame points a_i and platform points b_i are (m, 3) arrays in metres; b_i is given in
  the platform frame, whose origin is the reference point p.
* ``rotation`` is a 3 x 3 rotation matrix R (platform frame to world) or three angles
  (alpha, beta, gamma) in radians, read as *extrinsic* rotations about the fixed world
  axes x, then y, then z: R = R_z(gamma) R_y(beta) R_x(alpha) (SciPy's ``"xyz"``).
* Cable i pulls the platform along the unit vector u_i = (a_i - p - R b_i) / L_i. Column i
  of the 6 x m structure matrix is [u_i; (R b_i) x u_i] (force; moment about p), and the
  tensions t balance the external wrench w = [f; tau] acting on the platform:
  S t + w = 0 (thesis eq. 6.11 in 6-D).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from .._checks import finite_rows, is_integer, is_number
from ._distribution6 import distribute6, full_rank6

__all__ = ["SpatialCableRobot", "SpatialWorkspace", "rotation_matrix", "ray_boundary", "ray_reach", "grid_points",
           "METHODS"]

#: Tension methods: minimum-norm (6.14), constrained l2 (6.17, a QP), l1 (6.19).
METHODS = ("l1", "l2", "min-norm")

#: Largest grid (resolution^3 cell centres) a workspace is sampled on: its points alone take
#: 24 bytes each (480 MB here), so a larger one is refused with its size rather than left to
#: exhaust memory.  Feasibility is tested in chunks of FEASIBILITY_CHUNK points, so the
#: robots' per-pose arrays (the cable robot's 6 x m structure matrices) stay bounded too.
MAX_GRID_POINTS = 20_000_000
FEASIBILITY_CHUNK = 65_536
_MAX_RESOLUTION = 271  # the largest n with n^3 <= MAX_GRID_POINTS


def rotation_matrix(rotation: Any) -> np.ndarray:
    """A 3 x 3 rotation matrix from a matrix or extrinsic x-y-z angles (radians)."""
    r = np.asarray(rotation, dtype=float)
    if r.shape == (3, 3):
        if not (np.all(np.isfinite(r)) and np.allclose(r.T @ r, np.eye(3), atol=1e-9)
                and np.linalg.det(r) > 0):
            raise ValueError("rotation matrix must be finite and orthonormal with det +1")
        return r
    if r.shape == (3,):
        if not np.all(np.isfinite(r)):
            raise ValueError(f"rotation angles must be finite; got {r.tolist()}")
        from scipy.spatial.transform import Rotation

        return Rotation.from_euler("xyz", r).as_matrix()
    raise ValueError(f"rotation must be a 3 x 3 matrix or 3 x-y-z angles; got shape {r.shape}")


def positions_array(positions: Any) -> np.ndarray:
    """Platform positions as a (k, 3) array: one position (3,) or k of them (k, 3), finite.

    A NaN or infinite coordinate is refused here, with the offending rows named, rather than
    read downstream as a singular or infeasible pose."""
    p = np.atleast_2d(np.asarray(positions, dtype=float))
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"positions must be (3,) or (k, 3) coordinates in metres; got shape {np.shape(positions)}")
    finite_rows(p, "positions")
    return p


def _points(name: str, value: Any) -> np.ndarray:
    """A read-only copy of a finite (m, 3) array: the robots are immutable values, so their
    points cannot change under a workspace or tension computation (nor the caller's array)."""
    a = np.array(value, dtype=float)
    if a.ndim != 2 or a.shape[1] != 3 or not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be a finite (m, 3) array in metres; got shape {a.shape}")
    a.flags.writeable = False
    return a


def _resolution(resolution: Any) -> int:
    """Grid cells per axis: an integer >= 1 whose cube is at most MAX_GRID_POINTS."""
    if not is_integer(resolution) or resolution < 1:
        raise ValueError(f"resolution must be an integer >= 1 (cells per axis); got {resolution!r}")
    n = int(resolution)
    if n**3 > MAX_GRID_POINTS:
        raise ValueError(f"resolution {n} means {n**3:,} grid points ({24 * n**3 / 1e9:.1f} GB of coordinates); "
                         f"at most {MAX_GRID_POINTS:,} are sampled (resolution {_MAX_RESOLUTION})")
    return n


def feasible_in_chunks(feasible: Any, points: np.ndarray) -> np.ndarray:
    """``feasible(points)`` (k,) bool, evaluated FEASIBILITY_CHUNK points at a time (each
    pose's feasibility is its own, so the chunks change nothing but the memory used)."""
    out = np.empty(len(points), dtype=bool)
    for s in range(0, len(points), FEASIBILITY_CHUNK):
        out[s:s + FEASIBILITY_CHUNK] = feasible(points[s:s + FEASIBILITY_CHUNK])
    return out


def rotation_list(rotations: Any) -> list[Any]:
    """The orientations of a dextrous workspace: a sequence of 3 x 3 matrices or angle triples.

    One bare orientation is refused, because ``list()`` would read it as something else: a
    rotation matrix as three angle triples (its rows), an angle triple as three scalars."""
    if isinstance(rotations, np.ndarray) and rotations.shape == (3, 3) and np.all(np.isfinite(rotations)) \
            and np.allclose(rotations.T @ rotations, np.eye(3), atol=1e-9):
        raise ValueError("rotations is one 3 x 3 rotation matrix; pass [R] for one orientation "
                         "(its rows would be read as three angle triples)")
    if np.ndim(rotations) == 0:
        raise ValueError(f"rotations must be a sequence of orientations; got {rotations!r}")
    rots = list(rotations)
    if not rots:
        raise ValueError("rotations must hold at least one orientation")
    if all(np.ndim(r) == 0 for r in rots):
        raise ValueError(f"rotations looks like one angle triple {list(rots)}; pass [(alpha, beta, gamma)] "
                         "for one orientation")
    return rots


@dataclasses.dataclass(frozen=True)
class SpatialWorkspace:
    """A constant-orientation (or dextrous) workspace sampled on a 3-D grid of cell centres.

    ``mask`` has shape (n, n, n) indexed [ix, iy, iz]; ``points`` (n^3, 3) in the same
    (C) order; ``volume`` = feasible cells x cell volume.
    """

    mask: np.ndarray
    points: np.ndarray
    box: np.ndarray
    resolution: int

    @property
    def cell_volume(self) -> float:
        return float(np.prod((self.box[1] - self.box[0]) / self.resolution))

    @property
    def volume(self) -> float:
        return float(self.mask.sum()) * self.cell_volume

    @property
    def feasible_points(self) -> np.ndarray:
        return self.points[self.mask.ravel()]


def grid_points(box: Any, resolution: int) -> tuple[np.ndarray, np.ndarray]:
    """(box (2, 3), cell-centre points (n^3, 3)) of an axis-aligned box [[lo], [hi]]."""
    b = np.asarray(box, dtype=float)
    if b.shape != (2, 3) or not np.all(np.isfinite(b)) or np.any(b[1] <= b[0]):
        raise ValueError(f"box must be [[x0, y0, z0], [x1, y1, z1]] with x1 > x0 etc.; got {b.tolist()}")
    n = _resolution(resolution)
    axes = [b[0, d] + (np.arange(n) + 0.5) * (b[1, d] - b[0, d]) / n for d in range(3)]
    X, Y, Z = np.meshgrid(*axes, indexing="ij")
    return b, np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])


def ray_reach(feasible: Any, centre: Any, directions: Any, reach: float, tol: float = 1e-9) -> np.ndarray:
    """Distance to the first feasibility change along rays from a feasible ``centre``, by
    bisection, all rays at once (the spatial counterpart of the chord method's bisection).

    ``feasible`` maps points (k, 3) to (k,) bool. For each direction d (normalized) returns
    s in [0, reach], found by bisection to ``tol`` (s = reach where the end of the segment is
    feasible: the ray is then not cut within ``reach``). Exact for sets that are
    star-shaped about the centre; otherwise some crossing on the ray.
    """
    c = np.asarray(centre, dtype=float)
    D = np.atleast_2d(np.asarray(directions, dtype=float))
    if c.shape != (3,) or D.shape[1] != 3 or not (np.all(np.isfinite(c)) and np.all(np.isfinite(D))):
        raise ValueError("centre must be 3 finite coordinates and directions a finite (k, 3) array")
    norms = np.linalg.norm(D, axis=1, keepdims=True)
    if np.any(norms == 0):
        raise ValueError("directions must be non-zero vectors")
    D = D / norms
    if not (is_number(reach) and np.isfinite(reach) and reach > 0):
        raise ValueError(f"reach must be a positive length; got {reach!r}")
    if not (is_number(tol) and np.isfinite(tol) and tol > 0):  # tol <= 0: the bisection never ends
        raise ValueError(f"tol must be a finite length > 0 (the bisection's interval); got {tol!r}")
    if not feasible(c[None])[0]:
        raise ValueError(f"centre {c.tolist()} is not in the workspace")
    lo, hi = np.zeros(len(D)), np.full(len(D), float(reach))
    out = ~feasible(c + hi[:, None] * D)
    lo[~out] = hi[~out]
    while np.any(out & (hi - lo > tol)):
        act = np.flatnonzero(out & (hi - lo > tol))
        mid = 0.5 * (lo[act] + hi[act])
        f = feasible(c + mid[:, None] * D[act])
        lo[act[f]] = mid[f]
        hi[act[~f]] = mid[~f]
    return lo


def ray_boundary(feasible: Any, centre: Any, directions: Any, reach: float, tol: float = 1e-9) -> np.ndarray:
    """Boundary points centre + s d along rays, s from `ray_reach` (same arguments)."""
    c = np.asarray(centre, dtype=float)
    D = np.atleast_2d(np.asarray(directions, dtype=float))
    s = ray_reach(feasible, c, D, reach, tol)
    return c + s[:, None] * (D / np.linalg.norm(D, axis=1, keepdims=True))


@dataclasses.dataclass(frozen=True)
class SpatialCableRobot:
    """A 6-dof cable robot with m >= 7 cables and tension limits t_min <= t_i <= t_max (N).

    Immutable, with read-only point arrays (copies of the ones given): a changed robot is a
    new one (``dataclasses.replace``), whose limits are checked again."""

    frame_points: Any
    platform_points: Any
    t_min: float = 1.0
    t_max: float = 100.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "frame_points", _points("frame_points", self.frame_points))
        object.__setattr__(self, "platform_points", _points("platform_points", self.platform_points))
        m = self.frame_points.shape[0]
        if self.platform_points.shape[0] != m:
            raise ValueError(f"frame_points has {m} rows but platform_points has {self.platform_points.shape[0]}")
        if m < 7:
            raise ValueError(f"a redundant spatial cable robot needs m >= 7 cables; got {m}")
        if not (is_number(self.t_min) and is_number(self.t_max) and np.isfinite(self.t_min)
                and np.isfinite(self.t_max) and 0 <= self.t_min < self.t_max):
            raise ValueError(f"need finite 0 <= t_min < t_max; got t_min={self.t_min!r}, t_max={self.t_max!r}")

    @property
    def m(self) -> int:
        return int(self.frame_points.shape[0])

    def structure_matrices(self, positions: Any, rotation: Any) -> np.ndarray:
        """Structure matrices (k, 6, m) at k positions (k, 3) for one orientation."""
        p = positions_array(positions)
        R = rotation_matrix(rotation)
        rb = self.platform_points @ R.T  # (m, 3) world-frame platform vectors R b_i
        d = self.frame_points[None] - p[:, None, :] - rb[None]  # (k, m, 3)
        u = d / np.linalg.norm(d, axis=2, keepdims=True)
        mom = np.cross(rb[None], u)
        return np.concatenate([np.swapaxes(u, 1, 2), np.swapaxes(mom, 1, 2)], axis=1)

    def structure_matrix(self, position: Any, rotation: Any) -> np.ndarray:
        """The 6 x m wrench (structure) matrix at one pose; see the module's conventions."""
        p = np.asarray(position, dtype=float)
        if p.shape != (3,):
            raise ValueError(f"position must be 3 coordinates; got shape {p.shape}")
        return self.structure_matrices(p[None], rotation)[0]

    @staticmethod
    def _wrench(wrench: Any) -> np.ndarray:
        w = np.asarray(wrench, dtype=float)
        if w.shape != (6,) or not np.all(np.isfinite(w)):
            raise ValueError(f"wrench must be 6 finite numbers [fx, fy, fz, mx, my, mz]; got shape {w.shape}")
        return w

    def tensions(self, position: Any, rotation: Any, wrench: Any, method: str = "l1",
                 backend: str = "vector") -> np.ndarray | None:
        """Tensions (m,) balancing ``wrench`` within the limits, or None if none exist.

        method: "l1" (6.19), "l2" (6.17) or "min-norm" (6.14). backend "vector" uses the
        exact basic-solution enumeration (l1, min-norm); an LP/QP backend of
        `solvers.convex` ("highs", "clarabel", "osqp", "linprog") solves the convex program.
        "l2" always goes to a QP backend ("clarabel" when backend is "vector").
        At a singular pose (S of rank < 6: the cables do not hold the platform in every
        direction) every backend returns None, as the enumeration does, so that feasibility
        never depends on the backend chosen.
        """
        if method not in METHODS:
            raise ValueError(f"unknown tension method {method!r}; valid: {', '.join(METHODS)}")
        S = self.structure_matrix(position, rotation)
        w = self._wrench(wrench)
        if method == "l2" and backend == "vector":
            backend = "clarabel"
        if backend == "vector" or method == "min-norm":
            feas, T = distribute6(S[None], w[None], self.t_min, self.t_max, method)
            return T[0] if feas[0] else None
        from solvers.convex import solve_lp, solve_qp

        if not full_rank6(S[None])[0]:  # the enumeration's rank test (null_space_form), per pose
            return None
        lb, ub = np.full(self.m, self.t_min), np.full(self.m, self.t_max)
        if method == "l1":
            res = solve_lp(np.ones(self.m), S, -w, lb, ub, backend=backend)
        else:
            res = solve_qp(S, -w, lb, ub, backend=backend)
        return None if res.x is None or res.feasible is not True else np.clip(res.x, self.t_min, self.t_max)

    def feasible(self, positions: Any, rotation: Any, wrench: Any) -> np.ndarray:
        """Wrench feasibility (k,) bool at k positions for one orientation, exactly."""
        S = self.structure_matrices(positions, rotation)
        return distribute6(S, self._wrench(wrench), self.t_min, self.t_max, "l1", need_tensions=False)[0]

    def workspace(self, rotation: Any, wrench: Any, box: Any, resolution: int = 30) -> SpatialWorkspace:
        """The constant-orientation wrench-feasible workspace on a resolution^3 grid."""
        b, pts = grid_points(box, resolution)
        mask = feasible_in_chunks(lambda P: self.feasible(P, rotation, wrench), pts).reshape((int(resolution),) * 3)
        return SpatialWorkspace(mask, pts, b, int(resolution))

    def dextrous_workspace(self, rotations: Any, wrench: Any, box: Any, resolution: int = 30) -> SpatialWorkspace:
        """Positions feasible at every orientation in ``rotations`` (the spatial form of
        the thesis's dextrous workspace, Algorithm 5.1): intersection of the masks."""
        rots = rotation_list(rotations)
        b, pts = grid_points(box, resolution)
        ok = np.ones(len(pts), dtype=bool)
        for R in rots:  # only the still-feasible points are re-tested
            idx = np.flatnonzero(ok)
            ok[idx] = feasible_in_chunks(lambda P, R=R: self.feasible(P, R, wrench), pts[idx])
        return SpatialWorkspace(ok.reshape((int(resolution),) * 3), pts, b, int(resolution))

    def boundary_points(self, rotation: Any, wrench: Any, centre: Any, directions: Any,
                        reach: float, tol: float = 1e-9) -> np.ndarray:
        """Boundary points by bisection along rays from a feasible ``centre`` (the spatial
        counterpart of the thesis's chord method), all rays at once.

        For each unit direction d (k, 3) returns centre + s d with s the first feasibility
        change found by bisection on [0, reach] to ``tol`` (s = reach where the whole ray
        segment is feasible). Assumes the feasible set is star-shaped about the centre.
        """
        return ray_boundary(lambda P: self.feasible(P, rotation, wrench), centre, directions, reach, tol)

    def __repr__(self) -> str:
        return f"SpatialCableRobot(m={self.m}, t_min={self.t_min}, t_max={self.t_max})"
