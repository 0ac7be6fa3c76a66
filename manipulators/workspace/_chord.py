"""The chord method for planar workspace boundaries (thesis Appendix C, Section 5.4.2).

Written once, generic over a manipulator's feasibility constraints ``C(U) <= 0``, and reused
by the 2-RPR (Chapter 4), the 3-RPR (Chapter 5) and the cable robots (Chapter 6).
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable

import numpy as np

from ._bifurcation import locate_corner
from ._polygon import signed_area
from ._roots import Evaluator, solve_bracket
from ._workspace import Workspace

__all__ = [
    "chord_boundary", "check_closed", "open_policy",
    "InfeasibleInterior", "ChordError", "OpenBoundary", "OpenBoundaryWarning",
]

TWO_PI = 2.0 * math.pi


class InfeasibleInterior(ValueError):
    """The radiating point given to the chord method is not strictly inside the workspace."""


class ChordError(RuntimeError):
    """The boundary could not be traced (no boundary along the ray, lost boundary)."""


class OpenBoundary(ChordError):
    """The trace did not close (``on_open="raise"``): its polygon is not the workspace's."""


class OpenBoundaryWarning(RuntimeWarning):
    """The trace did not close (``on_open="warn"``, the default): ``area`` is not the workspace's."""


ON_OPEN = ("warn", "raise", "ignore")


def open_policy(on_open: str) -> str:
    """``on_open`` if it is a valid policy (``"warn"``, ``"raise"``, ``"ignore"``), else ValueError."""
    if on_open not in ON_OPEN:
        raise ValueError(f"on_open must be one of {ON_OPEN}, got {on_open!r}")
    return on_open


def check_closed(ws: Workspace, on_open: str = "warn", stacklevel: int = 2) -> Workspace:
    """Apply the ``on_open`` policy to a traced workspace and return it.

    A trace that does not close (closure test C.14 never met: the boundary was lost, or
    ``max_points`` ran out) has a polygon that is an open polyline, and its ``area`` (0 for
    fewer than 3 points) is not the workspace's area. ``"warn"`` (default) issues an
    `OpenBoundaryWarning`, ``"raise"`` raises `OpenBoundary`, ``"ignore"`` returns the
    workspace as it is (``info["closed"]`` is False either way) [OWN: Appendix C assumes the
    trace closes].
    """
    if open_policy(on_open) == "ignore" or "n_steps" not in ws.info or ws.info.get("closed"):
        return ws  # ignored, not a trace (grid, empty), or closed
    i = ws.info
    refined = f", refined from {i['refined_from']}" if "refined_from" in i else ""
    u0 = np.asarray(i.get("interior")).tolist()
    msg = (f"the chord trace did not close: {i.get('failure') or 'closure test (C.14) not met'} "
           f"(chord d = {i.get('chord')}{refined}, interior point {u0}); its area {ws.area:.6g} is that "
           f"of an open polyline of {ws.n_boundary} points, not the workspace's. A shorter chord, or another "
           f"interior point, usually closes it")
    if on_open == "raise":
        raise OpenBoundary(msg)
    warnings.warn(msg, OpenBoundaryWarning, stacklevel=stacklevel)
    return ws


