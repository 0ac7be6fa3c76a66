"""The planar 2-RPR parallel manipulator of thesis Chapter 4 (Fig. 4.1).

Two linear actuators of lengths l1, l2 pivot at the base points A = (xA, yA) and
B = (xB, yB), yB = yA, and meet at the working point P = u = (x, y). Leg limits
l_i^min <= l_i <= l_i^max (eq. 4.4). The workspace is mirrored about the base line; as in
the thesis (Appendix D, ERRATA) only the part above it (y > yA, where kappa^-1 > 0) is used,
so y_A - y <= 0 is simply one of the workspace constraints.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import shapely

from .workspace import Workspace, chord_boundary
from .workspace._polygon import as_points

__all__ = ["RPR2", "CONSTRAINT_NAMES", "inverse_condition"]

CONSTRAINT_NAMES = ("l1 >= l1_min", "l1 <= l1_max", "l2 >= l2_min", "l2 <= l2_max", "y >= yA")


REFINE = 3  # halvings of the chord when a trace misses the radiating point (`RPR2.workspace`)


def inverse_condition(xA: float, yA: float, xB: float, U) -> np.ndarray:
    """kappa^-1 = det J = (y - yA)(xB - xA) / (l1 l2) (eq. 4.23, D.15) for any base
    (also xA == xB, where it is 0); NaN at the pivots."""
    U = as_points(U, "U")
    dy = U[:, 1] - yA
    with np.errstate(divide="ignore", invalid="ignore"):
        return dy * (xB - xA) / (np.hypot(U[:, 0] - xA, dy) * np.hypot(U[:, 0] - xB, dy))


@dataclasses.dataclass(frozen=True)
class RPR2:
    """A 2-RPR manipulator design (thesis Section 4.3).

    Parameters
    ----------
    xA, yA, xB : base pivot coordinates (yB = yA).
    l_min, l_max : (l1, l2) actuator limits (eq. 4.4); 0 < l_min < l_max.

    Raises
    ------
    ValueError : non-finite values, xA == xB (singular everywhere), l_min <= 0 or
        l_min >= l_max.
    """

    xA: float
    yA: float
    xB: float
    l_min: tuple[float, float] = (4.0, 4.0)
    l_max: tuple[float, float] = (7.0, 7.0)

    def __post_init__(self) -> None:
        set_ = lambda k, v: object.__setattr__(self, k, v)  # noqa: E731  (frozen)
        for k in ("xA", "yA", "xB"):
            v = float(getattr(self, k))
            if not np.isfinite(v):
                raise ValueError(f"RPR2: {k} must be finite, got {v}")
            set_(k, v)
        lo = tuple(float(v) for v in np.broadcast_to(np.asarray(self.l_min, dtype=float), (2,)))
        hi = tuple(float(v) for v in np.broadcast_to(np.asarray(self.l_max, dtype=float), (2,)))
        if not all(np.isfinite(lo + hi)):
            raise ValueError(f"RPR2: leg limits must be finite, got l_min={lo}, l_max={hi}")
        if min(lo) <= 0:
            raise ValueError(f"RPR2: l_min must be > 0, got {lo}")
        if lo[0] >= hi[0] or lo[1] >= hi[1]:
            raise ValueError(f"RPR2: need l_min < l_max for both legs, got l_min={lo}, l_max={hi}")
        if self.xA == self.xB:
            raise ValueError("RPR2: xA == xB puts both pivots at one point (singular everywhere)")
        set_("l_min", lo)
        set_("l_max", hi)

    @property
    def yB(self) -> float:
        return self.yA

    @property
    def A(self) -> np.ndarray:
        return np.array([self.xA, self.yA])

    @property
    def B(self) -> np.ndarray:
        return np.array([self.xB, self.yA])

    # ---------------------------------------------------------------- kinematics
    def leg_lengths(self, U) -> np.ndarray:
        """Inverse kinematics (D.1): leg lengths (l1, l2) at points U (k, 2) -> (k, 2)."""
        U = as_points(U, "U")
        dy = U[:, 1] - self.yA
        return np.column_stack((np.hypot(U[:, 0] - self.xA, dy), np.hypot(U[:, 0] - self.xB, dy)))

    def forward(self, l1, l2) -> np.ndarray:
        """Forward kinematics: the point above the base line with leg lengths l1, l2.

        Vectorized; NaN where the two circles do not meet above the base line.
        """
        l1 = np.asarray(l1, dtype=float)
        l2 = np.asarray(l2, dtype=float)
        x = self.xA + (l1**2 - l2**2 + (self.xB - self.xA) ** 2) / (2.0 * (self.xB - self.xA))
        h2 = l1**2 - (x - self.xA) ** 2
        with np.errstate(invalid="ignore"):
            y = self.yA + np.sqrt(np.where(h2 > 0, h2, np.nan))
        return np.stack((x, y), axis=-1)

    def jacobian(self, U) -> np.ndarray:
        """Manipulator Jacobian J = -J_v^{-1} J_u (eq. 4.22, D.6) at U: shape (k, 2, 2)."""
        U = as_points(U, "U")
        L = self.leg_lengths(U)
        J = np.empty((U.shape[0], 2, 2))
        J[:, 0, 0] = (U[:, 0] - self.xA) / L[:, 0]
        J[:, 0, 1] = (U[:, 1] - self.yA) / L[:, 0]
        J[:, 1, 0] = (U[:, 0] - self.xB) / L[:, 1]
        J[:, 1, 1] = (U[:, 1] - self.yB) / L[:, 1]
        return J

    def inverse_condition(self, U) -> np.ndarray:
        """kappa^-1 = det J = (y - yA)(xB - xA) / (l1 l2) (eq. 4.23, D.15), W = I/2 (4.20)."""
        return inverse_condition(self.xA, self.yA, self.xB, U)

    # --------------------------------------------------------------- workspace
    def constraints(self, U) -> np.ndarray:
        """Workspace constraints C(U) <= 0, shape (k, 5), in the order of CONSTRAINT_NAMES:
        leg limits (4.4) and the base line y >= yA."""
        if not (type(U) is np.ndarray and U.ndim == 2 and U.shape[1] == 2):  # hot path: skip checks
            U = as_points(U, "U")
        x, dy = U[:, 0], U[:, 1] - self.yA
        dy2 = dy * dy
        l1 = x - self.xA
        l1 *= l1
        l1 += dy2
        np.sqrt(l1, out=l1)
        l2 = x - self.xB
        l2 *= l2
        l2 += dy2
        np.sqrt(l2, out=l2)
        C = np.empty((U.shape[0], 5))
        np.subtract(self.l_min[0], l1, out=C[:, 0])
        np.subtract(l1, self.l_max[0], out=C[:, 1])
        np.subtract(self.l_min[1], l2, out=C[:, 2])
        np.subtract(l2, self.l_max[1], out=C[:, 3])
        np.negative(dy, out=C[:, 4])
        return C

    def constraint_jacobian(self, U) -> np.ndarray:
        """Derivatives of `constraints` with respect to (x, y): shape (k, 5, 2)."""
        U = as_points(U, "U")
        L = self.leg_lengths(U)
        g1 = np.column_stack((U[:, 0] - self.xA, U[:, 1] - self.yA)) / L[:, :1]
        g2 = np.column_stack((U[:, 0] - self.xB, U[:, 1] - self.yB)) / L[:, 1:]
        J = np.zeros((U.shape[0], 5, 2))
        J[:, 0], J[:, 1], J[:, 2], J[:, 3] = -g1, g1, -g2, g2
        J[:, 4, 1] = -1.0
        return J

    def interior_point(self, n: int = 9) -> np.ndarray | None:
        """A point inside the workspace (Appendix C.4), or None if the workspace above
        the base line is empty.

        The pose with mid-range leg lengths (eq. C.7) if it is strictly inside; otherwise
        forward kinematics over an n x n grid of leg lengths inside the limits, keeping the
        point with the largest margin min_j(-C_j).
        """
        # (C.7): the point with both legs at mid-range, v = (v_min + v_max)/2. It moves
        # continuously with the design, so the whole chord trace (and every discretized
        # objective) does too; a grid argmax would jump between grid points and put
        # steps of ~1e-3 into f (finite differences of 1e-5 then read gradients of ~1e2).
        mid = self.forward(0.5 * (self.l_min[0] + self.l_max[0]), 0.5 * (self.l_min[1] + self.l_max[1]))
        if np.all(np.isfinite(mid)) and np.all(self.constraints(mid[None, :]) < 0):
            return mid
        # otherwise (no mid-range pose above the base line): the best of a grid of leg lengths
        f = (np.arange(n) + 0.5) / n
        l1 = self.l_min[0] + f * (self.l_max[0] - self.l_min[0])
        l2 = self.l_min[1] + f * (self.l_max[1] - self.l_min[1])
        L1, L2 = np.meshgrid(l1, l2)
        P = self.forward(L1.ravel(), L2.ravel())
        P = P[np.all(np.isfinite(P), axis=1)]
        if P.shape[0] == 0:
            return None
        margin = np.min(-self.constraints(P), axis=1)
        k = int(np.argmax(margin))
        return P[k] if margin[k] > 0 else None

    def workspace(self, chord: float = 0.1, **kw) -> Workspace:
        """The workspace above the base line by the chord method (Appendix C).

        Keyword arguments go to `manipulators.workspace.chord_boundary`. An empty
        workspace (no leg-length pair reaches above the base line) gives
        ``Workspace.empty()`` with ``info["reason"]``.
        """
        u0 = self.interior_point()
        if u0 is None:
            return Workspace.empty(reason="no point above the base line satisfies the leg limits")
        kw.setdefault("jacobian", self.constraint_jacobian)
        ws = chord_boundary(self.constraints, u0, chord, **kw)
        # A trace of a simply connected region must close around the radiating point u0.
        # Where the region is narrower than the chord (the sharp tips of a thin crescent)
        # a chord can jump across it and the trace turns back on itself, enclosing a
        # sliver that misses u0 (measured: area 0.001 for an exact 4.92 at d = 0.5). Such
        # a trace is redone at half the chord, up to `REFINE` times [OWN: Appendix C
        # assumes d small against the workspace's features].
        d = float(chord)
        for k in range(REFINE):
            if ws.info.get("closed") and ws.n_boundary >= 3 and bool(ws.contains(u0[None, :])[0]):
                break
            d *= 0.5
            ws = chord_boundary(self.constraints, u0, d, **kw)
            ws.info["refined_from"] = float(chord)
        return ws

    def exact_region(self, quad_segs: int = 1024) -> shapely.Geometry:
        """The exact workspace (two annuli intersected, above the base line) as a shapely
        geometry; circles by polygons of 4*quad_segs sides (relative area error ~ 1e-7 at
        the default)."""
        A = shapely.Point(self.xA, self.yA)
        B = shapely.Point(self.xB, self.yB)
        ring_a = A.buffer(self.l_max[0], quad_segs=quad_segs).difference(A.buffer(self.l_min[0], quad_segs=quad_segs))
        ring_b = B.buffer(self.l_max[1], quad_segs=quad_segs).difference(B.buffer(self.l_min[1], quad_segs=quad_segs))
        big = max(self.l_max) + abs(self.xB - self.xA) + 1.0
        upper = shapely.box(min(self.xA, self.xB) - big, self.yA, max(self.xA, self.xB) + big, self.yA + big)
        return ring_a.intersection(ring_b).intersection(upper)
