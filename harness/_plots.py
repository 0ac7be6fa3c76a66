"""``harness plot``: performance profiles, data profiles, convergence histories (PNG+SVG).

Figures go to ``DIR/<suite>/figures/``; every figure has labelled axes, a legend and a
title naming the suite and the metric.  ``--kind thesis`` hands the runs to the suite's
figure plug-in (`harness.figures`).  Uses matplotlib's Agg backend: no display needed.
"""

from __future__ import annotations

import os
import pathlib
import re
import time
from typing import TextIO

import numpy as np
import pandas as pd

from ._api import load_results
from ._plan import HarnessArgumentError
from ._profiles import (
    FEAS_TOL,
    best_so_far,
    data_profile,
    performance_profile,
    prepare_histories,
    reference_data_profile,
    solver_labels,
)
from ._styles import solver_order, solver_styles
from .figures import save_figure

__all__ = ["plot", "KINDS", "DATA_TAUS"]

KINDS = ("profile", "data-profile", "history", "thesis", "log-ratio")
#: suites whose runs count as solved by the campaign rule (harness/tables/_campaign.py), not by the
#: solver's own convergence flag: library campaigns where "converged" alone means little
CAMPAIGN_SUITES = ("cutest", "hs-all")
#: (thesis solver, established solver) pairs of the log-ratio profiles, where both ran
LOG_RATIO_PAIRS = (("dynamic-q", "scipy-slsqp"), ("dynamic-q-plus", "scipy-slsqp"), ("dynamic-q", "ipopt"),
                   ("lfopc", "ipopt"),
                   ("etopc", "ipopt"), ("sqsd", "scipy-bfgs"))
REFERENCE_ER = 1e-5  # E^r of a solved run in the thesis's tables (eq. 3.12)
DATA_TAUS = (1e-1, 1e-3, 1e-5, 1e-7)
METRICS = {"nfg": "function+gradient evaluations $N^{fg}$", "wall_time_s": "wall time"}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, outdir: pathlib.Path, stem: str) -> list[pathlib.Path]:
    return save_figure(fig, outdir / f"{stem}.png", svg=True)


def _legend(ax, n: int, outside: bool | None = None) -> None:
    """Inside the axes for a few solvers; to the right of them for many (campaigns)."""
    if outside if outside is not None else n > 6:
        ax.legend(fontsize="small", loc="center left", bbox_to_anchor=(1.01, 0.5))
    else:
        ax.legend(fontsize="small", loc="lower right")


MIN_SUBSET = 10  # smallest part of a campaign that gets its own profiles


def campaign_parts(runs: pd.DataFrame) -> list[tuple[str, str, pd.DataFrame]]:
    """(file suffix, title note, runs) for each part of a campaign that only some solvers handle.

    The suffix names the part by the first (alphabetically) of the solvers that handle
    exactly it, so file names stay the same when the selection grows.

    Over a library, the unconstrained methods (SQSD, CG, BFGS) run on the unconstrained
    problems only and L-BFGS-B on those with bounds: in a profile over every case they can
    reach at most that fraction, which says nothing about them.  Each distinct set of cases a
    solver handles (`not_applicable` rows excluded), other than the largest, gets its own
    profiles over that set, with every solver that handles all of it.
    """
    labels = solver_labels(runs)
    handled = runs["status"].astype(str) != "not_applicable"
    sets = {lab: frozenset(runs.loc[handled & (labels == lab), "case_id"]) for lab in labels.unique()}
    distinct = sorted(set(sets.values()), key=lambda c: (-len(c), sorted(c)))
    parts = []
    for cases in distinct[1:]:
        if len(cases) < MIN_SUBSET:
            continue
        keep = [lab for lab, c in sets.items() if cases <= c]
        defining = sorted(lab for lab, c in sets.items() if c == cases)
        sub = runs[runs["case_id"].isin(cases) & labels.isin(keep)]
        parts.append((f"_cases_of_{_slug(defining[0])}", f"the {len(cases)} cases {', '.join(defining)} handle",
                      sub))
    return parts


