"""Figures of suite ``tdpm`` (thesis Chapter 6), regenerated with matplotlib (Agg).

* ``fig_6_3``: minimum-norm (6.14, dashed) versus constrained-l2 (6.17, solid) workspaces
  of the robot with c = [+-1, +-0.15], phi = 0, 0.2, 0.4, chord method (load L1: the text
  gives no load for this figure [OWN]).
* ``fig_6_4`` / ``fig_6_5``: grid workspaces (Algorithm 6.2, m = 50) of the 3-cable
  robot (phi = 0, 0.05, 0.1) and the 4-cable robot (phi = -0.2, 0, 0.2: the text does not
  state Fig. 6.5's orientations; Fig. 6.9 mentions phi = -0.2 [OWN]) for loads L1-L3.
* ``fig_6_8`` / ``fig_6_9``: the same cases by the chord method (d = 0.05; d = 0.03 for
  the 3-cable phi = 0 cases with L2 and L3, d = 0.02 for 4 cables L3 at phi = -0.2,
  Section 6.4.3), bifurcation points marked.
* ``fig_6_10`` ... ``fig_6_15``: starting and optimized design with its dextrous
  workspace, for the best run of each load case in the stored runs (one figure per
  solver is not drawn: the best solver's run is shown; the thesis shows a representative
  Dynamic-Q run).
"""

from __future__ import annotations

import pathlib

import numpy as np
import pandas as pd

from harness.figures import save_figure

__all__ = ["figures"]

LOADS = ("L1", "L2", "L3")
PHIS = {3: (0.0, 0.05, 0.1), 4: (-0.2, 0.0, 0.2)}
SYNTH_FIGS = {(3, "L1"): "6_10", (3, "L2"): "6_11", (3, "L3"): "6_12",
              (4, "L1"): "6_13", (4, "L2"): "6_14", (4, "L3"): "6_15"}


def _frame(ax, robot):
    ax.plot([-1, 1, 1, -1, -1], [-1, -1, 1, 1, -1], color="0.6", lw=0.8)
    ax.plot(*robot.frame_points.T, "ks", ms=4)
    ax.set_aspect("equal")
    ax.set_xlim(-1.1, 1.1)
    ax.set_ylim(-1.1, 1.1)
    ax.tick_params(labelsize=6)


def _draw_grid(ax, ws):
    x, y = ws.grid
    X, Y = np.meshgrid(x, y)
    ax.plot(X[ws.mask], Y[ws.mask], ".", ms=1.2, color="tab:blue")


def _draw_chord(ax, ws, **kw):
    for r in ws.info.get("regions", [ws]):
        if r.n_boundary >= 3:
            b = np.vstack([r.boundary, r.boundary[:1]])
            ax.plot(b[:, 0], b[:, 1], **{"color": "tab:blue", "lw": 1.0, **kw})
            if r.bifurcations.size and kw.get("ls", "-") == "-":
                ax.plot(*r.bifurcations.T, "o", ms=2.5, color="tab:red")


def _save(fig, outdir: pathlib.Path, stem: str) -> pathlib.Path:
    return save_figure(fig, outdir / f"{stem}.png", dpi=150)[0]


def _grid_of_workspaces(n: int, method: str, outdir: pathlib.Path, stem: str, title: str) -> pathlib.Path:
    import matplotlib.pyplot as plt

    from manipulators.cable import loads, thesis_robot

    robot = thesis_robot(n)
    fig, axes = plt.subplots(3, 3, figsize=(7.5, 7.5))
    for i, load in enumerate(LOADS):
        for j, phi in enumerate(PHIS[n]):
            ax = axes[i, j]
            _frame(ax, robot)
            if method == "grid":
                ws = robot.workspace(phi, loads()[load], method="grid", resolution=50)
                _draw_grid(ax, ws)
            else:
                chord = 0.05
                if n == 3 and phi == 0.0 and load in ("L2", "L3"):
                    chord = 0.03
                if n == 4 and phi == -0.2 and load == "L3":
                    chord = 0.02
                ws = robot.workspace(phi, loads()[load], method="chord", chord=chord)
                _draw_chord(ax, ws)
            ax.set_title(f"{load}, phi = {phi:g}: A = {ws.area:.3f}", fontsize=7)
    fig.suptitle(title, fontsize=9)
    return _save(fig, outdir, stem)


