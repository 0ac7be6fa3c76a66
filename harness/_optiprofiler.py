"""Export a stored campaign in OptiProfiler's results layout, so its profile code can draw it.

OptiProfiler (Ragonneau & Zhang) keeps one ``results_plib`` dictionary per problem library,
with per-evaluation histories of shape (problems, solvers, runs, evaluations) and saves it
with ``optiprofiler.loader.save_results_to_h5``.  This module builds that dictionary from
the harness's runs (one run per case and solver, so ``runs`` = 1) and writes it with
OptiProfiler's own writer.  A run's history ``[[nfg, f, max_violation], ...]`` is expanded
to one value per counted evaluation (the best point so far is OptiProfiler's business; we
give it the point evaluated at each count, held until the next recorded one).
"""

from __future__ import annotations

import json
import os

import numpy as np
import pandas as pd

from ._plan import HarnessArgumentError

__all__ = ["export_optiprofiler", "to_optiprofiler"]


def _expand(history_json: str, length: int) -> tuple[np.ndarray, np.ndarray]:
    """Per-evaluation f and max-violation of one run, padded with its last value to `length`."""
    rows = np.asarray(json.loads(history_json) or [], dtype=float).reshape(-1, 3)
    fun = np.full(length, np.nan)
    cv = np.full(length, np.nan)
    if len(rows) == 0:
        return fun, cv
    counts = np.clip(rows[:, 0].astype(int), 1, None)
    # index k (0-based) takes the latest recorded entry with count <= k + 1
    k = np.arange(1, length + 1)
    pos = np.searchsorted(counts, k, side="right") - 1
    pos = np.clip(pos, 0, len(rows) - 1)
    fun[:] = rows[pos, 1]
    cv[:] = np.maximum(rows[pos, 2], 0.0)
    return fun, cv


def to_optiprofiler(runs: pd.DataFrame, plib: str = "haybench") -> dict:
    """OptiProfiler's ``results_plib`` dictionary of a campaign's runs (one row per case and solver)."""
    if runs.empty:
        raise HarnessArgumentError("no runs to export")
    # failed runs (error, time-out, lost worker) may carry no counts or history: zero evaluations
    runs = runs.assign(nfg=pd.to_numeric(runs["nfg"], errors="coerce").fillna(0).astype(int),
                       f=pd.to_numeric(runs["f"], errors="coerce").astype(float),
                       max_violation=pd.to_numeric(runs["max_violation"], errors="coerce").astype(float),
                       wall_time_s=pd.to_numeric(runs["wall_time_s"], errors="coerce").astype(float),
                       history=runs["history"].fillna("[]"))
    solvers = sorted(runs["solver"].unique())
    cases = sorted(runs["case_id"].unique())
    length = max(1, int(runs["nfg"].max()))
    n_p, n_s = len(cases), len(solvers)
    fun_h = np.full((n_p, n_s, 1, length), np.nan)
    cv_h = np.full((n_p, n_s, 1, length), np.nan)
    fun_out = np.full((n_p, n_s, 1), np.nan)
    cv_out = np.full((n_p, n_s, 1), np.nan)
    n_evals = np.zeros((n_p, n_s, 1), dtype=int)
    times = np.full((n_p, n_s, 1), np.nan)
    fun_init = np.full(n_p, np.nan)
    cv_init = np.full(n_p, np.nan)
    dims = np.zeros(n_p, dtype=int)
    ci = {c: i for i, c in enumerate(cases)}
    si = {s: j for j, s in enumerate(solvers)}
    for r in runs.itertuples(index=False):
        i, j = ci[r.case_id], si[r.solver]
        fun_h[i, j, 0], cv_h[i, j, 0] = _expand(r.history, length)
        fun_out[i, j, 0] = r.f
        cv_out[i, j, 0] = r.max_violation
        n_evals[i, j, 0] = int(r.nfg)
        times[i, j, 0] = r.wall_time_s
        dims[i] = int(r.n)
        first = json.loads(r.history or "[]")
        if first and np.isnan(fun_init[i]):
            fun_init[i], cv_init[i] = first[0][1], max(first[0][2], 0.0)
    return {
        "plib": plib, "solver_names": solvers, "problem_names": cases, "problem_dims": dims,
        "fun_histories": fun_h, "maxcv_histories": cv_h, "fun_outs": fun_out, "maxcv_outs": cv_out,
        "fun_inits": fun_init, "maxcv_inits": cv_init, "n_evals": n_evals, "computation_times": times,
    }


def export_optiprofiler(runs: pd.DataFrame, path: str | os.PathLike[str], plib: str = "haybench") -> str:
    """Write a campaign as an OptiProfiler HDF5 archive (its ``save_results_to_h5``); returns the path."""
    from optiprofiler.loader import save_results_to_h5

    save_results_to_h5([to_optiprofiler(runs, plib)], str(path))
    return str(path)
