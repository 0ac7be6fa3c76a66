"""Workspaces of the 3-RPR by the shared chord method (thesis Sections 5.4, 5.5, App. C).

Each workspace is the shared `chord_boundary` applied to a vectorized constraint function
of the `RPR3` (feasible iff all columns ``<= 0``); this module supplies the interior
points and the bookkeeping:

* constant orientation ``W^C[phi]`` (Section 5.4): the leg limits at fixed ``phi``
  (6 columns, + the branch column).  Radiating point: the grid point of greatest
  constraint margin (the thesis uses the assembled point (5.28); any interior point
  serves the ray search (5.16)).
* dextrous ``W^D[phi_min, phi_max]`` (Algorithm 5.1): step 1 the assembled point
  ``u^a`` (5.28), step 2 the point of greatest dexterity ``u^d`` (5.29), steps 3-5 the
  ray (5.30), chord steps (5.31) and bifurcation points (5.32, 5.33) by `chord_boundary`
  with the closed-form constraints `RPR3.dextrous_constraints` (default) or the thesis's
  orientation-range constraints ``c1, c2`` (`RPR3.orientation_constraints`).  Bifurcation
  points are typed I or II from the constraints active on either side (Section 5.5.3).
* maximal ``W^M`` (Appendix C): one column, `RPR3.maximal_constraints`.
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy.optimize import least_squares, minimize

from .workspace import Workspace, chord_boundary

__all__ = [
    "constant_orientation_workspace",
    "dextrous_workspace",
    "maximal_workspace",
    "interior_point",
    "EmptyWorkspace",
]


class EmptyWorkspace(ValueError):
    """No feasible point was found (the design cannot reach any pose)."""


def _bbox_of_legs(m, phi_values):
    """Box containing every pose reachable by all three legs at the given orientations."""
    lo = np.full(2, -np.inf)
    hi = np.full(2, np.inf)
    sgn = np.array([-1.0, -1.0, 1.0])
    for phi in np.atleast_1d(phi_values):
        e = np.array([np.cos(phi), np.sin(phi)])
        for i in range(3):
            c = m.base[i] - sgn[i] * m.r * e
            lo = np.maximum(lo, c - m.lmax[i])
            hi = np.minimum(hi, c + m.lmax[i])
    return lo, hi


def interior_point(C, lo, hi, *, n: int = 64, refine: bool = True):
    """Point of (nearly) greatest margin ``-max_j C_j`` in the box ``[lo, hi]``.

    A vectorized ``n x n`` grid search, then Nelder-Mead on the margin from the best grid
    point (so thin workspaces missed by the grid are still found).  Returns
    ``(u, margin)``; ``margin > 0`` means ``u`` is strictly interior.
    """
    if np.any(hi <= lo):
        return None, -np.inf
    xs = np.linspace(lo[0], hi[0], n)
    ys = np.linspace(lo[1], hi[1], n)
    X, Y = np.meshgrid(xs, ys)
    U = np.column_stack([X.ravel(), Y.ravel()])
    margin = -np.max(C(U), axis=1)
    k = int(np.argmax(margin))
    u, best = U[k], float(margin[k])
    if refine:
        res = minimize(
            lambda x: float(np.max(C(x[None, :]))),
            u,
            method="Nelder-Mead",
            options={
                "xatol": 1e-9,
                "fatol": 1e-12,
                "maxiter": 400,
                "initial_simplex": np.array([u, u + [(hi[0] - lo[0]) / n, 0], u + [0, (hi[1] - lo[1]) / n]]),
            },
        )
        if -res.fun > best:
            u, best = res.x, float(-res.fun)
    return np.asarray(u, dtype=float), best


def _with_info(ws: Workspace, **extra) -> Workspace:
    import dataclasses

    return dataclasses.replace(ws, info={**dict(ws.info), **extra})


def constant_orientation_workspace(
    m, phi: float, chord: float, *, branch="upper", interior=None, **chord_kw
) -> Workspace:
    """``W^C[phi]`` of design ``m`` (eq. 5.14) by the chord method (Section 5.4.2)."""
    t0 = time.perf_counter()
    # a number or a 0-d array of one; a bool of either kind is none (as in `_checks.is_number`)
    ok = not isinstance(phi, (bool, np.bool_, str)) and np.ndim(phi) == 0
    try:
        ok = ok and math.isfinite(float(phi))
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ValueError(f"phi must be one finite orientation (radians), got {phi!r}")
    phi = float(phi)
    C = lambda U: m.constraints(U, phi, branch=branch)
    if interior is None:
        lo, hi = _bbox_of_legs(m, phi)
        if branch == "upper":
            lo[1] = max(lo[1], m.yC)
        interior, margin = interior_point(C, lo, hi)
        if interior is None or margin <= 0:
            raise EmptyWorkspace(
                f"3-RPR design {m.design.tolist()} has an empty constant-orientation workspace at phi={phi}"
                f" (largest margin {margin:.3g})"
            )
    ws = chord_boundary(C, interior, chord, **chord_kw)
    return _with_info(ws, kind="constant-orientation", phi=phi, interior=np.asarray(interior),
                      time_total=time.perf_counter() - t0, constraint_names=_co_names(branch))


def _co_names(branch):
    names = [f"l{i + 1}<=max" for i in range(3)] + [f"l{i + 1}>=min" for i in range(3)]
    return names + (["y>=yC"] if branch == "upper" else [])


def _dex_names(branch):
    names = []
    for end in ("phi_min", "phi_max"):
        names += [f"l{i + 1}<=max@{end}" for i in range(3)] + [f"l{i + 1}>=min@{end}" for i in range(3)]
    names += [f"l{i + 1}<=max@interior" for i in range(3)] + [f"l{i + 1}>=min@interior" for i in range(3)]
    return names + (["y>=yC"] if branch == "upper" else [])


def assembled_point(m):
    """Step 1 of Algorithm 5.1: ``u^a, w^a`` minimizing ``||v(u, w) - v_bar||^2`` (5.27-5.28).

    Started above the base line (the upper assembly branch), at the centroid of the base
    joints raised by the mean average leg length, orientation 0.
    """
    vbar = 0.5 * (m.lmin + m.lmax)
    x0 = np.array([m.base[:, 0].mean(), m.yC + vbar.mean(), 0.0])
    res = least_squares(lambda q: m.leg_lengths(q[:2], q[2])[0] - vbar, x0, xtol=1e-12, ftol=1e-12)
    return res.x[:2], float(res.x[2])


def greatest_dexterity_point(m, u_start, w_ref):
    """Step 2 of Algorithm 5.1: ``u^d`` maximizing ``(w_max(u) - w_min(u))^2`` (5.29).

    The orientation range is the closed-form interval containing ``w_ref`` (capped at
    ``2 pi``); Nelder-Mead from ``u_start``.
    """
    def neg_width(u):
        lo, hi = m.orientation_range(u[None, :], w_ref)
        w = float(np.nan_to_num(min(hi[0] - lo[0], 2 * np.pi), nan=0.0))
        return -(w * w)

    res = minimize(neg_width, np.asarray(u_start, float), method="Nelder-Mead",
                   options={"xatol": 1e-8, "fatol": 1e-12, "maxiter": 600})
    return res.x, float(np.sqrt(max(-res.fun, 0.0)))


def dextrous_workspace(m, phi_min: float, phi_max: float, chord: float, *, branch="upper",
                       constraints: str = "legs", orientation_method: str = "closed", interior=None,
                       **chord_kw) -> Workspace:
    """``W^D[phi_min, phi_max]`` by Algorithm 5.1 (Section 5.5.2).

    constraints : ``"legs"`` (default): the closed-form worst-case leg constraints
        (`RPR3.dextrous_constraints`); ``"orientation"``: the thesis's ``c1, c2`` of
        (5.30)-(5.31) from the orientation range (``orientation_method`` "closed" or
        "numeric", the latter the thesis's problem (5.26) per point, slow).  Both describe
        the same set.
    """
    t0 = time.perf_counter()
    phi_min, phi_max = float(phi_min), float(phi_max)
    if not (np.isfinite(phi_min) and np.isfinite(phi_max) and phi_min <= phi_max):
        raise ValueError(f"need finite phi_min <= phi_max (radians), got [{phi_min}, {phi_max}]")
    if constraints == "legs":
        C = lambda U: m.dextrous_constraints(U, phi_min, phi_max, branch=branch)
        names = _dex_names(branch)
    elif constraints == "orientation":
        def C(U):
            c = m.orientation_constraints(U, phi_min, phi_max, method=orientation_method)
            if branch == "upper":
                c = np.column_stack([c, m.yC - np.asarray(U, float).reshape(-1, 2)[:, 1]])
            return c
        names = ([f"phi_max<=w_max(l{i + 1})" for i in range(3)] + [f"w_min(l{i + 1})<=phi_min" for i in range(3)]
                 if orientation_method == "closed" else ["phi_max<=w_max", "w_min<=phi_min"])
        names += ["y>=yC"] if branch == "upper" else []
    else:
        raise ValueError(f"constraints must be 'legs' or 'orientation', got {constraints!r}")
    w_mid = 0.5 * (phi_min + phi_max)
    if interior is not None:
        u_a = w_a = u_d = width = None
        interior = np.asarray(interior, dtype=float).reshape(2)
        margin = -float(np.max(C(interior[None, :])))
    else:
        u_a, w_a = assembled_point(m)                      # (5.28)
        u_d, width = greatest_dexterity_point(m, u_a, w_mid)  # (5.29)
        interior = u_d
        margin = -float(np.max(C(u_d[None, :])))
    if not margin > 0:
        # u^d need not lie in W^D (its orientation interval may not cover the range):
        # fall back to the point of greatest dextrous-constraint margin.
        lo, hi = _bbox_of_legs(m, [phi_min, w_mid, phi_max])
        if branch == "upper":
            lo[1] = max(lo[1], m.yC)
        Cl = lambda U: m.dextrous_constraints(U, phi_min, phi_max, branch=branch)
        interior, margin = interior_point(Cl, lo, hi)
        if interior is None or margin <= 0:
            raise EmptyWorkspace(f"3-RPR design {m.design.tolist()} has an empty dextrous workspace over "
                                 f"[{phi_min}, {phi_max}] (largest margin {margin:.3g})")
    ws = chord_boundary(C, interior, chord, **chord_kw)
    types = _bifurcation_types(ws, constraints, branch, orientation_method)
    return _with_info(ws, kind="dextrous", phi_min=phi_min, phi_max=phi_max, u_a=u_a, w_a=w_a, u_d=u_d,
                      dexterity_at_u_d=width, interior=np.asarray(interior), bifurcation_types=types,
                      constraint_names=names, time_total=time.perf_counter() - t0)


def _orientation_tag(j, constraints, branch, orientation_method="closed"):
    if constraints == "legs":
        if j < 6:
            return "phi_min"
        if j < 12:
            return "phi_max"
        if j < 18:
            return "interior"
        return "branch"
    if orientation_method == "closed":
        return {0: "phi_max", 1: "phi_max", 2: "phi_max", 3: "phi_min", 4: "phi_min", 5: "phi_min"}.get(
            int(j), "branch"
        )
    return {0: "phi_max", 1: "phi_min"}.get(int(j), "branch")


def _bifurcation_types(ws, constraints, branch, orientation_method="closed"):
    """Type I (same extreme orientation on both sides) or II (it changes), Section 5.5.3."""
    act = np.asarray(ws.active)
    k = act.size
    types = []
    for i in np.flatnonzero(act < 0):
        before = next((act[(i - s) % k] for s in range(1, k) if act[(i - s) % k] >= 0), -1)
        after = next((act[(i + s) % k] for s in range(1, k) if act[(i + s) % k] >= 0), -1)
        if before < 0 or after < 0:
            types.append("?")
            continue
        tb = _orientation_tag(before, constraints, branch, orientation_method)
        ta = _orientation_tag(after, constraints, branch, orientation_method)
        types.append("I" if tb == ta else "II")
    return types


def maximal_workspace(m, chord: float, *, interior=None, **chord_kw) -> Workspace:
    """``W^M`` (eq. C.4): points reachable in some orientation, by the chord method (App. C).

    Radiating point: the assembled point ``u^a`` (C.8).  The whole connected component is
    traced (no branch restriction: the orientation is free).
    """
    t0 = time.perf_counter()
    C = lambda U: m.maximal_constraints(U)
    if interior is None:
        interior, _ = assembled_point(m)
        if not float(C(interior[None, :])[0, 0]) < 0:
            lo = m.base.min(axis=0) - m.lmax.max() - m.r
            hi = m.base.max(axis=0) + m.lmax.max() + m.r
            interior, margin = interior_point(C, lo, hi, n=48)
            if interior is None or margin <= 0:
                raise EmptyWorkspace(f"3-RPR design {m.design.tolist()} has an empty maximal workspace")
    ws = chord_boundary(C, interior, chord, **chord_kw)
    return _with_info(ws, kind="maximal", interior=np.asarray(interior), time_total=time.perf_counter() - t0)
