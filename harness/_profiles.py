"""Benchmark profiles computed from stored runs (no plotting here).

* Dolan & Moré (2002) performance profiles: for problem p and solver s the cost t_ps
  (N^fg or wall time) of a *successful* run, infinity otherwise (unsolved, error,
  time-out, not applicable); ratio r_ps = t_ps / min_s t_ps;
  rho_s(tau) = |{p : log2 r_ps <= tau}| / |P|.
* Moré & Wild (2009) data profiles: a run solves p at tolerance tau after the first
  evaluation at which a feasible point satisfies f <= f_L + tau (f(x0) - f_L), f_L the
  best feasible f any solver found on p; d_s(alpha) = |{p : t_ps / (n_p + 1) <= alpha}| / |P|.

Each case (problem, n, start, variant) is one "problem" p.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

__all__ = ["solver_labels", "performance_profile", "data_profile", "reference_data_profile", "best_so_far",
           "history_array", "FEAS_TOL"]

FEAS_TOL = 1e-6


def solver_labels(runs: pd.DataFrame) -> pd.Series:
    """Solver id, with the command-line options of the run if any (``sqsd[rho=0.1]``).

    Options a suite sets per case (e.g. SQSD's rho per problem) do not split a solver.
    """
    over = runs["overrides"] if "overrides" in runs else pd.Series("", index=runs.index)

    def label(solver: str, text: str) -> str:
        if not text:
            return solver
        opts = json.loads(text)
        return f"{solver}[{','.join(f'{k}={v}' for k, v in sorted(opts.items()))}]"

    return pd.Series([label(s, o or "") for s, o in zip(runs["solver"], over)], index=runs.index)


def cost_matrix(runs: pd.DataFrame, metric: str) -> pd.DataFrame:
    """t_ps: cases x solver labels; inf where the run did not succeed or is missing."""
    df = runs.assign(label=solver_labels(runs))
    cost = pd.to_numeric(df[metric], errors="coerce").astype(float)
    cost = cost.where(df["success"].astype(bool) & np.isfinite(cost), np.inf)
    # a zero cost (possible for wall time rounding) would make ratios undefined
    cost = cost.clip(lower=np.finfo(float).tiny)
    t = pd.DataFrame({"case_id": df["case_id"], "label": df["label"], "t": cost})
    return t.pivot_table(index="case_id", columns="label", values="t", aggfunc="min").fillna(np.inf)


def performance_profile(runs: pd.DataFrame, metric: str = "nfg") -> tuple[np.ndarray, pd.DataFrame]:
    """(log2-tau grid, rho) with rho: one column per solver label, one row per tau."""
    t = cost_matrix(runs, metric)
    best = t.min(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.log2(t.to_numpy() / best.to_numpy()[:, None])
    ratio[~np.isfinite(ratio)] = np.inf  # unsolved by s, or by every solver
    finite = ratio[np.isfinite(ratio)]
    top = max(1.0, float(finite.max()) * 1.05) if finite.size else 1.0
    grid = np.unique(np.concatenate([[0.0, top], finite]))
    rho = (ratio[:, :, None] <= grid[None, None, :]).mean(axis=0).T
    return grid, pd.DataFrame(rho, columns=t.columns)


def history_array(history_json: str) -> np.ndarray:
    """A stored history as an (m, 3) array of [nfg, f, max_violation]."""
    rows = json.loads(history_json or "[]")
    return np.asarray(rows, dtype=float).reshape(-1, 3) if rows else np.empty((0, 3))


def best_so_far(history: str | np.ndarray, feas_tol: float = FEAS_TOL) -> tuple[np.ndarray, np.ndarray]:
    """(nfg, best feasible f so far) from a stored history [[nfg, f, viol], ...]."""
    h = history_array(history) if isinstance(history, str) else history
    if h.size == 0:
        return np.empty(0), np.empty(0)
    f = np.where((h[:, 2] <= feas_tol) & np.isfinite(h[:, 1]), h[:, 1], np.inf)
    return h[:, 0], np.minimum.accumulate(f)


def prepare_histories(runs: pd.DataFrame) -> dict:
    """Parse every history once (data profiles at several tolerances reuse it)."""
    df = runs.assign(label=solver_labels(runs))
    df = df[df["status"] != "not_applicable"]
    curves: dict[tuple[str, str], tuple[np.ndarray, np.ndarray, int]] = {}
    f0: dict[str, float] = {}
    for r in df.itertuples():
        h = history_array(r.history)
        nfg, fb = best_so_far(h)
        curves[(r.case_id, r.label)] = (nfg, fb, int(r.n))
        if nfg.size and r.case_id not in f0:
            f0[r.case_id] = float(h[0, 1])  # f(x0): every solver's first evaluation is x0
    return {"curves": curves, "f0": f0, "labels": sorted(df["label"].unique()),
            "cases": sorted({c for c, _ in curves})}


def data_profile(runs: pd.DataFrame | None, tau: float, alpha_max: float | None = None,
                 prepared: dict | None = None) -> tuple[np.ndarray, pd.DataFrame]:
    """(alpha grid in simplex gradients (n_p + 1) evaluations, d_s(alpha) per solver label)."""
    prep = prepared if prepared is not None else prepare_histories(runs)
    curves, f0, labels, cases = prep["curves"], prep["f0"], prep["labels"], prep["cases"]
    fl = {c: np.inf for c in cases}
    for (c, _), (_, fb, _) in curves.items():
        if fb.size:
            fl[c] = min(fl[c], float(fb[-1]))
    t = np.full((len(cases), len(labels)), np.inf)
    for i, c in enumerate(cases):
        if c not in f0 or not np.isfinite(fl[c]) or not np.isfinite(f0[c]):
            continue
        target = fl[c] + tau * (f0[c] - fl[c])
        for j, lab in enumerate(labels):
            nfg, fb, n = curves.get((c, lab), (np.empty(0), np.empty(0), 1))
            hit = np.flatnonzero(fb <= target)
            if hit.size:
                t[i, j] = nfg[hit[0]] / (n + 1)
    finite = t[np.isfinite(t)]
    top = alpha_max or (max(1.0, float(finite.max()) * 1.05) if finite.size else 1.0)
    grid = np.unique(np.concatenate([[0.0, top], finite[finite <= top]]))
    d = (t[:, :, None] <= grid[None, None, :]).mean(axis=0).T if len(cases) else np.zeros((grid.size, len(labels)))
    return grid, pd.DataFrame(d, columns=labels)


def reference_data_profile(runs: pd.DataFrame, er_tol: float = 1e-5, feas_tol: float = 1e-5,
                           ) -> tuple[np.ndarray, pd.DataFrame]:
    """Data profile against the known optimum, by the rule of the thesis's tables: a point
    solves p when its violation is <= ``feas_tol`` and E^r = |f_ref - f| / (1 + |f_ref|) <=
    ``er_tol`` (eq. 3.12).  Cases without a finite f_ref are left out.

    A run solves p only if the point it *returns* passes the test, as in the tables (a run
    that passed through the optimum and then returned another point has not solved p); its
    cost is the first evaluation at which its history passed the test, or all its
    evaluations when the returned point was never evaluated (e.g. projected onto the
    bounds).  So the final value of each curve is the tables' solved fraction.
    """
    df = runs.assign(label=solver_labels(runs))
    df = df[(df["status"] != "not_applicable") & np.isfinite(pd.to_numeric(df["f_ref"], errors="coerce"))]
    labels = sorted(df["label"].unique())
    cases = sorted(df["case_id"].unique())
    t = np.full((len(cases), len(labels)), np.inf)
    ci = {c: i for i, c in enumerate(cases)}
    li = {lab: j for j, lab in enumerate(labels)}
    for r in df.itertuples():
        h = history_array(r.history)
        if not h.size or not np.isfinite(float(r.f)):
            continue
        fr = float(r.f_ref)
        if not (float(r.max_violation) <= feas_tol and abs(fr - float(r.f)) / (1 + abs(fr)) <= er_tol):
            continue  # the returned point does not solve p
        ok = (h[:, 2] <= feas_tol) & (np.abs(fr - h[:, 1]) / (1 + abs(fr)) <= er_tol)
        hit = np.flatnonzero(ok)
        cost = h[hit[0], 0] if hit.size else h[-1, 0]
        t[ci[r.case_id], li[r.label]] = min(t[ci[r.case_id], li[r.label]], cost / (int(r.n) + 1))
    finite = t[np.isfinite(t)]
    top = max(1.0, float(finite.max()) * 1.05) if finite.size else 1.0
    grid = np.unique(np.concatenate([[0.0, top], finite]))
    d = (t[:, :, None] <= grid[None, None, :]).mean(axis=0).T if len(cases) else np.zeros((grid.size, len(labels)))
    return grid, pd.DataFrame(d, columns=labels)