def chord_boundary(
    constraints: Callable[[np.ndarray], np.ndarray],
    interior,
    chord: float,
    *,
    direction=(1.0, 0.0),
    tol: float = 1e-10,
    smooth: bool = True,
    max_points: int = 20_000,
    jacobian: Callable[[np.ndarray], np.ndarray] | None = None,
    n_scan: int = 48,
    n_refine: int = 15,
    r_max: float | None = None,
    bifurcations: bool = True,
    on_open: str = "warn",
) -> Workspace:
    """Trace a workspace boundary counterclockwise at constant chord length (Appendix C).

    Reduced-variable form of Section 5.4.2 (eqs. 5.16-5.19, missing from the printed text;
    see ERRATA): the constraint of each subproblem is enforced analytically so each point
    is the root of one variable.

    1. Ray search (C.9, eq. 5.16): ``u(r) = u0 + r s``; ``b^1`` is the first root of
       ``max_j C_j(u(r))`` (the ray is sampled at steps of d/2, then the bracket is solved).
    2. Chord steps (C.12): ``u(omega) = b^i + d (cos(theta + omega), sin(theta + omega))``
       with ``theta`` the direction of the previous chord. ``omega`` is scanned counter-
       clockwise from just past the backward direction (``n_scan`` trial angles in one
       vectorized call) and ``b^{i+1}`` is the first infeasible-to-feasible crossing: the
       smallest feasible ``omega`` measured from the outward side, as in (C.11)-(C.12), but
       it also follows reflex turns of up to 180 degrees (the thesis's start at the outward
       normal s^1 of (C.13) allows 90).
    3. Closure test (C.14): stop when ``||b^i - b^1|| <= d`` and ``||b^i - b^2|| <= d``;
       that last point lies between ``b^1`` and ``b^2`` and is dropped (Section 4.5.1).
    4. Bifurcation points (C.6, eq. 5.20): wherever the active constraint changes between
       consecutive points, the corner where both are active is solved for exactly: Newton
       on the 2x2 system ``C_i(u) = C_j(u) = 0`` (``jacobian`` or forward differences)
       for smooth constraints, bisection on a sub-chord radius otherwise, and inserted.

    Each 1-D subproblem is solved by a safeguarded Newton iteration (smooth) or by
    multi-point bisection (``smooth=False``: indicator constraints such as cable-tension
    feasibility, thesis Algorithm 6.3) rather than by the thesis's general constrained
    optimizers (LfopC / Dynamic-Q): each subproblem is one variable and a bracketed root,
    so a 1-D root finder is exact to ``tol`` at a fraction of the cost.

    Parameters
    ----------
    constraints : callable ``C(U) -> (k, m)``
        Vectorized feasibility constraints at points ``U`` of shape (k, 2); a point is
        feasible iff every ``C[:, j] <= 0``. With ``smooth=False`` values are only used for
        their sign (a 0/1 "infeasible" indicator per column is fine).
    interior : (2,) a point strictly inside the workspace (radiating point u0).
    chord : chord length d > 0.
    direction : ray direction s (normalized here).
    tol : accuracy of every boundary and bifurcation point (length units).
    smooth : see above.
    max_points : give up (``info["closed"] = False``) after this many boundary points.
    jacobian : optional ``J(U) -> (k, m, 2)``, derivatives of ``constraints`` for the
        bifurcation Newton solves (forward differences otherwise).
    n_scan : trial angles per chord step.
    n_refine : trial points per bisection call (non-smooth only).
    r_max : longest ray searched (default 1e4 d).
    bifurcations : locate and insert bifurcation points.
    on_open : what a trace that does not close does: ``"warn"`` (default), ``"raise"`` or
        ``"ignore"`` (`check_closed`).

    Returns
    -------
    Workspace with ``method="chord"``; ``info`` holds ``n_evals`` (calls of
    ``constraints``), ``n_points`` (points evaluated), ``time``, ``closed``, ``n_steps``,
    ``bifurcation_failures``.

    Raises
    ------
    InfeasibleInterior : ``interior`` violates a constraint (or, if smooth, sits on one).
    ChordError : no boundary within ``r_max`` along the ray.
    OpenBoundary : the trace did not close and ``on_open="raise"``.
    """
    t_start = time.perf_counter()
    d = float(chord)
    if not (d > 0 and math.isfinite(d)):
        raise ValueError(f"chord length must be a positive number, got {chord!r}")
    if not (tol > 0):
        raise ValueError(f"tol must be positive, got {tol!r}")
    if n_scan < 8:
        raise ValueError(f"n_scan must be >= 8, got {n_scan}")
    open_policy(on_open)
    u0 = np.asarray(interior, dtype=float).reshape(-1)
    if u0.shape != (2,) or not np.all(np.isfinite(u0)):
        raise ValueError(f"interior must be a finite point (x, y), got {interior!r}")
    s = np.asarray(direction, dtype=float).reshape(-1)
    if s.shape != (2,) or not np.all(np.isfinite(s)) or np.hypot(*s) == 0:
        raise ValueError(f"direction must be a non-zero 2-vector, got {direction!r}")
    s = s / np.hypot(*s)
    ev = Evaluator(constraints)

    c0 = ev(u0[None, :])[0]
    ok = c0 < 0 if smooth else c0 <= 0  # indicator constraints are 0 where feasible
    if not np.all(ok):
        bad = np.flatnonzero(~ok).tolist()
        raise InfeasibleInterior(
            f"interior point {u0.tolist()} is not strictly feasible: constraints {bad} have values "
            f"{c0[bad].tolist()} (need all {'< 0' if smooth else '<= 0'})")

    # ---- 1. ray search for b^1 (eq. 5.16)
    b1, j1 = _ray_search(ev, u0, s, d, tol, smooth, n_refine, r_max if r_max is not None else 1e4 * d)
    pts = [b1]
    act = [j1]
    theta0 = math.atan2(s[1], s[0]) + 0.5 * math.pi  # outward s rotated +90: interior on the left
    thetas = [theta0]  # direction of the chord arriving at each point

    # ---- 2. chord steps with the closure test (C.14)
    closed = False
    failure = ""
    base = -math.pi + (np.arange(n_scan) + 0.5) * (TWO_PI / n_scan)
    while len(pts) < max_points:
        turn = (thetas[-1] - thetas[-2] + math.pi) % TWO_PI - math.pi if len(thetas) >= 2 else None
        step = _chord_step(ev, pts[-1], thetas[-1], d, base, tol, smooth, n_refine, turn)
        if (step is not None and len(pts) >= 2 and act[-1] != act[-2] and step[1] == act[-2]
                and np.hypot(*(step[0] - pts[-2])) < d):
            # The last chord cut across a sharp convex corner (active constraint changed);
            # the circle about the new point dips back into the thin wedge behind the
            # corner and its first crossing lies on the curve just left, next to the point
            # before: a step backwards, not the boundary ahead.  Take the next crossing.
            step = _chord_step(ev, pts[-1], thetas[-1], d, base, tol, smooth, n_refine, turn, skip=1) or step
        if step is None:
            failure = f"lost the boundary after {len(pts)} points (no feasible crossing on the chord circle)"
            break
        b_next, j_next = step
        diff = b_next - pts[-1]
        thetas.append(math.atan2(diff[1], diff[0]))
        pts.append(b_next)
        act.append(j_next)
        if len(pts) >= 4 and np.hypot(*(b_next - pts[0])) <= d and np.hypot(*(b_next - pts[1])) <= d:
            closed = True
            break
    else:
        failure = f"max_points = {max_points} reached before closure"

    if closed:  # the closing point lies between b^1 and b^2 (Section 4.5.1)
        pts.pop()
        act.pop()
        thetas.pop()
        # so may the point before it, when the last full chord already passed b^1 (the
        # trace closing across a corner): it would double the polygon back over b^1
        while len(pts) > 3 and np.hypot(*(pts[-1] - pts[0])) < d and np.dot(pts[-1] - pts[0], pts[-2] - pts[0]) < 0:
            pts.pop()
            act.pop()
            thetas.pop()
    P = np.array(pts)
    A = np.array(act, dtype=int)
    T = np.array(thetas)

    # ---- 3. bifurcation points
    bif_pts: list[np.ndarray] = []
    n_fail = 0
    if bifurcations and closed and P.shape[0] >= 3:
        P, A, bif_pts, n_fail = _insert_bifurcations(ev, P, A, T, d, tol, smooth, n_refine, base, jacobian)

    if closed and P.shape[0] >= 3:
        P, A = _remove_spikes(P, A, 10 * tol)

    reversed_ = False
    if P.shape[0] >= 3 and signed_area(P) < 0:  # only for pathological inputs
        P, A, reversed_ = P[::-1].copy(), A[::-1].copy(), True
    info = {
        "n_evals": ev.calls, "n_points": ev.points, "time": time.perf_counter() - t_start,
        "closed": closed, "n_steps": len(pts), "chord": d, "tol": tol, "smooth": smooth,
        "interior": u0.tolist(), "direction": s.tolist(), "bifurcation_failures": n_fail,
        "n_constraints": ev.m, "reversed": reversed_, "failure": failure,
    }
    bif = np.array(bif_pts) if bif_pts else np.zeros((0, 2))
    ws = Workspace(boundary=P, bifurcations=bif, active=A, method="chord", info=info)
    return check_closed(ws, on_open, stacklevel=3)  # the warning names chord_boundary's caller


