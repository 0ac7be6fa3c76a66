"""Figure for suite ``rpr2-spread``: the O and E ends from starts within 1e-6 of SP1-SP4.

One panel per formulation: every run's f* above its thesis start, one colour per solver
(Dynamic-Q left, Dynamic-Q+ right of the start's position; the start itself as a larger
marker), the thesis's Dynamic-Q f* as a red bar, the acceptance band of the table (O:
f* <= 0.66; E: within 5 % of the thesis) and, for E, Dynamic-Q+'s target f* <= 3.2.
"""

from __future__ import annotations

import pathlib

import numpy as np
import pandas as pd

from harness._styles import solver_styles

__all__ = ["figures"]


def figures(runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib.pyplot as plt

    from harness.figures import finish
    from harness.tables.rpr2 import E_REL, E_TARGET, O_LIMIT
    from harness.tables.rpr2_spread import KINDS, _solver_order, _thesis_f
    from manipulators.synthesis.rpr2_spread_suite import EPS, parse_start
    from manipulators.synthesis.rpr2_suite import STARTS

    if runs is None or runs.empty:
        return []
    th = _thesis_f()
    solvers = sorted(runs["solver"].unique(), key=_solver_order)
    colors = {k: v["color"] for k, v in solver_styles(solvers).items()}
    width = 0.6 / max(len(solvers), 1)  # each solver's strip within the start's slot
    starts = list(STARTS)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, (pid, (label, kind)) in zip(axes, KINDS.items()):
        sub = runs[runs["problem"] == pid]
        for i, sp in enumerate(starts):
            for j, solver in enumerate(solvers):
                g = sub[np.array([parse_start(s)[0] == sp for s in sub["start"]], dtype=bool)
                        & (sub["solver"] == solver).to_numpy()]
                ks = np.array([parse_start(s)[1] for s in g["start"]])
                f = g["f"].to_numpy(dtype=float)
                centre = i - 0.3 + width * (j + 0.5)
                jitter = 0.8 * width * (ks / max(ks.max(), 1) - 0.5) if len(ks) else ks
                ax.plot(centre + jitter[ks > 0], f[ks > 0], "o", ms=4, color=colors[solver], alpha=0.7,
                        label=f"{solver}, perturbed start" if i == 0 else None)
                ax.plot(np.full((ks == 0).sum(), centre), f[ks == 0], "D", ms=7, color=colors[solver], mfc="white",
                        label=f"{solver}, thesis start" if i == 0 else None)
            f_th = th.get((pid, sp))
            if f_th is not None:
                ax.hlines(f_th, i - 0.3, i + 0.3, color="k", lw=2, label="thesis f*" if i == 0 else None)
                if kind == "e":
                    ax.fill_between([i - 0.3, i + 0.3], f_th * (1 - E_REL), f_th * (1 + E_REL), color="0.5",
                                    alpha=0.15, label=f"thesis +-{E_REL:.0%}" if i == 0 else None)
        if kind == "o":
            ax.axhline(O_LIMIT, color="k", ls="--", lw=1, label=f"acceptance f* <= {O_LIMIT}")
        else:
            ax.axhline(E_TARGET, color="0.3", ls="--", lw=1, label=f"Dynamic-Q+ target f* <= {E_TARGET}")
        ax.set_xticks(range(len(starts)), starts)
        ax.set_ylabel("f* (triangle scheme)")
        ax.set_title(f"{label} synthesis ({'Tables 4.3-4.6' if kind == 'o' else 'Table 4.7'})")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    return finish(fig, f"{', '.join(solvers)} from SP1-SP4 and from starts within {EPS:g} of them",
                  pathlib.Path(outdir) / "fig_4_7s_spread.png")
