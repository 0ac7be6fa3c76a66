"""``harness plot``: performance profiles, data profiles, convergence histories (PNG+SVG).

Figures go to ``DIR/<suite>/figures/``; every figure has labelled axes, a legend and a
title naming the suite and the metric.  ``--kind thesis`` hands the runs to the suite's
figure plug-in (`harness.figures`).  Uses matplotlib's Agg backend: no display needed.
"""

from __future__ import annotations

import os
import pathlib
import re

import numpy as np
import pandas as pd

from ._api import load_results
from ._plan import HarnessArgumentError
from ._profiles import best_so_far, data_profile, performance_profile, prepare_histories, solver_labels

__all__ = ["plot", "KINDS", "DATA_TAUS"]

KINDS = ("profile", "data-profile", "history", "thesis")
DATA_TAUS = (1e-1, 1e-3, 1e-5, 1e-7)
METRICS = {"nfg": "function+gradient evaluations $N^{fg}$", "wall_time_s": "wall time"}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, outdir: pathlib.Path, stem: str) -> list[pathlib.Path]:
    outdir.mkdir(parents=True, exist_ok=True)
    paths = [outdir / f"{stem}.png", outdir / f"{stem}.svg"]
    fig.savefig(paths[0], dpi=120, bbox_inches="tight")
    fig.savefig(paths[1], bbox_inches="tight")
    _plt().close(fig)
    return paths


def _profiles(suite: str, runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    plt = _plt()
    paths = []
    n_cases = runs["case_id"].nunique()
    for metric, what in METRICS.items():
        grid, rho = performance_profile(runs, metric)
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        for lab in rho.columns:
            ax.step(grid, rho[lab], where="post", label=lab)
        ax.set_xlabel(r"$\log_2 \tau$ (cost relative to the best solver)")
        ax.set_ylabel(r"fraction of problems solved, $\rho_s(\tau)$")
        ax.set_ylim(-0.02, 1.02)
        ax.set_title(f"{suite}: performance profile over {what} ({n_cases} cases)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize="small", loc="lower right")
        paths += _save(fig, outdir, f"profile_{metric.removesuffix('_s')}")
    return paths


def _data_profiles(suite: str, runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    plt = _plt()
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharey=True)
    prepared = prepare_histories(runs)
    for ax, tau in zip(axes.flat, DATA_TAUS):
        grid, d = data_profile(None, tau, prepared=prepared)
        for lab in d.columns:
            ax.step(grid, d[lab], where="post", label=lab)
        ax.set_title(rf"$\tau = 10^{{{int(np.log10(tau))}}}$")
        if grid[-1] > 50 * max(grid[1] if grid.size > 1 else 1.0, 1e-3):
            ax.set_xscale("log")  # budgets spanning decades: linear axes hide the fast solvers
        ax.set_xlabel(r"evaluations / $(n_p + 1)$")
        ax.set_ylabel("fraction of problems solved")
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
    axes.flat[0].legend(fontsize="small", loc="lower right")
    fig.suptitle(f"{suite}: data profiles (Moré–Wild), feasible f ≤ f_L + τ (f(x0) − f_L)")
    fig.tight_layout()
    return _save(fig, outdir, "data_profile")


def _slug(s: str) -> str:
    return re.sub(r"[^A-Za-z0-9.=_-]+", "_", s).strip("_")


def _histories(suite: str, runs: pd.DataFrame, outdir: pathlib.Path, problem: str | None) -> list[pathlib.Path]:
    plt = _plt()
    runs = runs[runs["status"] != "not_applicable"].assign(label=solver_labels(runs))
    if problem:
        sel = runs[(runs["problem"] == problem) | (runs["case_id"] == problem)]
        if sel.empty:
            raise HarnessArgumentError(f"no stored runs of problem {problem!r}; stored problems: "
                                       f"{', '.join(sorted(runs['problem'].unique()))}")
        runs = sel
    paths = []
    for case_id, grp in runs.groupby("case_id", sort=True):
        f_ref = grp["f_ref"].iloc[0]
        has_ref = bool(np.isfinite(f_ref))
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        for r in grp.itertuples():
            nfg, fb = best_so_far(r.history)
            ok = np.isfinite(fb)
            if not ok.any():
                continue
            y = np.maximum(fb[ok] - f_ref, 1e-17) if has_ref else fb[ok]
            ax.step(nfg[ok], y, where="post", label=f"{r.label} ({r.status})")
        if has_ref:
            ax.set_yscale("log")
            ax.set_ylabel(r"best feasible $f - f_{ref}$")
        else:
            ax.set_ylabel("best feasible f")
        ax.set_xscale("log")
        ax.set_xlabel("distinct evaluation points (N$^{fg}$)")
        ax.set_title(f"{suite} {case_id}: convergence history")
        ax.grid(alpha=0.3, which="both")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize="small")
        paths += _save(fig, outdir, f"history_{_slug(case_id)}")
    return paths


def plot(suite: str, kind: str, out: str | os.PathLike[str] = "results", problem: str | None = None,
         runs: pd.DataFrame | None = None) -> list[pathlib.Path]:
    """Draw figures of ``kind`` from stored runs; returns the written paths."""
    if kind not in KINDS:
        raise HarnessArgumentError(f"unknown plot kind {kind!r}; valid kinds: {', '.join(KINDS)}")
    runs = load_results(suite, out) if runs is None else runs
    outdir = pathlib.Path(out) / suite / "figures"
    if kind == "profile":
        return _profiles(suite, runs, outdir)
    if kind == "data-profile":
        return _data_profiles(suite, runs, outdir)
    if kind == "history":
        return _histories(suite, runs, outdir, problem)
    from .figures import thesis_figures

    return thesis_figures(suite, runs, outdir)