def _ray_search(ev: Evaluator, u0, s, d, tol, smooth, n_refine, r_max):
    """First boundary point along u0 + r s (C.9 in the reduced form, eq. 5.16)."""
    batch = 32
    step = 0.5 * d
    r_lo, f_lo = 0.0, float(np.max(ev(u0[None, :])[0]))
    while r_lo < r_max:
        rs = r_lo + step * np.arange(1, batch + 1)
        v, j = ev.phi(u0 + rs[:, None] * s)
        bad = v > 0
        if bad.any():
            k = int(np.argmax(bad))
            a, fa, ja = rs[k], v[k], int(j[k])
            b, fb = (rs[k - 1], v[k - 1]) if k > 0 else (r_lo, f_lo)

            def phi_r(r):
                return ev.phi(u0 + np.asarray(r)[:, None] * s)

            r, jr = solve_bracket(phi_r, a, b, fa, fb, ja, xtol=tol, smooth=smooth, n_refine=n_refine)
            return u0 + r * s, jr
        r_lo, f_lo = rs[-1], v[-1]
        step *= 2.0  # large or unbounded workspaces: grow the sampling step
    raise ChordError(f"no workspace boundary found along the ray from {u0.tolist()} in direction "
                     f"{s.tolist()} within r_max = {r_max:g}: either the workspace is unbounded in this "
                     f"direction, or its boundary lies farther out and r_max must be larger (pass a larger "
                     f"r_max=...; the default is 1e4 * chord)")


