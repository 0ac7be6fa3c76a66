"""Figures of the ``spatial`` suite, from stored runs: the best design of each formulation.

* ``fig_spatial_cable``: the best 8-cable design's dextrous wrench-feasible workspace as a
  point cloud of grid cells (every load and orientation), with the cable anchors, and
  three horizontal slices of it.
* ``fig_spatial_gs``: the best hexapod's constant-orientation workspaces (every
  orientation of the set intersected) in the vertical and horizontal mid-planes of the
  prescribed box, with the box drawn in.
"""

from __future__ import annotations

import pathlib

import numpy as np
import pandas as pd

from harness.figures import save_figure

__all__ = ["figures"]


def _best(runs: pd.DataFrame, word: str) -> pd.Series | None:
    sub = runs[runs["problem"].astype(str).str.contains(word) & (runs["max_violation"].astype(float) <= 1e-6)
               & np.isfinite(runs["f"].astype(float))]
    if not len(sub):
        return None
    return sub.loc[sub["f"].astype(float).idxmin()]


def _cable_figure(r: pd.Series, outdir: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib.pyplot as plt

    from manipulators.synthesis.spatial_suite import CABLE, cable_design

    m = cable_design(np.asarray(r["x"], dtype=float))
    if m is None:
        return []
    box = np.array([m.frame_points.min(axis=0), m.frame_points.max(axis=0)])
    wss = [m.dextrous_workspace(CABLE["orientations"], w, box, resolution=24) for w in CABLE["loads"]]
    ws = wss[0]
    mask = np.logical_and.reduce([w.mask for w in wss])
    pts = ws.points[mask.ravel()]
    fig = plt.figure(figsize=(11, 4.2))
    ax = fig.add_subplot(1, 4, 1, projection="3d")
    ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], s=2, alpha=0.25, color="tab:blue")
    ax.scatter(*m.frame_points.T, color="k", s=18, marker="^")
    ax.set_title(f"{r['problem']}, {r['solver']}\nV = {-float(r['f']):.2f} m^3 (rays)", fontsize=9)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    n = mask.shape[2]
    for i, k in enumerate((n // 4, n // 2, 3 * n // 4)):
        a = fig.add_subplot(1, 4, i + 2)
        z = box[0, 2] + (k + 0.5) * (box[1, 2] - box[0, 2]) / n
        a.imshow(mask[:, :, k].T, origin="lower", extent=(box[0, 0], box[1, 0], box[0, 1], box[1, 1]), cmap="Blues")
        a.set_title(f"z = {z:.2f} m", fontsize=9)
        a.set_xlabel("x [m]")
        if i == 0:
            a.set_ylabel("y [m]")
    fig.tight_layout()
    return _save(fig, outdir, "fig_spatial_cable")


def _gs_figure(r: pd.Series, outdir: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib.patches as mpatches
    import matplotlib.pyplot as plt

    from manipulators.synthesis.spatial_suite import GS, gs_design

    x = np.asarray(r["x"], dtype=float)
    m = gs_design(x)
    if m is None:
        return []
    zc = float(x[16] if x.size == 18 else x[7])
    hx, hy, hz = GS["half"]
    reach = m.l_max
    g = np.linspace(-reach, reach, 161)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.4))
    for ax, plane in zip(axes, ("xz", "xy")):
        A, B = np.meshgrid(g, g if plane == "xy" else np.linspace(0.0, 2 * reach, 161), indexing="xy")
        P = (np.column_stack([A.ravel(), np.zeros(A.size), B.ravel()]) if plane == "xz"
             else np.column_stack([A.ravel(), B.ravel(), np.full(A.size, zc)]))
        ok = np.ones(len(P), dtype=bool)
        for rot in GS["orientations"]:
            ok &= m.feasible(P, rot)
        ax.contourf(A, B, ok.reshape(A.shape).astype(float), levels=[0.5, 1.5], colors=["tab:blue"], alpha=0.4)
        w, h, y0 = (2 * hx, 2 * hz, zc - hz) if plane == "xz" else (2 * hx, 2 * hy, -hy)
        ax.add_patch(mpatches.Rectangle((-hx, y0), w, h, fill=False, color="k", lw=1.5))
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("z [m]" if plane == "xz" else "y [m]")
        ax.set_title(f"{plane} plane{' (y = 0)' if plane == 'xz' else f' (z = {zc:.2f} m)'}", fontsize=9)
    fig.suptitle(f"{r['problem']}, {r['solver']}: worst kappa^-1 = {-float(r['f']):.4f}; blue: reachable at "
                 "every orientation; box: prescribed", fontsize=9)
    fig.tight_layout()
    return _save(fig, outdir, "fig_spatial_gs")


def _save(fig, outdir: pathlib.Path, stem: str) -> list[pathlib.Path]:
    return save_figure(fig, outdir / f"{stem}.png", dpi=130, tight=False, svg=True)


def figures(runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    out: list[pathlib.Path] = []
    for word, draw in (("cable", _cable_figure), ("gs", _gs_figure)):
        best = _best(runs, word)
        if best is not None:
            out += draw(best, pathlib.Path(outdir))
    return out
