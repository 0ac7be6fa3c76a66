"""The 3-RPR planar parallel manipulator of thesis Chapter 5.

`RPR3` holds one design ``d = [x_C, y_C, x_D, x_E, r]`` (eq. 5.36) with its actuator
limits and offers, vectorized over poses:

* inverse kinematics (eq. 5.7), the normalized Jacobian (eq. 5.13) and ``kappa^-1``
  (eqs. 4.19-4.20, ``W = I/3``);
* constraint functions ``C(U) <= 0`` for the constant-orientation (eq. 5.14), dextrous
  (eq. 5.22) and maximal (eq. C.4) workspaces;
* the orientation workspace ``[w_min, w_max]`` of a point (eq. 5.26), in closed form
  (default) or by the thesis's numerical optimization;
* the workspaces themselves, traced by the shared chord method
  (`manipulators.workspace.chord_boundary`): `workspace`, `dextrous_workspace`
  (Algorithm 5.1) and `maximal_workspace` (Appendix C).  The point-set logic lives in
  `manipulators._rpr3_workspaces`.

Assembly branch.  With ``y_C = y_D = y_E`` the mechanism's workspaces are (for phi = 0
exactly, otherwise nearly) mirrored about the base line; as for the 2-RPR (ERRATA.md) the
workspace reported is the part with ``y >= y_C`` (``branch="upper"``).  ``branch=None``
traces the whole connected component that contains the interior point instead.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from . import _orientation as orient
from ._checks import finite_rows, is_integer, is_number
from ._rpr3_kinematics import LEG_SIGN, inverse_condition, jacobian, leg_lengths
from .workspace import check_closed, open_policy

__all__ = ["RPR3", "M_DESIGNS", "DEFAULT_L_MIN", "DEFAULT_L_MAX"]

DEFAULT_L_MIN = (math.sqrt(2.0), math.sqrt(2.0), 1.0)  # Section 5.5.4 / 5.6.2
DEFAULT_L_MAX = (2.0, 2.0, math.sqrt(3.0))

#: Table 5.1 (its second printed "M2" row is M3, ERRATA.md): [x_C, y_C, x_D, x_E, r].
M_DESIGNS = {
    "M1": (-1.0, 0.0, 1.0, 2.0, 1.0),
    "M2": (-0.75, 0.0, 0.75, 1.5, 0.75),
    "M3": (-0.5, 0.0, 0.5, 1.0, 0.25),
}

_INACTIVE = -10.0  # value of an interior-extreme constraint column when no interior extreme exists


@dataclasses.dataclass(frozen=True)
class RPR3:
    """A 3-RPR design (Figure 5.1) with leg-length limits (eq. 5.3).

    Parameters
    ----------
    xC, yC : base joint C of leg 1 (``y_C = y_D = y_E``, Section 5.2).
    xD, xE : x-coordinates of base joints D (leg 2) and E (leg 3).
    r : platform half-length (> 0).
    l_min, l_max : leg-length limits; default ``(sqrt2, sqrt2, 1)`` and ``(2, 2, sqrt3)``
        (Sections 5.5.4, 5.6.2).
    """

    xC: float
    yC: float
    xD: float
    xE: float
    r: float
    l_min: tuple[float, float, float] = DEFAULT_L_MIN
    l_max: tuple[float, float, float] = DEFAULT_L_MAX

    def __post_init__(self) -> None:
        vals = (self.xC, self.yC, self.xD, self.xE, self.r)
        for k, v in zip(("xC", "yC", "xD", "xE", "r"), vals):
            if not is_number(v):
                raise ValueError(f"RPR3: {k} must be a number, got {v!r}")
        if not all(np.isfinite(float(v)) for v in vals):
            raise ValueError(f"RPR3: design [xC, yC, xD, xE, r] must be finite, got {list(vals)}")
        if not float(self.r) > 0.0:
            raise ValueError(f"RPR3: platform half-length r must be > 0, got {self.r}")
        lmin, lmax = _leg_limits(self.l_min, "l_min"), _leg_limits(self.l_max, "l_max")
        if any(not (0.0 <= a < b < np.inf) for a, b in zip(lmin, lmax)):
            raise ValueError(f"RPR3: need 0 <= l_min < l_max < inf per leg, got l_min={lmin}, l_max={lmax}")
        for k, v in (("xC", self.xC), ("yC", self.yC), ("xD", self.xD), ("xE", self.xE), ("r", self.r)):
            object.__setattr__(self, k, float(v))
        object.__setattr__(self, "l_min", lmin)
        object.__setattr__(self, "l_max", lmax)

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_design(cls, d, **limits) -> RPR3:
        """Build from the design vector ``d = [x_C, y_C, x_D, x_E, r]`` (eq. 5.36)."""
        d = np.asarray(d, dtype=float).ravel()
        if d.shape != (5,):
            raise ValueError(f"RPR3.from_design: d must have 5 entries [xC, yC, xD, xE, r], got {d.shape}")
        return cls(*d, **limits)

    @classmethod
    def named(cls, name: str) -> RPR3:
        """Design M1, M2 or M3 of Table 5.1 with the Section 5.5.4 leg limits."""
        if name not in M_DESIGNS:
            raise ValueError(f"unknown design {name!r}; valid: {', '.join(M_DESIGNS)}")
        return cls(*M_DESIGNS[name])

    @property
    def design(self) -> np.ndarray:
        return np.array([self.xC, self.yC, self.xD, self.xE, self.r])

    @property
    def base(self) -> np.ndarray:
        """Base joints C, D, E as rows, shape (3, 2)."""
        return np.array([[self.xC, self.yC], [self.xD, self.yC], [self.xE, self.yC]])

    @property
    def lmin(self) -> np.ndarray:
        return np.asarray(self.l_min)

    @property
    def lmax(self) -> np.ndarray:
        return np.asarray(self.l_max)

    # ------------------------------------------------------------------ kinematics
    def leg_lengths(self, U, phi) -> np.ndarray:
        """Inverse kinematics ``v(u, phi)``, shape (k, 3) (eq. 5.7)."""
        return leg_lengths(self.base, self.r, U, phi)

    def jacobian(self, U, phi) -> np.ndarray:
        """Normalized Jacobian of eq. (5.13), shape (k, 3, 3)."""
        return jacobian(self.base, self.r, U, phi)

    def inverse_condition(self, U, phi) -> np.ndarray:
        """``kappa^-1`` (eqs. 4.19-4.20 with ``W = I/3``) at poses ``(U, phi)``, shape (k,)."""
        return inverse_condition(self.jacobian(U, phi))

    # ------------------------------------------------------------------ constraints
    def constraints(self, U, phi, *, branch: str | None = "upper") -> np.ndarray:
        """Constant-orientation constraints, feasible iff all ``<= 0`` (eqs. 5.9, 5.14).

        Columns: ``l_i - l_i^max`` (i = 1..3), ``l_i^min - l_i`` (i = 1..3), and with
        ``branch="upper"`` a seventh column ``y_C - y``.
        """
        U = _points(U)
        if np.ndim(phi) == 0:
            # fixed orientation (the chord method's hot path): each leg constrains u to an
            # annulus about c_i = b_i - s_i r e(phi); a few broadcast operations
            e = np.array([math.cos(phi), math.sin(phi)])
            centres = self.base - (LEG_SIGN * self.r)[:, None] * e[None, :]
            dx = U[:, 0:1] - centres[None, :, 0]
            dy = U[:, 1:2] - centres[None, :, 1]
            v = np.sqrt(dx * dx + dy * dy)
        else:
            v = self.leg_lengths(U, phi)
        out = np.empty((U.shape[0], 7 if branch == "upper" else 6))
        np.subtract(v, self.lmax, out=out[:, 0:3])
        np.subtract(self.lmin, v, out=out[:, 3:6])
        if branch == "upper":
            np.subtract(self.yC, U[:, 1], out=out[:, 6])
        elif branch is not None:
            raise ValueError(f"branch must be 'upper' or None, got {branch!r}")
        return out

    def _cosine_legs(self, U):
        U = _points(U)
        return [orient.cosine_leg(U, self.base[i], LEG_SIGN[i], self.r) for i in range(3)]

    def dextrous_constraints(self, U, phi_min: float, phi_max: float, *, branch: str | None = "upper") -> np.ndarray:
        """Closed-form dextrous-workspace constraints (eq. 5.22), feasible iff all ``<= 0``.

        ``u`` is dextrous iff every leg stays within its limits for every ``w`` in
        ``[phi_min, phi_max]``.  ``l_i^2(w) = P + Q cos(w - alpha)`` (see `_orientation`),
        so its extremes over the range are at the ends or at a critical angle inside.
        Columns, per leg i (18 in all, + 1 for the branch):

        * 0-5:  ``l_i(u, phi_min) - l_i^max``, ``l_i^min - l_i(u, phi_min)``;
        * 6-11: the same at ``phi_max``;
        * 12-17: ``max_w l_i - l_i^max`` and ``l_i^min - min_w l_i`` when that extreme is
          attained strictly inside the range, else an inactive constant (-10).

        Every boundary point has an active column; the column tells which leg, which
        limit and which extreme orientation, which is how bifurcation points are typed
        (type I: same orientation, Section 5.5.3; type II: orientation changes).
        """
        phi_min, phi_max = _orientation_range_args(phi_min, phi_max)
        U = _points(U)
        ends = [self.leg_lengths(U, p) for p in (phi_min, phi_max)]
        cols = [ends[0] - self.lmax, self.lmin - ends[0], ends[1] - self.lmax, self.lmin - ends[1]]
        imax, imin = [], []
        for i, (P, Q, alpha) in enumerate(self._cosine_legs(U)):
            _, _, min_int, max_int = orient.cos_extremes_on_interval(alpha, phi_min, phi_max)
            imax.append(np.where(max_int, np.sqrt(P + Q) - self.lmax[i], _INACTIVE))
            imin.append(np.where(min_int, self.lmin[i] - np.sqrt(np.maximum(P - Q, 0.0)), _INACTIVE))
        cols += [np.stack(imax, axis=1), np.stack(imin, axis=1)]
        if branch == "upper":
            cols.append((self.yC - U[:, 1])[:, None])
        elif branch is not None:
            raise ValueError(f"branch must be 'upper' or None, got {branch!r}")
        return np.concatenate(cols, axis=1)

    def orientation_constraints(self, U, phi_min: float, phi_max: float, *, method: str = "closed") -> np.ndarray:
        """The thesis's dextrous constraints (5.30)-(5.31), split by leg.

        ``c1 = phi_max - w_max(u)`` and ``c2 = w_min(u) - phi_min``, where
        ``[w_min, w_max]`` is the orientation interval containing the mid-range
        orientation (so several orientation intervals are handled).  Since
        ``w_max = min_i w_max^i`` and ``w_min = max_i w_min^i`` over the legs' own
        intervals, the columns are ``c1^i = phi_max - w_max^i`` (i = 1..3) then
        ``c2^i = w_min^i - phi_min``: their maxima are c1 and c2, and the active column
        names the leg at its limit, which the thesis reads off the final constraint
        values of (5.31) to find type I bifurcation points (Section 5.5.3).  Where the
        mid-range orientation is unreachable for a leg its columns are ``pi``.

        method : ``"closed"`` (default) or ``"numeric"`` (the thesis's (5.26) per point;
            only c1 and c2 themselves, shape (k, 2), since it does not split by leg).
        """
        phi_min, phi_max = _orientation_range_args(phi_min, phi_max)
        w_mid = 0.5 * (phi_min + phi_max)
        if method == "numeric":
            w_lo, w_hi = self.orientation_range(U, w_ref=w_mid, method="numeric")
            c1 = np.where(np.isnan(w_hi), np.pi, phi_max - w_hi)
            c2 = np.where(np.isnan(w_lo), np.pi, w_lo - phi_min)
            return np.stack([c1, c2], axis=1)
        if method != "closed":
            raise ValueError(f"method must be 'closed' or 'numeric', got {method!r}")
        U = _points(U)
        w_ref = np.full(U.shape[0], w_mid)
        c1, c2 = [], []
        for i, (P, Q, alpha) in enumerate(self._cosine_legs(U)):
            lo, hi = orient.component_containing(P, Q, alpha, self.lmin[i], self.lmax[i], w_ref)
            c1.append(np.where(np.isnan(hi), np.pi, phi_max - np.minimum(hi, 1e3)))
            c2.append(np.where(np.isnan(lo), np.pi, np.maximum(lo, -1e3) - phi_min))
        return np.stack(c1 + c2, axis=1)

    def maximal_constraints(self, U, *, n_grid: int = 360, n_refine: int = 40) -> np.ndarray:
        """One column ``c(u) = min_w max_i viol_i(u, w)`` (eq. C.4): ``c <= 0`` iff some
        orientation satisfies every leg limit.

        The inner minimum over ``w`` is taken on a grid of ``n_grid`` orientations and
        refined by a vectorized golden-section search around the best grid angle; the
        sign is then made exact with the closed-form arc intersection (the intersection of
        the legs' allowed arcs is non-empty iff one of the arcs' end angles is allowed
        by all legs).
        """
        for name, v, least in (("n_grid", n_grid, 1), ("n_refine", n_refine, 0)):
            if not is_integer(v) or v < least:
                raise ValueError(f"maximal_constraints: {name} must be an integer >= {least}, got {v!r}")
        U = _points(U)
        legs = self._cosine_legs(U)

        def viol(w):  # w: (k, m) -> (k, m)
            out = None
            for i, (P, Q, alpha) in enumerate(legs):
                length = np.sqrt(np.maximum(P[:, None] + Q[:, None] * np.cos(w - alpha[:, None]), 0.0))
                vi = np.maximum(length - self.lmax[i], self.lmin[i] - length)
                out = vi if out is None else np.maximum(out, vi)
            return out

        grid = np.linspace(-np.pi, np.pi, n_grid, endpoint=False)[None, :]
        vals = viol(np.broadcast_to(grid, (U.shape[0], n_grid)))
        j = np.argmin(vals, axis=1)
        h = 2 * np.pi / n_grid
        a, b = grid[0, j] - h, grid[0, j] + h
        g = (np.sqrt(5.0) - 1.0) / 2.0
        for _ in range(n_refine):
            x1, x2 = b - g * (b - a), a + g * (b - a)
            f1, f2 = viol(x1[:, None])[:, 0], viol(x2[:, None])[:, 0]
            left = f1 < f2
            b = np.where(left, x2, b)
            a = np.where(left, a, x1)
        best = np.minimum(viol((0.5 * (a + b))[:, None])[:, 0], vals.min(axis=1))
        # exact sign from arc end angles: candidates are the legs' arc ends
        cand = []
        for i, (P, Q, alpha) in enumerate(legs):
            a_lo, a_hi, _ = orient._half_widths(P, Q, self.lmin[i], self.lmax[i])
            cand += [alpha + a_lo, alpha - a_lo, alpha + a_hi, alpha - a_hi]
        cand = np.stack(cand, axis=1)
        cv = viol(cand).min(axis=1)
        return np.minimum(best, cv)[:, None]

    # ------------------------------------------------------------------ orientation workspace
    def orientation_range(self, U, w_ref=0.0, *, method: str = "closed"):
        """Orientation workspace ``[w_min(u), w_max(u)]`` (eqs. 5.24-5.26), vectorized.

        Returns the interval of reachable orientations that contains ``w_ref`` (the
        thesis's ``w^ave``): ``(nan, nan)`` where ``w_ref`` itself is unreachable,
        ``(-inf, inf)`` where every orientation is.

        method : ``"closed"`` (default) intersects each leg's allowed arcs analytically
            (`manipulators._orientation`); ``"numeric"`` solves the thesis's problem
            (5.26), ``max (w - w_ave)^2`` subject to the leg limits, from a start just
            above / below ``w_ave`` with SciPy's SLSQP, one point at a time (slow; for
            comparison).
        """
        U = _points(U, finite=True)
        try:
            w_ref = np.broadcast_to(np.asarray(w_ref, dtype=float), (U.shape[0],))
        except ValueError:
            raise ValueError(f"orientation_range: w_ref must be a number or one per point ({U.shape[0]},), "
                             f"got shape {np.shape(w_ref)}") from None
        if not np.all(np.isfinite(w_ref)):
            raise ValueError(f"orientation_range: w_ref must be finite (radians), got {w_ref[~np.isfinite(w_ref)][:3]}")
        if method == "numeric":
            return self._orientation_range_numeric(U, w_ref)
        if method != "closed":
            raise ValueError(f"orientation_range method must be 'closed' or 'numeric', got {method!r}")
        lo = np.full(U.shape[0], -np.inf)
        hi = np.full(U.shape[0], np.inf)
        for i, (P, Q, alpha) in enumerate(self._cosine_legs(U)):
            a, b = orient.component_containing(P, Q, alpha, self.lmin[i], self.lmax[i], w_ref)
            lo = np.maximum(lo, a)  # NaN propagates: unreachable w_ref
            hi = np.minimum(hi, b)
        return lo, hi

    def _orientation_range_numeric(self, U, w_ref):
        from scipy.optimize import minimize

        lo = np.full(U.shape[0], np.nan)
        hi = np.full(U.shape[0], np.nan)
        for k, (u, w0) in enumerate(zip(U, w_ref)):
            def cons(w, u=u):
                v = self.leg_lengths(u, w[0])[0]
                return np.concatenate([self.lmax - v, v - self.lmin])  # SciPy: >= 0

            if np.any(cons(np.array([w0])) < 0):
                continue
            for sgn in (1.0, -1.0):
                res = minimize(
                    lambda w, w0=w0: -((w[0] - w0) ** 2),
                    np.array([w0 + sgn * 1e-3]),
                    jac=lambda w, w0=w0: np.array([-2.0 * (w[0] - w0)]),
                    method="SLSQP",
                    constraints=[{"type": "ineq", "fun": cons}],
                    bounds=[(w0, w0 + np.pi)] if sgn > 0 else [(w0 - np.pi, w0)],
                    options={"ftol": 1e-12, "maxiter": 200},
                )
                (hi if sgn > 0 else lo)[k] = res.x[0]
        return lo, hi

    def orientation_intervals(self, u) -> list[tuple[float, float]]:
        """All reachable orientation intervals at one point ``u`` (subsets of [-pi, pi])."""
        u = _points(u, finite=True)
        if u.shape[0] != 1:
            raise ValueError(f"orientation_intervals takes one point (shape (2,)), got {u.shape[0]} points")
        per_leg = []
        for i, (P, Q, alpha) in enumerate(self._cosine_legs(u)):
            per_leg.append(orient.allowed_arcs(P[0], Q[0], alpha[0], self.lmin[i], self.lmax[i]))
        return orient.intersect_arcs(per_leg)

    def enclosing_orientations(self, U, *, tol: float = 0.0, branch: str | None = "upper") -> list[tuple[float, float]]:
        """Platform orientations ``phi`` at which *every* point of ``U`` is in ``W^C[phi]``.

        The intersection over the points of their orientation sets (eqs. 5.7, 5.26): for
        each point and leg ``l_i^2(w) = P + Q cos(w - alpha)`` (`_orientation`), so the
        leg limits (5.3) forbid at most two open arcs of ``w`` -- ``|w - alpha| < a_lo``
        (leg too long) and ``|w - alpha - pi| < pi - a_hi`` (too short).  The allowed set
        is the circle minus the union of all the points' forbidden arcs, computed by one
        sort and a running maximum (vectorized over points; exact, no sampling of ``w``).

        With ``U`` the boundary of a prescribed workspace W_p this is the set of phi at
        which W_p is enclosed in ``W^C[phi]`` (eq. 5.14): an annulus's hole (radius
        ``l_min >= 1``) cannot fit inside the small W_p, so W_p is in the annulus iff its
        boundary is (see `rpr3_exact.exact_optimum`).  MO synthesis (5.37) asks the
        slices to lie in this set, D synthesis (5.39) the whole range ``[phi_min,
        phi_max]`` (eq. 5.22).

        tol : leg-length slack; the limits become ``[l_min - tol, l_max + tol]``.
        branch : ``"upper"`` (default, as `constraints`): no orientation if a point has
            ``y < y_C``; ``None``: leg limits only.

        Returns disjoint intervals ``(lo, hi)`` of positive length in ``[-pi, pi]``
        (radians, sorted; a set containing phi = +-pi is split there).
        """
        U = _points(U, finite=True)
        if not (is_number(tol) and math.isfinite(tol)):
            raise ValueError(f"enclosing_orientations: tol must be a finite leg-length slack, got {tol!r}")
        if branch == "upper":
            if np.any(U[:, 1] < self.yC):
                return []
        elif branch is not None:
            raise ValueError(f"branch must be 'upper' or None, got {branch!r}")
        centres, halves = [], []
        for i, (P, Q, alpha) in enumerate(self._cosine_legs(U)):
            a_lo, a_hi, empty = orient._half_widths(P, Q, self.lmin[i] - tol, self.lmax[i] + tol)
            if np.any(empty):
                return []
            centres += [alpha, alpha + np.pi]
            halves += [a_lo, np.pi - a_hi]
        c, h = np.concatenate(centres), np.concatenate(halves)
        c, h = c[h > 0.0], h[h > 0.0]
        if np.any(h >= np.pi):
            return []
        lo = orient.wrap_pi(c - h)
        lo = np.where(lo >= np.pi, -np.pi, lo)  # [-pi, pi)
        hi = lo + 2.0 * h
        over = hi > np.pi  # split the arcs that cross +-pi
        lo = np.concatenate([lo, np.full(over.sum(), -np.pi)])
        hi = np.concatenate([np.minimum(hi, np.pi), hi[over] - 2.0 * np.pi])
        order = np.argsort(lo, kind="stable")
        lo, hi = lo[order], hi[order]
        reach = np.maximum.accumulate(hi)  # right end of the union so far
        gap_lo = np.concatenate([[-np.pi], reach])
        gap_hi = np.concatenate([lo, [np.pi]])
        keep = gap_hi > gap_lo
        return [(float(a), float(b)) for a, b in zip(gap_lo[keep], gap_hi[keep])]

    # ------------------------------------------------------------------ workspaces
    def workspace(self, phi: float = 0.0, chord: float = 0.02, *, on_open: str = "warn", **kw):
        """Constant-orientation workspace ``W^C[phi]`` by the chord method (Section 5.4).

        ``on_open``: a trace that does not close warns (default), raises or passes
        (`manipulators.workspace.check_closed`); the same for every workspace method below.
        """
        from ._rpr3_workspaces import constant_orientation_workspace

        open_policy(on_open)  # checked before the trace, applied to it after
        ws = constant_orientation_workspace(self, phi, chord, on_open="ignore", **kw)
        return check_closed(ws, on_open, stacklevel=3)

    def dextrous_workspace(self, phi_min: float, phi_max: float, chord: float = 0.02, *, on_open: str = "warn",
                           **kw):
        """Dextrous workspace ``W^D[phi_min, phi_max]`` by Algorithm 5.1."""
        from ._rpr3_workspaces import dextrous_workspace

        open_policy(on_open)  # checked before the trace, applied to it after
        ws = dextrous_workspace(self, phi_min, phi_max, chord, on_open="ignore", **kw)
        return check_closed(ws, on_open, stacklevel=3)

    def maximal_workspace(self, chord: float = 0.02, *, on_open: str = "warn", **kw):
        """Maximal (reachable) workspace ``W^M`` (eq. C.4) by the chord method (Appendix C)."""
        from ._rpr3_workspaces import maximal_workspace

        open_policy(on_open)  # checked before the trace, applied to it after
        ws = maximal_workspace(self, chord, on_open="ignore", **kw)
        return check_closed(ws, on_open, stacklevel=3)


def _points(U, *, finite: bool = False) -> np.ndarray:
    """Positions as (k, 2).  ``finite``: refuse NaN / inf rows, for the orientation sets, where
    a NaN point would silently drop out of the answer (the constraint functions, the chord
    method's hot path, return NaN rows for NaN points instead)."""
    U = np.asarray(U, dtype=float)
    if U.ndim == 1:
        U = U[None, :]
    if U.ndim != 2 or U.shape[1] != 2:
        raise ValueError(f"positions must have shape (k, 2) or (2,), got {U.shape}")
    return finite_rows(U, "positions") if finite else U


def _leg_limits(v, name: str) -> tuple[float, float, float]:
    """One limit per leg: a number (all three legs) or three numbers."""
    try:
        a = np.broadcast_to(np.asarray(v, dtype=float), (3,))
    except (TypeError, ValueError):
        raise ValueError(f"RPR3: {name} must be a number or three numbers (one per leg), got {v!r}") from None
    return tuple(float(x) for x in a)  # type: ignore[return-value]


def _orientation_range_args(phi_min, phi_max):
    phi_min, phi_max = float(phi_min), float(phi_max)
    if not (np.isfinite(phi_min) and np.isfinite(phi_max) and phi_min <= phi_max):
        raise ValueError(f"need finite phi_min <= phi_max (radians), got [{phi_min}, {phi_max}]")
    return phi_min, phi_max