def _circle(b, d, angles):
    out = np.empty((angles.size, 2))
    np.cos(angles, out=out[:, 0])
    np.sin(angles, out=out[:, 1])
    out *= d
    out += b
    return out


def _chord_step(ev, b, theta, d, base, tol, smooth, n_refine, turn=None, skip=0):
    """Next boundary point at distance d from b (C.12, reduced to the angle omega).

    ``turn``: predicted turn of the chord direction (the previous one; exact on circular
    arcs). The Newton pair at the predicted angle is evaluated in the same call as the
    scan, so a smooth boundary usually costs two calls per point.  ``skip``: take the
    crossing after the first ``skip`` ones (counterclockwise from the backward direction).
    Returns (point, active index) or None if the circle has no (such) feasible crossing.
    """
    ang = theta + base
    n = ang.size
    xtol = tol / d
    if smooth and turn is not None:
        pred = theta + turn
        pred = theta + (pred - theta + math.pi) % TWO_PI - math.pi
        ang_all = np.concatenate((ang, (pred, pred + xtol)))
    else:
        ang_all = ang
    v_all, j_all = ev.phi(_circle(b, d, ang_all))
    v, j = v_all[:n], j_all[:n]
    feas = v <= 0
    trans = np.flatnonzero(~feas[:-1] & feas[1:])
    if skip < trans.size:
        k = int(trans[skip])
        a, fa, ja, bb, fb = ang[k], v[k], int(j[k]), ang[k + 1], v[k + 1]
    elif skip == trans.size and (not feas[-1]) and feas[0]:  # crossing straddles the backward direction
        a, fa, ja, bb, fb = ang[-1], v[-1], int(j[-1]), ang[0] + TWO_PI, v[0]
    else:
        return None

    def phi_w(w):
        return ev.phi(_circle(b, d, np.asarray(w)))

    first = None
    if ang_all.size > n:
        pred = ang_all[n]
        if bb > math.pi + theta and pred < a:  # the wrapped bracket
            pred += TWO_PI
        first = (pred, v_all[n:], j_all[n:])
    w, jw = solve_bracket(phi_w, a, bb, fa, fb, ja, xtol=xtol, smooth=smooth, n_refine=n_refine, first=first)
    return _circle(b, d, np.array([w]))[0], jw


def _remove_spikes(P, A, eps):
    """Drop zero-area spikes of a closed trace: repeated points, and there-and-back runs
    ``..., p, q, p, ...`` (a chord step that returned to the point before, e.g. across the
    sharp corner at the trace's start and end) become ``..., p, ...``.  They enclose no area
    but make the polar angle about O' run backwards, which the triangle scheme (eq. 4.9)
    would count twice."""
    while P.shape[0] > 3:
        d1 = np.hypot(*(np.roll(P, -1, axis=0) - P).T)
        d2 = np.hypot(*(np.roll(P, -2, axis=0) - P).T)
        hit = np.flatnonzero((d1 <= eps) | (d2 <= eps))
        if not hit.size:
            break
        k, n = int(hit[0]), P.shape[0]
        keep = np.ones(n, dtype=bool)
        keep[[(k + 1) % n] if d1[k] <= eps else [(k + 1) % n, (k + 2) % n]] = False
        P, A = P[keep], A[keep]
    return P, A


def _insert_bifurcations(ev, P, A, T, d, tol, smooth, n_refine, base, jacobian):
    """Insert the exact corner wherever the active constraint changes (cyclically)."""
    n = P.shape[0]
    out_p: list[np.ndarray] = []
    out_a: list[int] = []
    bifs: list[np.ndarray] = []
    n_fail = 0
    for i in range(n):
        out_p.append(P[i])
        out_a.append(int(A[i]))
        k = (i + 1) % n
        if A[i] == A[k] or A[i] < 0 or A[k] < 0:
            continue
        # T[i] is the direction of the chord arriving at P[i]: the reference for a
        # (sub-)chord step from P[i] when the corner is found by bisection
        corner = locate_corner(ev, P[i], P[k], int(A[i]), int(A[k]), d=d, tol=tol, smooth=smooth,
                               jacobian=jacobian, theta=float(T[i]), n_refine=n_refine,
                               base=base, chord_step=_chord_step)
        if corner is None:
            n_fail += 1
            continue
        # a corner that coincides with a traced point is already in the polygon
        if min(np.hypot(*(corner - P[i])), np.hypot(*(corner - P[k]))) <= 10 * tol:
            continue
        out_p.append(corner)
        out_a.append(-1)
        bifs.append(corner)
    return np.array(out_p), np.array(out_a, dtype=int), bifs, n_fail

