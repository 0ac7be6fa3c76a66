"""``harness compare OLD NEW`` and ``harness baseline``: performance tracking (docs/harness.md).

Runs are matched on (suite, case_id, solver, settings_hash), then - for runs whose
settings changed (a new option, a new default) - on (suite, case_id, solver) where that
is unique on both sides.  A run with command-line options (``dynamic-q[rho=0.5]``) counts
as a solver of its own, so it is only ever matched with a run of the same options.
A regression is a run solved in OLD and unsolved in NEW, or a
run solved in both whose N^fg grew by more than ``nfg_tol`` (default 10%), or, when
``rel_error_factor`` is given, whose E^r grew by more than that factor (above 1e-12).  A
run that timed out in OLD and finished in NEW is "finished in time", neither an
improvement nor a regression: the time limit depends on the machine.  So does a run that
stopped early with an answer because of the clock on either side (a multistart search at
its deadline, `harness.tables._campaign.clock_stopped`): a difference there is "cut by the
clock", never a regression; and a baseline leaves such runs out, as it leaves out time-outs.

A baseline is the deterministic part of stored runs (counts, status, f, E^r; never
times) in ``<dir>/<suite>/counts.csv``: small, diff-able, committed.
"""

from __future__ import annotations

import dataclasses
import os
import pathlib
import textwrap
from collections.abc import Sequence

import numpy as np
import pandas as pd

from problems._catalog import is_suite_name

from ._api import NoResults, load_results
from ._plan import HarnessArgumentError
from ._profiles import solver_labels
from ._store import Store
from .tables._base import count
from .tables._campaign import clock_decided, clock_stopped

__all__ = ["compare_dirs", "compare_runs", "format_changes", "save_baseline", "load_counts", "Comparison"]

BASELINE_COLUMNS = ["suite", "problem", "n", "start", "variant", "case_id", "solver", "settings_hash", "status",
                    "success", "nfg", "nf", "ng", "nc", "nj", "nit", "f", "rel_error", "inf_error", "code_version",
                    "overrides"]
KEY = ["suite", "case_id", "solver", "settings_hash"]


@dataclasses.dataclass
class Comparison:
    changes: pd.DataFrame  # one row per matched run
    only_old: pd.DataFrame
    only_new: pd.DataFrame

    @property
    def regressions(self) -> pd.DataFrame:
        return self.changes[self.changes["verdict"].astype(str).str.startswith("REGRESSION")]


def load_counts(root: str | os.PathLike[str], suite: str) -> pd.DataFrame:
    """A suite's runs from a results directory (runs.parquet) or a baseline (counts.csv)."""
    if Store(root, suite).exists():
        return load_results(suite, root)
    csv = pathlib.Path(root) / suite / "counts.csv"
    if csv.exists():
        df = pd.read_csv(csv, keep_default_na=False, na_values=[""], dtype={"variant": str, "settings_hash": str,
                                                                            "overrides": str})
        df["variant"] = df["variant"].fillna("")
        # baselines written before the column existed hold runs without command-line options
        df["overrides"] = df["overrides"].fillna("") if "overrides" in df else ""
        return df
    raise NoResults(f"no runs of suite {suite!r} under {root}")


def save_baseline(suite: str, out: str | os.PathLike[str] = "results",
                  to: str | os.PathLike[str] = "results/baseline",
                  solvers: Sequence[str] | None = None) -> pathlib.Path:
    """Write the deterministic counts of the stored runs to ``to/<suite>/counts.csv``.

    With ``solvers``, only those solvers' rows are replaced and every other row of an existing
    baseline is kept as it is (a deliberate change of one solver refreshes that solver only;
    a baseline may leave out solvers whose counts vary with the machine, such as SLSQP's).
    """
    runs = load_results(suite, out)
    # a time-out depends on the machine, not the code, and so does how far a run cut by the clock got
    runs = runs[~clock_decided(runs)]
    path = pathlib.Path(to) / suite / "counts.csv"
    rows = runs[BASELINE_COLUMNS]
    if solvers is not None:
        names = sorted(set(solvers))
        unknown = sorted(set(names) - set(runs["solver"]))
        if unknown:
            raise HarnessArgumentError(f"baseline of {suite!r}: no stored runs of {unknown} under {out}; "
                                       f"stored solvers: {sorted(set(runs['solver']))}")
        rows = rows[rows["solver"].isin(names)]
        if path.exists():
            kept = load_counts(to, suite)
            rows = pd.concat([kept[~kept["solver"].isin(names)][BASELINE_COLUMNS], rows])
    path.parent.mkdir(parents=True, exist_ok=True)
    rows.sort_values(["case_id", "solver", "settings_hash"]).to_csv(path, index=False, float_format="%.10g")
    return path