def fig_6_3(outdir: pathlib.Path) -> pathlib.Path:
    import matplotlib.pyplot as plt

    from manipulators.cable import CableRobot, loads, thesis_robot

    robot = CableRobot(np.array([[1, 0.15], [-1, 0.15], [-1, -0.15], [1, -0.15]]), thesis_robot(4).platform_points)
    fig, axes = plt.subplots(1, 3, figsize=(9, 3.4))
    for ax, phi in zip(axes, (0.0, 0.2, 0.4)):
        _frame(ax, robot)
        ax.set_ylim(-1.1, 0.4)  # the chord workspace reaches below the frame points
        l2 = robot.workspace(phi, loads()["L1"], method="chord", chord=0.02, tensions="l2")
        mn = robot.workspace(phi, loads()["L1"], method="chord", chord=0.02, tensions="min-norm")
        _draw_chord(ax, l2)
        _draw_chord(ax, mn, ls="--", color="k")
        ax.set_title(f"phi = {phi:g}: l2 {l2.area:.3f}, min-norm {mn.area:.3f}", fontsize=7)
    fig.suptitle("Fig. 6.3: minimum-norm (dashed) vs constrained l2-norm (solid) workspaces, L1", fontsize=9)
    return _save(fig, outdir, "fig_6_3")


def _synthesis_figs(runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib.pyplot as plt

    from manipulators.cable import design_robot, loads
    from manipulators.synthesis.tdpm_suite import SETTINGS, SUITE

    out: list[pathlib.Path] = []
    if runs is None or runs.empty or "problem" not in runs:
        return out
    for (n, load), num in SYNTH_FIGS.items():
        sub = runs[(runs.problem == f"tdpm{n}-{load.lower()}") & np.isfinite(runs.f)]
        if sub.empty:
            continue
        best = sub.loc[sub.f.idxmin()]
        try:
            d0 = SUITE.case(best.case_id).problem.x0
        except KeyError:
            continue
        s = SETTINGS[n]
        fig, axes = plt.subplots(1, 2, figsize=(7, 3.6))
        for ax, d, lab in ((axes[0], d0, "(a) start"), (axes[1], np.asarray(best.x, dtype=float), "(b) optimized")):
            robot = design_robot(d)
            ws = robot.dextrous_workspace(s["phi"][0], s["phi"][1], loads()[load],
                                          resolution=s["resolution"], slices=s["slices"])
            _frame(ax, robot)
            _draw_grid(ax, ws)
            for c in robot.frame_points:
                ax.plot([c[0], 0], [c[1], 0], color="0.75", lw=0.6)
            ax.set_title(f"{lab}: d = [{', '.join(f'{v:.3f}' for v in d)}]\nA_d = {ws.area:.4f}", fontsize=7)
        fig.suptitle(f"Fig. {num.replace('_', '.')}: {n}-cable TDPM, {load} ({best.solver}, {best.start})", fontsize=9)
        out.append(_save(fig, outdir, f"fig_{num}"))
    return out


def figures(runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    """All Chapter 6 figures; the synthesis figures only for load cases present in ``runs``."""
    import matplotlib

    matplotlib.use("Agg")
    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    paths = [
        fig_6_3(outdir),
        _grid_of_workspaces(3, "grid", outdir, "fig_6_4", "Fig. 6.4: 3-cable TDPM, discretization method (m = 50)"),
        _grid_of_workspaces(4, "grid", outdir, "fig_6_5", "Fig. 6.5: 4-cable TDPM, discretization method (m = 50)"),
        _grid_of_workspaces(3, "chord", outdir, "fig_6_8", "Fig. 6.8: 3-cable TDPM, chord method"),
        _grid_of_workspaces(4, "chord", outdir, "fig_6_9", "Fig. 6.9: 4-cable TDPM, chord method"),
    ]
    return paths + _synthesis_figs(runs, outdir)
