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

from ._checks import finite_rows
from .workspace import Workspace, check_closed, chord_boundary, open_policy
from .workspace._polygon import as_points

__all__ = ["RPR2", "CONSTRAINT_NAMES", "inverse_condition", "lens_area"]

CONSTRAINT_NAMES = ("l1 >= l1_min", "l1 <= l1_max", "l2 >= l2_min", "l2 <= l2_max", "y >= yA")


REFINE = 3  # halvings of the chord when a trace misses the radiating point (`RPR2.workspace`)


def inverse_condition(xA: float, yA: float, xB: float, U) -> np.ndarray:
    """kappa^-1 = det J = (y - yA)(xB - xA) / (l1 l2) (eq. 4.23, D.15) for any base
    (also xA == xB, where it is 0); NaN at the pivots.

    The value is signed.  J's rows are the legs' unit vectors e1 = (u - A) / l1 and
    e2 = (u - B) / l2 (`RPR2.jacobian`), so det J = e1 x e2 = sin of the angle from leg 1 to
    leg 2.  Its magnitude is the inverse condition number proper (in [0, 1]; with W = I/2
    (4.20) the weighted Frobenius condition number of J is 1 / |det J|), 0 where the legs
    are collinear (on the base line y = yA: a singular pose).  Its sign tells the assembly
    mode, i.e. the side of the base line: > 0 for y > yA with B right of A (xB > xA), the
    half-plane the workspace keeps (``y >= yA`` is one of its constraints); < 0 below the
    base line (the mirrored mode) or with B left of A.

    The objectives use the signed value, not its absolute value: `min_inverse_condition`
    (`manipulators.objectives`) takes the signed minimum over the prescribed boundary (NaN
    counts as -inf), suite rpr2's P objective is minus that minimum, and the exact P problem
    (`synthesis.rpr2_exact`) constrains kappa^-1 - t >= 0 with the signed value.  A prescribed
    workspace reaching below the base line, or a design with xB < xA, therefore scores
    kappa^-1 < 0, worse than any design with the workspace above it, rather than being
    rewarded for its mirror image.  (The 3-RPR's kappa^-1, `manipulators._rpr3_kinematics`,
    is unsigned: 3 |det J| / (||J||_F ||adj J||_F).)
    """
    U = as_points(U, "U")
    finite_rows(U, "positions U")
    dy = U[:, 1] - yA
    with np.errstate(divide="ignore", invalid="ignore"):
        return dy * (xB - xA) / (np.hypot(U[:, 0] - xA, dy) * np.hypot(U[:, 0] - xB, dy))


