"""Figures of suite ``rpr3`` (thesis Figs. 5.4-5.17), drawn from stored runs.

* ``fig_5_4``-``fig_5_6``: nested dextrous workspaces of M1, M2, M3 (Algorithm 5.1).
* ``fig_<kind>_start``: prescribed workspaces P1-P3, the start design's workspace(s) and
  its kappa^-1 contours (Figs. 5.7a, 5.10, 5.15a).
* ``fig_<kind>_optima``: each prescribed workspace with the workspace(s) and kappa^-1
  contours of the best run's d* (Figs. 5.7b-5.8, 5.11-5.13, 5.15b-5.16).
* ``fig_<kind>_histories``: f (= min kappa^-1) against N^fg for every solver
  (Figs. 5.9, 5.14, 5.17).
"""

from __future__ import annotations

import json
import math
import pathlib

import numpy as np
import pandas as pd

from harness._styles import solver_order, solver_styles
from harness.figures import save_figure

__all__ = ["figures"]

KIND_FIGS = {"so": "5.7-5.9", "mo": "5.10-5.14", "d": "5.15-5.17"}


def _draw_ws(ax, ws, **kw):
    if ws.n_boundary >= 3:
        b = np.vstack([ws.boundary, ws.boundary[:1]])
        ax.plot(b[:, 0], b[:, 1], **kw)
        if ws.bifurcations.shape[0]:
            ax.plot(ws.bifurcations[:, 0], ws.bifurcations[:, 1], "k.", ms=4)


def _contours(ax, m, phi, box):
    x = np.linspace(box[0], box[1], 120)
    y = np.linspace(box[2], box[3], 120)
    X, Y = np.meshgrid(x, y)
    K = m.inverse_condition(np.column_stack([X.ravel(), Y.ravel()]), phi).reshape(X.shape)
    cs = ax.contour(X, Y, K, levels=np.arange(0.5, 1.0, 0.05), linewidths=0.5, cmap="viridis")
    ax.clabel(cs, fontsize=6, fmt="%.2f")


def _dextrous_figures(outdir: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib.pyplot as plt

    from manipulators.rpr3 import RPR3

    paths = []
    for k, name in enumerate(("M1", "M2", "M3")):
        m = RPR3.named(name)
        fig, ax = plt.subplots(figsize=(5, 4))
        for deg, c in zip((0, 5, 10, 15, 20), plt.cm.plasma(np.linspace(0, 0.85, 5))):
            try:
                ws = m.dextrous_workspace(-math.radians(deg), math.radians(deg), 0.02)
            except ValueError:
                continue
            _draw_ws(ax, ws, color=c, lw=1, label=f"[-{deg}, {deg}] deg")
        ax.plot(m.base[:, 0], m.base[:, 1], "ks", ms=4)
        ax.set_aspect("equal")
        ax.legend(fontsize=7)
        ax.set_title(f"Fig. 5.{4 + k}: dextrous workspaces of {name}")
        p = outdir / f"fig_5_{4 + k}_dextrous_{name}.png"
        paths += save_figure(fig, p, dpi=130)
    return paths


def _panel(ax, kind, d, pnames, title):
    from manipulators.synthesis.rpr3_suite import PRESCRIBED3, SETTINGS, _Evaluator

    s = SETTINGS[kind]
    ev = _Evaluator(kind, PRESCRIBED3[pnames[0]])
    m, wss = ev(d)
    colors = plt_colors(len(wss))
    for w, c in zip(wss, colors):
        label = ("W^D" if s["dextrous"] else f"W^C[{math.degrees(w.info.get('phi', 0.0)):.0f} deg]")
        _draw_ws(ax, w, color=c, lw=1, label=label)
    for pn in pnames:
        pts = PRESCRIBED3[pn].points(400)
        pts = np.vstack([pts, pts[:1]])
        ax.plot(pts[:, 0], pts[:, 1], "k--", lw=0.8)
    if m is not None:
        _contours(ax, m, s["phis"][0], (0.0, 2.2, 0.6, 2.2))
    ax.set_aspect("equal")
    ax.set_xlim(-0.2, 2.4)
    ax.set_ylim(0.4, 2.3)
    ax.set_title(title, fontsize=8)
    ax.legend(fontsize=6, loc="lower left")


def plt_colors(n):
    import matplotlib.pyplot as plt

    return plt.cm.tab10(np.arange(n))


def _best_run(kind: str, pname: str, sub: pd.DataFrame):
    """The best f* among runs whose d* encloses W_p (exact check); else the least infeasible run."""
    from manipulators.synthesis.rpr3_suite import exact_enclosure

    best, best_key = None, None
    for _, r in sub.iterrows():
        x = np.asarray(r["x"], dtype=float)
        if x.shape != (5,) or not np.all(np.isfinite(x)):
            continue
        ex = exact_enclosure(kind, x, pname)
        key = (0, r["f"]) if ex["enclosed"] else (1, ex["ratio"])
        if best_key is None or key < best_key:
            best, best_key = r, key
    return best, best_key is not None and best_key[0] == 0


def figures(runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib.pyplot as plt

    from manipulators.synthesis.rpr3_suite import SETTINGS

    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    paths = _dextrous_figures(outdir)
    runs = runs[runs["suite"] == "rpr3"] if len(runs) and "suite" in runs else runs
    for kind in ("so", "mo", "d"):
        s = SETTINGS[kind]
        fig, ax = plt.subplots(figsize=(5, 4))
        _panel(
            ax,
            kind,
            np.asarray(s["start"]),
            ["P1", "P2", "P3"],
            f"{kind.upper()} synthesis start d0 {list(s['start'])}",
        )
        p = outdir / f"fig_{kind}_start.png"
        paths += save_figure(fig, p, dpi=130)
        if not len(runs):
            continue
        fig, axes = plt.subplots(1, 3, figsize=(13, 4))
        fig2, axes2 = plt.subplots(1, 3, figsize=(13, 3.5))
        for ax, ax2, pn in zip(axes, axes2, ("P1", "P2", "P3")):
            sub = runs[runs["problem"] == f"rpr3-{kind}-{pn.lower()}"]
            r, enclosed = _best_run(kind, pn, sub)
            if r is not None:
                _panel(ax, kind, np.asarray(r["x"], float), [pn],
                       f"{pn}: {r['solver']} f* = {-r['f']:.3f}" + ("" if enclosed else " (W_p NOT enclosed)"))
            look = solver_styles(sub["solver"])
            for _, r in sorted(sub.iterrows(), key=lambda ir: solver_order(ir[1]["solver"])):
                h = np.asarray(json.loads(r["history"]) or [[0, np.nan, np.nan]], dtype=float)
                ax2.plot(h[:, 0], -h[:, 1], lw=1, label=r["solver"], **look[r["solver"]])
            ax2.set_xlabel("N^fg")
            ax2.set_ylabel("min kappa^-1")
            ax2.set_title(pn, fontsize=8)
            ax2.legend(fontsize=6)
        fig.suptitle(f"{kind.upper()} synthesis optima (thesis Figs. {KIND_FIGS[kind]})", fontsize=9)
        fig2.suptitle(f"{kind.upper()} synthesis convergence histories", fontsize=9)
        for f_, name in ((fig, "optima"), (fig2, "histories")):
            p = outdir / f"fig_{kind}_{name}.png"
            paths += save_figure(f_, p, dpi=130)
    return paths