def _profiles(suite: str, runs: pd.DataFrame, outdir: pathlib.Path, suffix: str = "",
              note: str = "") -> list[pathlib.Path]:
    plt = _plt()
    paths = []
    n_cases = runs["case_id"].nunique()
    for metric, what in METRICS.items():
        grid, rho = performance_profile(runs, metric)
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        look = solver_styles(rho.columns)
        for lab in sorted(rho.columns, key=solver_order):
            ax.step(grid, rho[lab], where="post", label=f"{lab} ({rho[lab].iloc[-1]:.0%})", **look[lab])
        ax.set_xlabel(r"$\log_2 \tau$ (cost relative to the best solver)")
        ax.set_ylabel(r"fraction of problems solved, $\rho_s(\tau)$")
        ax.set_ylim(-0.02, 1.02)
        ax.set_title(f"{suite}: performance profile over {what}\n({note})" if note
                     else f"{suite}: performance profile over {what} ({n_cases} cases)")
        ax.grid(alpha=0.3)
        _legend(ax, len(rho.columns))
        paths += _save(fig, outdir, f"profile_{metric.removesuffix('_s')}{suffix}")
    return paths


def _data_profiles(suite: str, runs: pd.DataFrame, outdir: pathlib.Path, suffix: str = "",
                   note: str = "") -> list[pathlib.Path]:
    plt = _plt()
    paths: list[pathlib.Path] = []
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharey=True)
    prepared = prepare_histories(runs)
    look = solver_styles(prepared["labels"])
    for ax, tau in zip(axes.flat, DATA_TAUS):
        grid, d = data_profile(None, tau, prepared=prepared)
        for lab in sorted(d.columns, key=solver_order):
            ax.step(grid, d[lab], where="post", label=lab, **look[lab])
        ax.set_title(rf"$\tau = 10^{{{int(np.log10(tau))}}}$")
        if grid[-1] > 50 * max(grid[1] if grid.size > 1 else 1.0, 1e-3):
            ax.set_xscale("log")  # budgets spanning decades: linear axes hide the fast solvers
        ax.set_xlabel(r"evaluations / $(n_p + 1)$")
        ax.set_ylabel("fraction of problems solved")
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
    n_labels = len(prepared["labels"])
    _legend(axes.flat[1] if n_labels > 6 else axes.flat[0], n_labels)
    fig.suptitle(f"{suite}: data profiles (Moré–Wild), feasible f ≤ f_L + τ (f(x0) − f_L)"
                 + (f"\n{note}" if note else ""))
    fig.tight_layout()
    paths += _save(fig, outdir, f"data_profile{suffix}")
    if not suffix and np.isfinite(pd.to_numeric(runs["f_ref"], errors="coerce")).any():
        paths += _reference_data_profile(suite, runs, outdir)
    return paths