def _same(a: object, b: object) -> bool:
    """Equal, where two missing values (runs without counts) are equal too."""
    na, nb = bool(pd.isna(a)), bool(pd.isna(b))
    return na and nb or (not na and not nb and a == b)


def _verdict(r: pd.Series, nfg_tol: float, rel_error_factor: float | None) -> str:
    so, sn = bool(r.success_old), bool(r.success_new)
    if r.status_old == "timeout" and r.status_new != "timeout":
        # the old run hit its wall-clock limit: a faster machine or a quieter one finishes it, so
        # this is a matter of time, not of counts (a new time-out, by contrast, stays a regression:
        # it is how a hang or a slowdown shows)
        return f"finished in time: timeout -> {r.status_new}" + (" (solved)" if sn else "")
    if r.clock_old or r.clock_new:
        # how many local runs a search fitted before its deadline depends on the machine's speed
        if so == sn and _same(r.nfg_old, r.nfg_new) and r.status_old == r.status_new:
            return "same"
        what = f"{'solved' if so else 'unsolved'} -> {'solved' if sn else 'unsolved'}" if so != sn else "changed"
        return f"cut by the clock: {what}"
    if so and not sn:
        return f"REGRESSION: solved -> unsolved ({r.status_new})"
    if sn and not so:
        return "improved: unsolved -> solved"
    no, nn = count(r.nfg_old), count(r.nfg_new)
    if so and sn and no is not None and nn is not None:
        if nn > no * (1 + nfg_tol):
            return f"REGRESSION: N^fg +{(nn - no) / max(no, 1):.0%}"
        if rel_error_factor is not None:
            eo, en = float(r.rel_error_old), float(r.rel_error_new)
            if np.isfinite(en) and en > 1e-12 and en > rel_error_factor * max(eo if np.isfinite(eo) else 0, 1e-12):
                return f"REGRESSION: E^r {eo:.2e} -> {en:.2e}"
        if nn < no * (1 - nfg_tol):
            return f"improved: N^fg {(nn - no) / max(no, 1):.0%}"
    if not _same(r.nfg_old, r.nfg_new) or r.status_old != r.status_new:
        return "changed"
    return "same"


def compare_runs(old: pd.DataFrame, new: pd.DataFrame, nfg_tol: float = 0.10,
                 rel_error_factor: float | None = None) -> Comparison:
    cols = ["nfg", "success", "status", "rel_error", "f", "clock"]
    # a run with command-line options is its own solver (`sqsd[rho=0.1]`): matched and shown as such
    o = old.assign(clock=clock_stopped(old), solver=solver_labels(old))[KEY + cols]
    n = new.assign(clock=clock_stopped(new), solver=solver_labels(new))[KEY + cols]
    m = o.merge(n, on=KEY, how="outer", suffixes=("_old", "_new"), indicator=True)
    both = m[m["_merge"] == "both"].drop(columns="_merge")
    lo = m[m["_merge"] == "left_only"]
    ro = m[m["_merge"] == "right_only"]
    # settings changed: pair the leftovers on (suite, case_id, solver) where unique
    k2 = ["suite", "case_id", "solver"]
    lo1 = o.merge(lo[KEY], on=KEY)
    ro1 = n.merge(ro[KEY], on=KEY)
    lo1 = lo1[~lo1.duplicated(k2, keep=False)]
    ro1 = ro1[~ro1.duplicated(k2, keep=False)]
    pair = lo1.merge(ro1, on=k2, suffixes=("_old", "_new"))
    if len(pair):
        pair = pair.rename(columns={"settings_hash_new": "settings_hash"}).drop(columns="settings_hash_old")
        both = pd.concat([both, pair[both.columns]], ignore_index=True)
    only_old = lo[~lo.set_index(k2).index.isin(pair.set_index(k2).index)] if len(pair) else lo
    only_new = ro[~ro.set_index(k2).index.isin(pair.set_index(k2).index)] if len(pair) else ro
    both = both.reset_index(drop=True)
    both["verdict"] = pd.Series([_verdict(r, nfg_tol, rel_error_factor) for _, r in both.iterrows()],
                                index=both.index, dtype=object)
    return Comparison(both.sort_values(["suite", "case_id", "solver"]).reset_index(drop=True),
                      only_old[KEY].reset_index(drop=True), only_new[KEY].reset_index(drop=True))


