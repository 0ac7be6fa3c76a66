"""Chord-method workspaces of cable robots (thesis Section 6.4.3, Algorithm 6.3).

The tension-limit constraint (6.21) is discontinuous on parts of the boundary (Fig. 6.6),
so the thesis locates each chord point by bisection (Algorithm 6.3) instead of
Dynamic-Q. Here the shared tracer `manipulators.workspace.chord_boundary` runs with
``smooth=False`` (bracketing and bisection on the sign of an indicator) on the
constraints

    C_0 = +1 if no tensions within [t_min, t_max] exist (or the minimum-norm ones violate
          them, for ``tensions="min-norm"``), else -1           (6.21)
    C_i = l_min - l_i, i = 1..n                                  (6.22)
    C_{n+1} = D_min - |det J|   (3 cables with det_min set)      (6.24)

and bifurcation points are the corners where the active constraint changes.

Interior points come from a coarse discretization (Section 6.4.3, first option): one
per connected region of the grid workspace, at the grid point farthest from the region's
edge. Every region is traced; the returned `Workspace` holds the largest region's
boundary, ``area`` is the sum over regions and ``info["regions"]`` lists each region's
own `Workspace`.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import shapely

from ._distribution import _det_cols, distribute
from ._geometry import as_poses, structure_rows

__all__ = ["constraint_function", "chord_workspace"]


def constraint_function(robot, phi: float, wrench: Any, tensions: str = "l1"):
    """The vectorized constraints ``C(U) -> (k, m)`` of the chord tracer (see module doc)."""
    w = np.asarray(wrench, dtype=float)

    def C(U: np.ndarray) -> np.ndarray:
        U, P = as_poses(U, phi)
        X, Y, M, lengths = structure_rows(robot.frame_points, robot.platform_points, U, P)
        method = "min-norm" if tensions == "min-norm" else "l1"
        feas, _ = distribute((X, Y, M), w, robot.t_min, robot.t_max, method, need_tensions=False)
        cols = [np.where(feas, -1.0, 1.0)[None, :], robot.l_min - lengths]
        if robot.det_min is not None:
            cols.append((robot.det_min - np.abs(_det_cols(X, Y, M, 0, 1, 2)))[None, :])
        out = np.concatenate(cols, axis=0).T
        return np.where(np.isnan(out), 1.0, out)  # a zero-length cable is infeasible

    return C


def _interiors(ws_grid) -> list[np.ndarray]:
    """One interior point per connected region of a grid workspace (largest region first)."""
    from scipy import ndimage

    labels, count = ndimage.label(ws_grid.mask)
    if count == 0:
        return []
    dist = ndimage.distance_transform_edt(np.pad(ws_grid.mask, 1))[1:-1, 1:-1]
    x, y = ws_grid.grid
    sizes = ndimage.sum(ws_grid.mask, labels, index=np.arange(1, count + 1))
    out = []
    for lab in np.argsort(-sizes) + 1:
        d = np.where(labels == lab, dist, -1.0)
        iy, ix = np.unravel_index(np.argmax(d), d.shape)
        out.append(np.array([x[ix], y[iy]]))
    return out


def chord_workspace(robot, phi: float, wrench: Any, *, tensions: str = "l1", chord: float = 0.05,
                    interior: Any = None, resolution: int = 50, tol: float = 1e-8, **options: Any):
    """Constant-orientation workspace by the chord method (Section 6.4.3, Algorithm 6.3).

    Parameters
    ----------
    chord : chord length d (thesis: 0.05, 0.03 or 0.02, Figs. 6.8-6.9).
    interior : a point strictly inside the workspace; None = one per region of a coarse
        grid workspace at ``resolution`` (regions of fewer than 2 grid points skipped).
    tol : bisection termination epsilon^u of Algorithm 6.3 (thesis 1e-8).
    **options : passed to `manipulators.workspace.chord_boundary`.
    """
    from manipulators.workspace import InfeasibleInterior, Workspace, chord_boundary

    t0 = time.perf_counter()
    C = constraint_function(robot, phi, wrench, tensions)
    if interior is not None:
        starts = [np.asarray(interior, dtype=float)]
    else:
        coarse = robot.workspace(phi, wrench, method="grid", resolution=resolution, tensions=tensions,
                                 keep_tensions=False)
        starts = _interiors(coarse)
    regions = []
    for u0 in starts:
        if any(shapely.contains_xy(r.polygon(), u0[0], u0[1]) for r in regions):
            continue  # already traced from another start
        try:
            ws = chord_boundary(C, u0, chord, tol=tol, smooth=False, **options)
        except InfeasibleInterior:
            if interior is not None:
                raise
            continue
        # grid regions joined by a neck thinner than the grid spacing are one workspace:
        # a second trace of the same region overlaps the first and is dropped
        poly = ws.polygon()
        if not any(poly.intersection(r.polygon()).area > 0.5 * min(ws.area, r.area) for r in regions):
            regions.append(ws)
    if not regions:  # with an interior point given, an infeasible one has raised above
        reason = coarse.info.get("reason") or (f"no region of the grid workspace at resolution {resolution} has the "
                                               "2 points a trace starts from; pass interior= or a finer resolution")
        return Workspace.empty(method="chord", regions=[], time=time.perf_counter() - t0, reason=reason)
    main = max(regions, key=lambda r: r.area)
    info = dict(main.info)
    info.update(regions=regions, n_regions=len(regions), time=time.perf_counter() - t0,
                tensions_method=tensions, phi=phi,
                n_evals=sum(r.info.get("n_evals", 0) for r in regions))
    return Workspace(boundary=main.boundary, bifurcations=main.bifurcations, active=main.active,
                     area=float(sum(r.area for r in regions)), method="chord", info=info)
