"""Workspace objectives of the synthesis formulations (thesis Sections 4.5-4.7, Appendix D).

* ``delta_areas``: the non-overlapping areas dW_p = area(W_p \\ W_c) and dW_c = area(W_c \\ W_p)
  by the thesis's triangle scheme (eq. 4.9, the four cases of Fig. 4.3), measured in polar
  coordinates about the prescribed workspace's centre O' at the polar angles beta_c^i of
  the computed boundary points. This is the discretized objective the thesis minimizes.
* ``delta_areas_exact``: the same areas from polygon geometry (shapely) against any
  geometry (for the 2-RPR the exact annulus intersection, `RPR2.exact_region`).
* ``enclosure_constraint``: the constraint function g(d) of eq. (4.16).
* ``min_inverse_condition``: min kappa^-1 over the prescribed boundary (Appendix D: for the
  2-RPR the minimum over W_p lies on its boundary), at the thesis's points b_p^i or densely.

Generic: used by the 2-RPR and the 3-RPR synthesis suites.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import shapely

from .prescribed import Prescribed
from .workspace import Workspace
from .workspace._polygon import as_points, to_shapely

__all__ = ["triangle_area", "polar_angles", "delta_areas", "delta_areas_checked", "delta_areas_exact",
           "star_shaped", "enclosure_constraint", "min_inverse_condition", "radial_gaps"]


def triangle_area(L, M, N) -> np.ndarray:
    """A(L, M, N) = |M_x N_y + N_x L_y + L_x M_y - M_x L_y - L_x N_y - N_x M_y| / 2 (eq. 4.9),
    vectorized over rows of (k, 2) arrays."""
    L, M, N = (np.asarray(v, dtype=float) for v in (L, M, N))
    return 0.5 * np.abs(M[..., 0] * N[..., 1] + N[..., 0] * L[..., 1] + L[..., 0] * M[..., 1]
                        - M[..., 0] * L[..., 1] - L[..., 0] * N[..., 1] - N[..., 0] * M[..., 1])


def polar_angles(points, centre) -> tuple[np.ndarray, np.ndarray]:
    """Polar angle beta and radius r of points about ``centre`` (Fig. 4.2)."""
    p = as_points(points) - np.asarray(centre, dtype=float)
    return np.arctan2(p[:, 1], p[:, 0]), np.hypot(p[:, 0], p[:, 1])


def _line_intersection(P1, P2, Q1, Q2) -> np.ndarray:
    """Intersection I of lines P1P2 and Q1Q2 (rows); midpoint of the segments if parallel."""
    r = P2 - P1
    s = Q2 - Q1
    den = r[:, 0] * s[:, 1] - r[:, 1] * s[:, 0]
    qp = Q1 - P1
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (qp[:, 0] * s[:, 1] - qp[:, 1] * s[:, 0]) / den
    t = np.where(np.isfinite(t), np.clip(t, 0.0, 1.0), 0.5)
    return P1 + t[:, None] * r


def radial_gaps(ws: Workspace | np.ndarray, prescribed: Prescribed) -> tuple[np.ndarray, np.ndarray]:
    """r^i = r_c^i - r_p^i along the rays from O' through the computed boundary points, and
    the angles beta_c^i (Section 4.7.1)."""
    bc = ws.boundary if isinstance(ws, Workspace) else as_points(ws)
    beta, rc = polar_angles(bc, prescribed.centre)
    return rc - prescribed.radius(beta), beta


def delta_areas(ws: Workspace | np.ndarray, prescribed: Prescribed) -> tuple[float, float]:
    """(dW_p, dW_c) by the triangle scheme of eq. (4.9) and Fig. 4.3.

    For consecutive computed points (b_c^i, b_c^{i+1}) (cyclically: the thesis's closing
    pair (b_c^{n-1}, b_c^1), the closure point being already dropped) and the prescribed
    points b_p^i at the same polar angles:

    a. r_c >= r_p at both: dW_c += A(b_c^i, b_c^{i+1}, O') - A(b_p^i, b_p^{i+1}, O')
    b. r_c <  r_p at both: dW_p += A(b_p^i, b_p^{i+1}, O') - A(b_c^i, b_c^{i+1}, O')
    c. r_c^i < r_p^i, r_c^{i+1} >= r_p^{i+1}: dW_c += A(b_c^{i+1}, b_p^{i+1}, I),
       dW_p += A(b_c^i, b_p^i, I)
    d. r_c^i >= r_p^i, r_c^{i+1} < r_p^{i+1}: dW_c += A(b_p^i, b_c^i, I),
       dW_p += A(b_p^{i+1}, b_c^{i+1}, I)

    with I the intersection of the two chords (the printed case d repeats its first line;
    the second term is the mirror of case c). An empty workspace gives (area(W_p), 0).
    """
    bc = ws.boundary if isinstance(ws, Workspace) else as_points(ws)
    if bc.shape[0] < 3:
        return float(prescribed.area()), 0.0
    centre = np.asarray(prescribed.centre, dtype=float)
    beta, rc = polar_angles(bc, centre)
    rp = prescribed.radius(beta)
    bp = prescribed.points_at(beta)
    out = rc >= rp
    c1, c2 = bc, np.roll(bc, -1, axis=0)
    p1, p2 = bp, np.roll(bp, -1, axis=0)
    o1, o2 = out, np.roll(out, -1)
    Oa = np.broadcast_to(centre, c1.shape)
    tc = triangle_area(c1, c2, Oa)
    tp = triangle_area(p1, p2, Oa)
    cross = _line_intersection(c1, c2, p1, p2)
    dwc = np.where(o1 & o2, tc - tp, 0.0)
    dwp = np.where(~o1 & ~o2, tp - tc, 0.0)
    case_c = ~o1 & o2
    case_d = o1 & ~o2
    dwc += np.where(case_c, triangle_area(c2, p2, cross), 0.0) + np.where(case_d, triangle_area(p1, c1, cross), 0.0)
    dwp += np.where(case_c, triangle_area(c1, p1, cross), 0.0) + np.where(case_d, triangle_area(p2, c2, cross), 0.0)
    return float(dwp.sum()), float(dwc.sum())


def star_shaped(points, centre) -> bool:
    """True when every ray from ``centre`` crosses the closed polygon ``points`` exactly once:
    it winds once around ``centre`` and its polar angle moves the same way along every edge.
    The premise of the triangle scheme (4.9), whose fan of triangles from O' covers W_c once
    only then."""
    p = as_points(points) - np.asarray(centre, dtype=float)
    if p.shape[0] < 3:
        return False
    a = np.arctan2(p[:, 1], p[:, 0])
    da = (np.diff(a, append=a[:1]) + np.pi) % (2 * np.pi) - np.pi
    turn = float(np.sum(da))
    return bool(abs(abs(turn) - 2 * np.pi) < 1e-6 and (np.all(da > 0) if turn > 0 else np.all(da < 0)))


def delta_areas_checked(ws: Workspace | np.ndarray, prescribed: Prescribed) -> tuple[float, float]:
    """(dW_p, dW_c) by the triangle scheme (eq. 4.9) where it can measure them, by polygon
    geometry of the same chord boundary where it cannot [OWN].

    The scheme sums triangles fanned from W_p's centre O' to consecutive boundary points,
    so it measures area(W_p minus W_c) only if every ray from O' crosses the computed
    boundary once (`star_shaped`). Where the boundary does not wind around O' (a workspace
    beside or below W_p), every boundary point can lie beyond r_p, and the scheme returns
    dW_p = 0 with W_p entirely uncovered: a spurious feasible design of (4.14) and (4.16)
    with a smaller objective than any true one, which the better optimizers find. Where it
    winds around O' but folds back (rays crossing it three times), the fan counts some
    triangles twice: on a 3-RPR dextrous workspace the scheme gave dW_p = 0.017 where the
    polygons give 0.110, and it jumped to the true value as O' crossed the boundary, so
    finite differences across the jump fed the optimizers gradients of the wrong sign.
    In both cases the areas are the polygon differences of the chord polygon
    (`delta_areas_exact`); wherever the boundary is star-shaped about O' they are the
    thesis's scheme, bit for bit. The 3-RPR formulation makes the same check per slice
    (`rpr3_suite`).
    """
    bc = ws.boundary if isinstance(ws, Workspace) else as_points(ws)
    if bc.shape[0] >= 3 and star_shaped(bc, prescribed.centre):
        return delta_areas(bc, prescribed)
    if bc.shape[0] < 3:
        return delta_areas(bc, prescribed)
    return delta_areas_exact(to_shapely(bc), prescribed)


def delta_areas_exact(region: shapely.Geometry | Workspace, prescribed: Prescribed | shapely.Geometry,
                      k: int = 4096) -> tuple[float, float]:
    """(area(W_p \\ W_c), area(W_c \\ W_p)) from polygon geometry."""
    wc = region.polygon() if isinstance(region, Workspace) else region
    wp = prescribed.polygon(k) if isinstance(prescribed, Prescribed) else prescribed
    return float(wp.difference(wc).area), float(wc.difference(wp).area)


def enclosure_constraint(ws: Workspace | np.ndarray, prescribed: Prescribed,
                         dwp: float | None = None) -> float:
    """g(d) of eq. (4.16): dW_p if dW_p > 0, else -r^2 with r = min_i |r_c^i - r_p^i|.

    ``dwp`` defaults to the triangle-scheme value (`delta_areas`). An empty workspace
    gives g = area(W_p) > 0.
    """
    bc = ws.boundary if isinstance(ws, Workspace) else as_points(ws)
    if dwp is None:
        dwp = delta_areas(bc, prescribed)[0]
    if dwp > 0 or bc.shape[0] < 3:
        return float(dwp) if bc.shape[0] >= 3 else float(prescribed.area())
    gaps, _ = radial_gaps(bc, prescribed)
    return -float(np.min(np.abs(gaps))) ** 2


def min_inverse_condition(inverse_condition: Callable[[np.ndarray], np.ndarray], prescribed: Prescribed,
                          beta=None, k: int = 2048) -> float:
    """min kappa^-1 over the prescribed boundary (Section 4.7.2, Appendix D).

    ``beta``: the polar angles at which to evaluate (the thesis uses beta_c^i, the angles of
    the computed boundary points); default: ``k`` equally spaced angles (the exact minimum
    to O(1/k^2)). ``inverse_condition(U)`` is vectorized over points (k, 2).
    """
    if beta is None:
        beta = 2 * np.pi * np.arange(k) / k
    kinv = np.asarray(inverse_condition(prescribed.points_at(beta)), dtype=float)
    kinv = np.where(np.isfinite(kinv), kinv, -np.inf)
    return float(np.min(kinv))