def compare_dirs(old: str | os.PathLike[str], new: str | os.PathLike[str], suite: str | None = None,
                 nfg_tol: float = 0.10, rel_error_factor: float | None = None) -> Comparison:
    """Compare every suite present in both directories (or only ``suite``)."""
    if not (np.isfinite(nfg_tol) and nfg_tol >= 0):
        raise HarnessArgumentError(f"--nfg-tol must be a finite number >= 0 (a relative N^fg increase), got {nfg_tol}")
    if rel_error_factor is not None and not (np.isfinite(rel_error_factor) and rel_error_factor >= 1):
        raise HarnessArgumentError(f"--rel-error-factor must be a finite number >= 1, got {rel_error_factor}")
    from ._report import suites_under

    def names(d: str | os.PathLike[str]) -> set[str]:
        root = pathlib.Path(d)
        if not root.is_dir():
            raise HarnessArgumentError(f"{d} is not a directory")
        return set(suites_under(d)) | {p.parent.name for p in root.glob("*/counts.csv") if is_suite_name(p.parent.name)}

    common = sorted(names(old) & names(new))
    if suite is not None:
        if suite not in common:
            raise HarnessArgumentError(f"suite {suite!r} is not in both {old} and {new}; common suites: "
                                       f"{', '.join(common) or '(none)'}")
        common = [suite]
    if not common:
        raise HarnessArgumentError(f"no suite has results in both {old} and {new}")
    olds = pd.concat([load_counts(old, s) for s in common], ignore_index=True)
    news = pd.concat([load_counts(new, s) for s in common], ignore_index=True)
    return compare_runs(olds, news, nfg_tol, rel_error_factor)


def _num_text(v: object) -> str:
    c = count(v)
    return "—" if c is None else str(c)


def _wrapped_keys(label: str, df: pd.DataFrame, limit: int = 12) -> list[str]:
    """A short, wrapped account of unmatched runs: counts per suite and solver, then a few keys."""
    if not len(df):
        return []
    lines = [f"\n{label}: {len(df)} runs"]
    per = df.groupby(["suite", "solver"]).size()
    lines += textwrap.wrap(", ".join(f"{s}/{v}: {k}" for (s, v), k in per.items()), width=100,
                           initial_indent="  by suite/solver: ", subsequent_indent="    ")
    shown = [f"{r.suite}:{r.case_id}:{r.solver}" for r in df.head(limit).itertuples()]
    more = f" ... and {len(df) - limit} more (--all lists every run)" if len(df) > limit else ""
    lines += textwrap.wrap(", ".join(shown) + more, width=100, initial_indent="  ", subsequent_indent="  ")
    return lines


def format_changes(c: Comparison, show_all: bool = False) -> str:
    rows = c.changes if show_all else c.changes[c.changes["verdict"] != "same"]
    lines = [f"{len(c.changes)} runs compared, {int((c.changes['verdict'] != 'same').sum())} changed, "
             f"{len(c.regressions)} regressions; {len(c.only_old)} only in old, {len(c.only_new)} only in new"]
    if len(rows):
        lines += [
            "",
            "| suite | case | solver | N^fg old | N^fg new | solved old | solved new | E^r old | E^r new | verdict |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        for r in rows.itertuples():
            lines.append(f"| {r.suite} | {r.case_id} | {r.solver} | {_num_text(r.nfg_old)} | {_num_text(r.nfg_new)} | "
                         f"{r.success_old} | {r.success_new} | {float(r.rel_error_old):.2e} | "
                         f"{float(r.rel_error_new):.2e} | {r.verdict} |")
    if show_all:
        for label, df in (("only in old", c.only_old), ("only in new", c.only_new)):
            if len(df):
                lines.append(f"\n{label}: " + ", ".join(f"{r.suite}:{r.case_id}:{r.solver}" for r in df.itertuples()))
    else:
        lines += _wrapped_keys("only in old", c.only_old) + _wrapped_keys("only in new", c.only_new)
    return "\n".join(lines)