def lens_area(r, R, c) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Area L(r, R, c) of the intersection of two disks of radii r, R whose centres are c
    apart, and its derivatives (dL/dr, dL/dR, dL/dc); vectorized (broadcasting).

    With alpha, beta the half-angles of the arcs of each circle that lie inside the other,
    cos alpha = (c^2 + r^2 - R^2) / (2 c r): L = r^2 alpha + R^2 beta - c r sin alpha, and
    dL/dr = 2 r alpha, dL/dR = 2 R beta (arc lengths), dL/dc = -2 r sin alpha (the common
    chord). Disjoint disks (c >= r + R): 0; nested (c <= |R - r|): pi min(r, R)^2. L is C^1
    in (r, R, c) for c > 0 (alpha -> pi or 0 at the transitions).
    """
    r, R, c = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (r, R, c)))
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.arccos(np.clip((c * c + r * r - R * R) / (2 * c * r), -1.0, 1.0))
        b = np.arccos(np.clip((c * c + R * R - r * r) / (2 * c * R), -1.0, 1.0))
    far, nest = c >= r + R, c <= np.abs(R - r)
    a = np.where(far, 0.0, np.where(nest, np.where(r <= R, np.pi, 0.0), a))
    b = np.where(far, 0.0, np.where(nest, np.where(r <= R, 0.0, np.pi), b))
    h = r * np.sin(a)  # half the common chord (0 when disjoint or nested)
    return r * r * a + R * R * b - c * h, 2 * r * a, 2 * R * b, -2 * h


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
        set_ = lambda k, v: object.__setattr__(self, k, v)  # the dataclass is frozen
        for k in ("xA", "yA", "xB"):
            try:
                v = float(getattr(self, k))
            except (TypeError, ValueError):  # a string or an array: say which coordinate
                raise ValueError(f"RPR2: {k} must be one number, got {getattr(self, k)!r}") from None
            if not np.isfinite(v):
                raise ValueError(f"RPR2: {k} must be finite, got {v}")
            set_(k, v)
        try:
            lo = tuple(float(v) for v in np.broadcast_to(np.asarray(self.l_min, dtype=float), (2,)))
            hi = tuple(float(v) for v in np.broadcast_to(np.asarray(self.l_max, dtype=float), (2,)))
        except ValueError:  # NumPy's broadcast message names no leg limit
            raise ValueError(f"RPR2: l_min and l_max must each be a number or two numbers (one per leg), got "
                             f"l_min={self.l_min!r}, l_max={self.l_max!r}") from None
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

        Vectorized; NaN where the two circles do not meet above the base line, and where a
        leg length is negative or NaN (no pose has it).
        """
        l1 = np.asarray(l1, dtype=float)
        l2 = np.asarray(l2, dtype=float)
        try:
            np.broadcast_shapes(l1.shape, l2.shape)
        except ValueError:
            raise ValueError(f"RPR2.forward: leg lengths l1 of shape {l1.shape} and l2 of shape {l2.shape} do not "
                             "broadcast; give one length per pose in each") from None
        with np.errstate(invalid="ignore"):
            bad = ~((l1 >= 0) & (l2 >= 0))  # a negative length squares to a valid one: refuse it
        if bad.any():
            l1, l2 = np.where(bad, np.nan, l1), np.where(bad, np.nan, l2)
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
        """kappa^-1 = det J = (y - yA)(xB - xA) / (l1 l2) (eq. 4.23, D.15), W = I/2 (4.20).

        Signed: > 0 above the base line (for xB > xA), < 0 below it, 0 on it; see the module
        function `inverse_condition` for what the sign means and how the objectives use it."""
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

    def workspace(self, chord: float = 0.1, *, on_open: str = "warn", **kw) -> Workspace:
        """The workspace above the base line by the chord method (Appendix C).

        Keyword arguments go to `manipulators.workspace.chord_boundary`. An empty
        workspace (no leg-length pair reaches above the base line) gives
        ``Workspace.empty()`` with ``info["reason"]``. A trace that does not close even at
        the refined chords warns, raises or passes by ``on_open`` (`check_closed`).
        """
        u0 = self.interior_point()
        if u0 is None:
            return Workspace.empty(reason="no point above the base line satisfies the leg limits")
        kw.setdefault("jacobian", self.constraint_jacobian)
        open_policy(on_open)
        kw["on_open"] = "ignore"  # judged once, on the last trace
        ws = chord_boundary(self.constraints, u0, chord, **kw)
        # A trace of a simply connected region must close around the radiating point u0.
        # Where the region is narrower than the chord (the sharp tips of a thin crescent)
        # a chord can jump across it and the trace turns back on itself, enclosing a
        # sliver that misses u0 (measured: area 0.001 for an exact 4.92 at d = 0.5). Such
        # a trace is redone at half the chord, up to `REFINE` times [OWN: Appendix C
        # assumes d small against the workspace's features].
        d = float(chord)
        for _ in range(REFINE):
            if ws.info.get("closed") and ws.n_boundary >= 3 and bool(ws.contains(u0[None, :])[0]):
                break
            d *= 0.5
            ws = chord_boundary(self.constraints, u0, d, **kw)
            ws.info["refined_from"] = float(chord)  # type: ignore[index]  # a dict, read-only to users
        return check_closed(ws, on_open, stacklevel=3)

    def exact_area(self, grad: bool = False):
        """Closed-form area of the workspace above the base line (the thesis's W_c,
        Section 4.3 and Appendix D; eqs. 4.4 and 4.13 with y >= yA).

        The 2-RPR workspace is the intersection of the annuli A_i = disk(l_i^max) minus
        disk(l_i^min) about the pivots A and B, both on the base line c = |xB - xA| apart, so
        by inclusion-exclusion of disk-disk lens areas L (`lens_area`)
        area(A1 n A2) = L(R1, R2) - L(R1, r2) - L(r1, R2) + L(r1, r2)  (r = l^min, R = l^max),
        and the region is mirrored about the base line: W_c is half of it.

        ``grad=True`` also returns the gradient with respect to
        (xA, yA, xB, l1_min, l2_min, l1_max, l2_max) (yA does not enter: 0).
        """
        c = abs(self.xB - self.xA)
        (r1, r2), (R1, R2) = self.l_min, self.l_max
        L, dr, dR, dc = lens_area([R1, R1, r1, r1], [R2, r2, R2, r2], c)
        s = np.array([0.5, -0.5, -0.5, 0.5])  # inclusion-exclusion signs, halved
        area = float(s @ L)
        if not grad:
            return area
        g = s * dr, s * dR, s @ dc  # per lens: d/d(first radius), d/d(second radius)
        sgn = np.sign(self.xB - self.xA)
        return area, np.array([-sgn * g[2], 0.0, sgn * g[2],
                               g[0][2] + g[0][3], g[1][1] + g[1][3],  # r1 is lens 3, 4's first; r2 lens 2, 4's second
                               g[0][0] + g[0][1], g[1][0] + g[1][2]])

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
