"""Workspaces of cable robots: discretization (Algorithm 6.2), chord method (Section 6.4.3,
Algorithm 6.3) and the dextrous workspace as an intersection of slices (Section 6.5).

The feasibility test of a pose (6.21)-(6.24) is vectorized over the whole grid: for the
constrained l1/l2 methods and their maximum variants the set of poses with feasible
tensions is the same (the feasible tension set is non-empty), so one exact test serves
all four (n = 3: the unique solution; n = 4: Algorithm 6.1; n >= 5: basic solutions);
the minimum-norm method (6.14) has its own, smaller set (Fig. 6.3).
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from ._distribution import METHODS, _det_cols, distribute
from ._geometry import as_poses, structure_rows

__all__ = ["grid_axes", "feasible_poses", "constant_orientation_workspace", "dextrous_workspace"]


def _workspace_type():
    from manipulators.workspace import Workspace

    return Workspace


def grid_axes(robot, resolution: int) -> tuple[np.ndarray, np.ndarray]:
    """Grid of Algorithm 6.2 (ERRATA): m + 1 points per axis on [min c_x, max c_x] x [min c_y, max c_y]."""
    m = int(resolution)
    if m != resolution or m < 1:
        raise ValueError(f"resolution m must be a positive integer, got {resolution!r}")
    c = robot.frame_points
    return (np.linspace(c[:, 0].min(), c[:, 0].max(), m + 1),
            np.linspace(c[:, 1].min(), c[:, 1].max(), m + 1))


def feasible_poses(robot, U: np.ndarray, phi: np.ndarray, wrench: Any, tensions: str = "l1",
                   need_tensions: bool = False) -> tuple[np.ndarray, np.ndarray | None]:
    """Workspace membership (6.23) of k poses: tensions (6.21), lengths (6.22), |det J| (6.24).

    The fast path of the grids: S is used row by row (`structure_rows`) and never stacked.
    """
    if tensions not in METHODS:
        raise ValueError(f"unknown tension method {tensions!r}; valid: {', '.join(METHODS)}")
    if np.ndim(phi) == 0:  # one orientation for all poses (grid slices): the fast path
        U = as_poses(U, 0.0)[0]
        phi = float(phi)
    else:
        U, phi = as_poses(U, phi)
    X, Y, M, lengths = structure_rows(robot.frame_points, robot.platform_points, U, phi)
    w = robot._wrench(wrench, U.shape[0])
    method = tensions if (need_tensions or tensions == "min-norm") else "l1"
    feas, T = distribute((X, Y, M), w, robot.t_min, robot.t_max, method, need_tensions=need_tensions)
    feas &= (lengths >= robot.l_min).all(0)
    if robot.det_min is not None:
        feas &= np.abs(_det_cols(X, Y, M, 0, 1, 2)) >= robot.det_min
    if T is not None:
        T[~feas] = np.nan
    return feas, T


def _empty_reason(robot, points: int, where: str) -> str:
    """Why a grid workspace is empty: what every one of its ``points`` poses failed."""
    det = f", |det J| >= {robot.det_min:g}" if robot.det_min is not None else ""
    return (f"none of the {points} grid poses {where} is feasible for this wrench: (6.23) asks for cable tensions "
            f"within [{robot.t_min:g}, {robot.t_max:g}], cable lengths >= {robot.l_min:g}{det}")


def _grid_area(x: np.ndarray, y: np.ndarray, count: int) -> float:
    m = x.size - 1
    return float(count) * ((x[-1] - x[0]) / m) * ((y[-1] - y[0]) / m)


def constant_orientation_workspace(robot, phi: float, wrench: Any, method: str = "grid",
                                   resolution: int = 50, tensions: str = "l1", *,
                                   keep_tensions: bool = True, chord: float = 0.05,
                                   interior: Any = None, **chord_options: Any):
    """Constant-orientation workspace W^C[phi] (6.23) of a cable robot.

    Parameters
    ----------
    method : ``"grid"`` (Algorithm 6.2, area = feasible count x cell area, ERRATA) or
        ``"chord"`` (Section 6.4.3: boundary traced at chord length ``chord`` with the
        bisection of Algorithm 6.3 through `manipulators.workspace.chord_boundary`).
    resolution : grid resolution m ((m + 1)^2 points); for ``chord`` the resolution of
        the coarse grid that supplies the interior point (Section 6.4.3, first option).
    tensions : tension method (``"l1"``, ``"l2"``, ``"min-norm"``, ``"l1-max"``, ``"l2-max"``).
    keep_tensions : grid only: compute the tensions of ``tensions`` at every feasible
        point and keep them in ``info["tensions"]`` (shape (m+1, m+1, n)).
    """
    if not np.isscalar(phi) or not np.isfinite(phi):
        raise ValueError(f"phi must be one finite orientation, got {phi!r}")
    if method == "grid":
        if chord_options:  # a misspelt option (resolutoin=5) would otherwise be dropped silently
            raise TypeError(f"workspace(method='grid') got unexpected keyword(s) {', '.join(sorted(chord_options))}; "
                            "valid: resolution, tensions, keep_tensions (chord, interior and the options of "
                            "manipulators.workspace.chord_boundary are for method='chord')")
        return _grid_workspace(robot, float(phi), wrench, resolution, tensions, keep_tensions)
    if method == "chord":
        from ._chord import chord_workspace

        return chord_workspace(robot, float(phi), wrench, tensions=tensions, chord=chord,
                               interior=interior, resolution=resolution, **chord_options)
    raise ValueError(f"unknown workspace method {method!r}; valid: grid, chord")


def _grid_workspace(robot, phi, wrench, resolution, tensions, keep_tensions):
    t0 = time.perf_counter()
    x, y = grid_axes(robot, resolution)
    X, Y = np.meshgrid(x, y)
    U = np.column_stack([X.ravel(), Y.ravel()])
    need = keep_tensions and (tensions != "l2" or robot.n <= 4)  # exact l2 is vectorized for n <= 4
    feas, T = feasible_poses(robot, U, phi, wrench, tensions, need_tensions=need)
    mask = feas.reshape(X.shape)
    info = {"n_points": int(U.shape[0]), "tensions_method": tensions, "phi": phi,
            "time": time.perf_counter() - t0}
    if T is not None:
        info["tensions"] = T.reshape(X.shape + (robot.n,))
    if not mask.any():
        info["reason"] = _empty_reason(robot, int(U.shape[0]), f"at phi = {phi:g}")
    return _workspace_type()(area=_grid_area(x, y, int(mask.sum())), method="grid", mask=mask,
                             grid=(x, y), info=info)


def dextrous_workspace(robot, phi_min: float, phi_max: float, wrench: Any, resolution: int = 50,
                       slices: int = 21, tensions: str = "l1"):
    """Dextrous workspace W^D[phi_min, phi_max] (6.28) on the grid of Algorithm 6.2.

    The intersection of ``slices`` constant-orientation workspaces at regularly spaced
    orientations (Section 6.5; the discretization test of Step 4 applied for every
    orientation), computed for all slices and grid points at once.
    ``info["mid_slice_valid"]`` is Du Plessis and Snyman's check (Section 6.5): the
    workspace at (phi_min + phi_max) / 2 contains the intersection of the two extreme
    slices; when it fails, two slices alone would overestimate W^D.
    """
    for name, v in (("phi_min", phi_min), ("phi_max", phi_max)):
        if not np.isscalar(v) or not np.isfinite(v):
            raise ValueError(f"{name} must be a finite number, got {v!r}")
    if phi_min > phi_max:
        raise ValueError(f"need phi_min <= phi_max, got {phi_min} > {phi_max}")
    s = int(slices)
    if s != slices or s < 1 or (s == 1 and phi_min != phi_max):
        raise ValueError(f"slices must be an integer >= 2 (>= 1 if phi_min == phi_max), got {slices!r}")
    t0 = time.perf_counter()
    x, y = grid_axes(robot, resolution)
    X, Y = np.meshgrid(x, y)
    U = np.column_stack([X.ravel(), Y.ravel()])
    phis = np.linspace(phi_min, phi_max, s)
    mid = 0.5 * (phi_min + phi_max)
    has_mid = bool(np.any(np.isclose(phis, mid, rtol=0, atol=1e-14)))
    all_phis = phis if has_mid else np.append(phis, mid)
    # slice by slice: arrays of one grid stay in cache (faster than one stack of all poses)
    F = np.stack([feasible_poses(robot, U, float(p), wrench, tensions)[0].reshape(X.shape)
                  for p in all_phis])
    mask = np.all(F[:s], axis=0)
    mid_mask = F[int(np.argmin(np.abs(all_phis - mid)))]
    extremes = F[0] & F[s - 1]
    info = {"n_points": int(F.size), "slices": phis, "tensions_method": tensions,
            "mid_slice_valid": bool(not np.any(extremes & ~mid_mask)),
            "extremes_area": _grid_area(x, y, int(extremes.sum())),
            "slice_areas": np.array([_grid_area(x, y, int(f.sum())) for f in F[:s]]),
            "time": time.perf_counter() - t0}
    if not mask.any():
        empty = ~F[:s].any(axis=(1, 2))  # slices with no feasible pose at all
        info["reason"] = (_empty_reason(robot, int(U.shape[0]), f"at phi = {phis[int(np.argmax(empty))]:g}")
                          if empty.any() else
                          f"each of the {s} slices in [{phi_min:g}, {phi_max:g}] has feasible poses, but no grid "
                          "pose is feasible in all of them")
    return _workspace_type()(area=_grid_area(x, y, int(mask.sum())), method="grid", mask=mask,
                             grid=(x, y), info=info)