def _reference_data_profile(suite: str, runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    """The tables' rule (E^r <= 1e-5 against the known optimum, feasible) as a data profile:
    its final values are the tables' solved fractions."""
    plt = _plt()
    grid, d = reference_data_profile(runs, er_tol=REFERENCE_ER, feas_tol=FEAS_TOL)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    look = solver_styles(d.columns)
    for lab in sorted(d.columns, key=solver_order):
        ax.step(grid, d[lab], where="post", label=f"{lab} ({d[lab].iloc[-1]:.0%})", **look[lab])
    if grid[-1] > 50 * max(grid[1] if grid.size > 1 else 1.0, 1e-3):
        ax.set_xscale("log")
    ax.set_xlabel(r"evaluations / $(n_p + 1)$")
    ax.set_ylabel("fraction of problems solved")
    ax.set_ylim(-0.02, 1.02)
    ax.grid(alpha=0.3)
    _legend(ax, len(d.columns))
    ax.set_title(f"{suite}: solved as in the tables (E^r ≤ {REFERENCE_ER:g} vs f_ref, violation ≤ {FEAS_TOL:g})")
    fig.tight_layout()
    return _save(fig, outdir, "data_profile_reference")


def _slug(s: str) -> str:
    return re.sub(r"[^A-Za-z0-9.=_-]+", "_", s).strip("_")


def _log_ratios(suite: str, runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    """Morales (2002) log-ratio profiles: per problem log2(N^fg_a / N^fg_b), sorted; a problem only
    one of the two solved sits at the end of the scale, one neither solved is left out."""
    from ._profiles import cost_matrix

    plt = _plt()
    t = cost_matrix(runs, "nfg")
    paths: list[pathlib.Path] = []
    for a, b in LOG_RATIO_PAIRS:
        if a not in t.columns or b not in t.columns:
            continue
        ta, tb = t[a].to_numpy(), t[b].to_numpy()
        keep = np.isfinite(ta) | np.isfinite(tb)
        if not keep.any():
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.log2(ta[keep] / tb[keep])
        finite = r[np.isfinite(r)]
        cap = max(1.0, float(np.max(np.abs(finite))) if finite.size else 1.0) * 1.1
        r = np.sort(np.clip(np.nan_to_num(r, posinf=cap, neginf=-cap), -cap, cap))
        fig, ax = plt.subplots(figsize=(7, 3.6))
        ax.bar(np.arange(r.size), r, width=1.0, color=np.where(r < 0, "C0", "C3"))
        ax.axhline(0, color="k", lw=0.6)
        ax.set_xlabel(f"problems solved by {a} or {b} (sorted)")
        ax.set_ylabel(f"log2(N^fg {a} / N^fg {b})")
        ax.set_title(f"{suite}: {a} cheaper (below 0, {int((r < 0).sum())}) vs {b} cheaper "
                     f"(above 0, {int((r > 0).sum())}); bars at ±{cap:.1f}: solved by one only", fontsize=9)
        ax.grid(alpha=0.3, axis="y")
        paths += _save(fig, outdir, f"log_ratio_{a}_vs_{b}")
    if not paths:  # say why nothing was drawn instead of exiting 0 with no file
        pairs = ", ".join(f"{a} vs {b}" for a, b in LOG_RATIO_PAIRS)
        raise HarnessArgumentError(f"no log-ratio profile to draw for {suite}: it needs both solvers of one of the "
                                   f"pairs {pairs} stored, with a case solved by either; stored solvers: "
                                   f"{', '.join(sorted(map(str, t.columns))) or 'none'}")
    return paths


def _histories(suite: str, runs: pd.DataFrame, outdir: pathlib.Path, problem: str | None,
               progress: TextIO | None = None) -> list[pathlib.Path]:
    plt = _plt()
    runs = runs[runs["status"] != "not_applicable"].assign(label=solver_labels(runs))
    if problem:
        sel = runs[(runs["problem"] == problem) | (runs["case_id"] == problem)]
        if sel.empty:
            raise HarnessArgumentError(f"no stored runs of problem {problem!r}; stored problems: "
                                       f"{', '.join(sorted(runs['problem'].unique()))}")
        runs = sel
    paths = []
    groups = list(runs.groupby("case_id", sort=True))
    t0 = last = time.perf_counter()
    for i, (case_id, grp) in enumerate(groups, 1):
        if progress is not None and (time.perf_counter() - last > 2.0 or i in (1, len(groups))):
            print(f"plot history: [{i}/{len(groups)}] {case_id} ({time.perf_counter() - t0:.0f} s)",
                  file=progress, flush=True)
            last = time.perf_counter()
        f_ref = grp["f_ref"].iloc[0]
        has_ref = bool(np.isfinite(f_ref))
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        look = solver_styles(grp["label"])
        for r in sorted(grp.itertuples(), key=lambda r: solver_order(r.label)):
            nfg, fb = best_so_far(r.history)
            ok = np.isfinite(fb)
            if not ok.any():  # say so in the legend rather than leave the solver out silently
                ax.plot([], [], " ", label=f"{r.label} ({r.status}; no feasible point recorded)")
                continue
            y = np.maximum(fb[ok] - f_ref, 1e-17) if has_ref else fb[ok]
            ax.step(nfg[ok], y, where="post", label=f"{r.label} ({r.status})", **look[r.label])
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
         runs: pd.DataFrame | None = None, progress: TextIO | None = None) -> list[pathlib.Path]:
    """Draw figures of ``kind`` from stored runs; returns the written paths.

    progress : stream for progress lines of long plots (history plots of many cases).
    """
    if kind not in KINDS:
        raise HarnessArgumentError(f"unknown plot kind {kind!r}; valid kinds: {', '.join(KINDS)}")
    runs = load_results(suite, out) if runs is None else runs
    if suite in CAMPAIGN_SUITES:
        from ._best_known import best_known_values
        from ._reference import load_reference
        from .tables._campaign import classify_runs

        known = best_known_values(load_reference(out, suite))  # the tables' reference values
        runs = runs.assign(success=(classify_runs(runs, known)["outcome"] == "solved").to_numpy())
    outdir = pathlib.Path(out) / suite / "figures"
    if kind == "log-ratio":
        return _log_ratios(suite, runs, outdir)
    if kind in ("profile", "data-profile"):
        draw = _profiles if kind == "profile" else _data_profiles
        paths = draw(suite, runs, outdir)
        for suffix, note, part in campaign_parts(runs) if suite in CAMPAIGN_SUITES else ():
            paths += draw(suite, part, outdir, suffix, note)
        return paths
    if kind == "history":
        return _histories(suite, runs, outdir, problem, progress)
    from .figures import thesis_figures

    return thesis_figures(suite, runs, outdir)
