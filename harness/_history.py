"""Thinning a run's stored history for campaigns of thousands of runs (``--history-points``).

A stored history is ``[[nfg, f, max_violation], ...]``, one entry per evaluation.  Over a
CUTEst campaign a few hundred long runs (time-outs, LFOPC's thousands of time steps) hold
most of the bytes.  `thin_history` keeps:

1. every evaluation that no earlier one dominates in (f, max_violation) -- the ones that
   lower f at some level of violation.  This step is lossless for what the profiles read:
   for any feasibility tolerance and any target, the first evaluation that is feasible and
   reaches the target is never dominated by an earlier one, so it is kept (Moré–Wild data
   profiles, best-so-far curves, `harness._profiles.best_so_far`);
2. if more than ``max_points`` remain, the evaluation range is cut into ``max_points``
   bins evenly spaced in log(nfg), and of the kept evaluations a bin keeps its last one and
   every one whose violation differs from the next kept one's.  Between two kept
   evaluations the violation is then constant and f falls, so a target first reached at a
   dropped evaluation is also reached at the next kept one, in the same bin: a
   first-hitting count read from the history is rounded up by at most a factor
   (nfg_last / nfg_first)^(1 / max_points) - for 1,000 bins and 10^5 evaluations, 1.2%.
   Unconstrained and feasible descents (most of the bytes) shrink to about ``max_points``.

The run's counts, f, x and status are never touched; only the history column is thinned.
"""

from __future__ import annotations

import bisect
import json
import math

import numpy as np

__all__ = ["thin_history"]


def _num(v: object) -> float:
    try:
        x = float(v)  # type: ignore[arg-type]  # JSON numbers, "nan"/"inf" strings, None
    except (TypeError, ValueError):
        return math.inf
    return math.inf if math.isnan(x) else x


def _undominated(f: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Indices i such that no j < i has f[j] <= f[i] and v[j] <= v[i]."""
    keep: list[int] = []
    front_f: list[float] = []  # the current front, by violation ascending (so f descending)
    front_v: list[float] = []
    for i, (fi, vi) in enumerate(zip(f.tolist(), v.tolist())):
        # dominated iff the last front point with violation <= vi has f <= fi
        k = bisect.bisect_right(front_v, vi)
        if k > 0 and front_f[k - 1] <= fi:
            continue
        keep.append(i)
        # the new point replaces the front points it dominates (violation >= vi, f >= fi)
        lo = bisect.bisect_left(front_v, vi)
        hi = lo
        while hi < len(front_v) and front_f[hi] >= fi:
            hi += 1
        front_f[lo:hi] = [fi]
        front_v[lo:hi] = [vi]
    return np.asarray(keep, dtype=int)


def thin_history(history_json: str, max_points: int) -> str:
    """The history thinned as the module says; unchanged if it has at most ``max_points`` entries."""
    if max_points < 2:
        raise ValueError(f"history points must be >= 2, got {max_points}")
    rows = json.loads(history_json or "[]")
    if len(rows) <= max_points:
        return history_json
    f = np.array([_num(r[1]) for r in rows])
    v = np.array([_num(r[2]) if len(r) > 2 else 0.0 for r in rows])
    idx = _undominated(f, v)
    if len(idx) > max_points:
        nfg = np.array([_num(rows[i][0]) for i in idx])
        nfg = np.where(np.isfinite(nfg) & (nfg > 0), nfg, 1.0)
        edges = np.geomspace(nfg.min(), nfg.max() * (1 + 1e-12), max_points + 1)
        b = np.searchsorted(edges, nfg, side="right")
        vk = v[idx]
        last_in_bin = np.append(b[1:] != b[:-1], True)
        v_changes = np.append(vk[1:] != vk[:-1], True)
        idx = idx[last_in_bin | v_changes | (np.arange(len(idx)) == 0)]
    last = len(rows) - 1
    if idx[-1] != last:  # the final evaluation always stays (the run's end)
        idx = np.append(idx, last)
    return json.dumps([rows[i] for i in idx], separators=(",", ":"))
