"""Figure for suite ``rpr3-spread`` (Fig. 5.4s): the 3-RPR MO and D ends from d0 and from
starts within 1e-6 of it.

One panel per synthesis (MO, D): every run's f* = min kappa^-1 above its prescribed
workspace, one colour per solver (the run from d0 as a diamond), filled where W_p is
enclosed in exact geometry (`rpr3_suite.exact_enclosure`, as Tables 5.4s-5.5s) and hollow
where it is not; the exact model's local optimum from d0 (dashed) and best design found
(solid) from the suite's stored reference, and the 0.01 band below the local optimum.
"""

from __future__ import annotations

import math
import pathlib

import numpy as np
import pandas as pd

from harness._styles import solver_styles

__all__ = ["figures"]


def figures(runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib.pyplot as plt

    from harness._reference import load_reference
    from harness.figures import finish
    from harness.tables.rpr2 import _decoded
    from harness.tables.rpr2_spread import _solver_order
    from harness.tables.rpr3 import F_TOL
    from harness.tables.rpr3_spread import _enclosed
    from manipulators.synthesis._spread import parse_start
    from manipulators.synthesis.rpr3_spread_suite import EPS, KINDS, PRESCRIBED

    runs = _decoded(runs) if runs is not None else runs
    if runs is None or runs.empty:
        return []
    outdir = pathlib.Path(outdir)
    # the figures directory is <out>/<suite>/figures: the reference sits beside it
    optima = dict(load_reference(outdir.parent.parent, "rpr3-spread").get("exact_optimum") or {})
    solvers = sorted(runs["solver"].unique(), key=_solver_order)
    colors = {k: v["color"] for k, v in solver_styles(solvers).items()}
    width = 0.6 / max(len(solvers), 1)
    fig, axes = plt.subplots(1, len(KINDS), figsize=(5 * len(KINDS), 4))
    for ax, kind in zip(np.atleast_1d(axes), KINDS):
        for i, pname in enumerate(PRESCRIBED):
            sub = runs[runs["problem"] == f"rpr3-{kind}-{pname.lower()}"]
            for j, solver in enumerate(solvers):
                g = sub[sub["solver"] == solver]
                kinv = np.array([-float(v) if v is not None else math.nan for v in g["f"]])
                enc = np.array([_enclosed(kind, np.asarray(x, dtype=float), pname) for x in g["x"]], dtype=bool)
                ks = np.array([parse_start(s)[1] for s in g["start"]], dtype=int)
                centre = i - 0.3 + width * (j + 0.5)
                pos = centre + (0.8 * width * (ks / max(ks.max(initial=0), 1) - 0.5) if ks.size else ks)
                for mask, marker, ms, label in ((ks > 0, "o", 5, "perturbed start"), (ks == 0, "D", 7, "d0")):
                    for inside, face in ((True, colors[solver]), (False, "white")):
                        m = mask & (enc == inside)
                        first = i == 0 and inside
                        ax.plot(pos[m] if marker == "o" else np.full(m.sum(), centre), kinv[m], marker, ms=ms,
                                color=colors[solver], mfc=face, alpha=0.8, ls="none",
                                label=f"{solver}, {label}" if first else None)
            opt = optima.get(f"{kind}/{pname}") or {}
            local, best = float(opt.get("local_kinv", math.nan)), float(opt.get("kinv", math.nan))
            if math.isfinite(local):
                ax.hlines(local, i - 0.35, i + 0.35, color="k", ls="--", lw=1,
                          label="exact local optimum from d0" if i == 0 else None)
                ax.fill_between([i - 0.35, i + 0.35], local - F_TOL, local, color="k", alpha=0.08,
                                label=f"within {F_TOL} of it" if i == 0 else None)
            if math.isfinite(best) and abs(best - local) > F_TOL:
                ax.hlines(best, i - 0.35, i + 0.35, color="k", lw=1.5,
                          label="exact best design found" if i == 0 else None)
        ax.set_xticks(range(len(PRESCRIBED)), PRESCRIBED)
        ax.set_xlabel("prescribed workspace W_p")
        ax.set_ylabel("f* = min kappa^-1 over W_p")
        ax.set_title(f"{kind.upper()} synthesis (Table {'5.4' if kind == 'mo' else '5.5'}s); hollow: W_p not enclosed")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6)
    return finish(fig, f"{', '.join(solvers)} from d0 and from starts within {EPS:g} of it",
                  outdir / "fig_5_4s_spread.png")
