"""Tables of a campaign over a problem library (suites ``cutest``, ``hs-all``; docs/cutest.md).

Reference value of a case: its known optimum (``f_ref``: the verified Hock–Schittkowski
values) where there is one, otherwise the best feasible f that any run reached, as in Moré
& Wild's data profiles and OptiProfiler: the stored runs' best, or the suite's stored
best-known point where an earlier run got lower (`harness._best_known`).  A run *solves* a case when its returned
point is feasible (violation <= `FEAS_TOL`) and E^r = |f - f_ref| / (1 + |f_ref|) <=
`SOLVED_ER` (eq. 3.12), the rule of the thesis's Table 3.1.  An infeasible end is never
solved, whatever its f.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping

import numpy as np
import pandas as pd

from .._profiles import solver_labels
from .._store import failure_kind
from ._base import Table, count

__all__ = ["reference_values", "classify_runs", "campaign_tables", "common_limit", "judged_under", "clock_stopped",
           "clock_decided", "SOLVED_ER", "FEAS_TOL"]

SOLVED_ER = 1e-5
FEAS_TOL = 1e-6


#: ref_source of a case whose stored best-known point is lower than every stored run's end
EARLIER = "best known (earlier run)"


def reference_values(runs: pd.DataFrame, best_known: Mapping[str, float] | None = None) -> pd.DataFrame:
    """Per case: ``f_ref`` and its source: "known optimum", "best found" (the lower of the
    stored runs' best feasible f and ``best_known[case]``, the suite's stored best-known f of
    `harness._best_known`), `EARLIER` (the stored f, where it is lower than every stored
    run's by more than the solved tolerance) or "none feasible" (NaN)."""
    best_known = best_known or {}
    out = []
    for case, g in runs.groupby("case_id", sort=True):
        known = pd.to_numeric(g["f_ref"], errors="coerce")
        if np.isfinite(known).any():
            ref = float(known[np.isfinite(known)].iloc[0])
            out.append({"case_id": case, "ref": ref, "ref_source": "known optimum"})
            continue
        feas = g[(pd.to_numeric(g["max_violation"], errors="coerce") <= FEAS_TOL) & np.isfinite(g["f"])]
        found = float(feas["f"].min()) if len(feas) else math.nan
        kept = float(best_known.get(str(case), math.nan))
        if math.isfinite(kept) and not kept >= found:  # lower than every stored run, or none is feasible
            # named for where it came from only when no stored run is within the solved tolerance of it
            near = (found - kept) / (1 + abs(kept)) <= SOLVED_ER
            out.append({"case_id": case, "ref": kept, "ref_source": "best found" if near else EARLIER})
        else:
            out.append({"case_id": case, "ref": found, "ref_source": "best found" if len(feas) else "none feasible"})
    return pd.DataFrame(out, columns=["case_id", "ref", "ref_source"])


def clock_stopped(runs: pd.DataFrame) -> pd.Series:
    """Runs that stopped early with an answer because of the wall clock (a multistart search
    at the harness's deadline or its ``max_time``: ``extra["stopped_by"]``).  How far such a
    run got depends on the machine's speed, so its row is not reproducible to the digit."""

    def stopped(extra: object) -> bool:
        try:
            return json.loads(str(extra)).get("stopped_by") in ("deadline", "max_time")
        except (ValueError, AttributeError):
            return False

    col = runs["extra"] if "extra" in runs else pd.Series("{}", index=runs.index)
    return col.map(stopped).astype(bool)


def clock_decided(runs: pd.DataFrame) -> pd.Series:
    """Runs whose outcome the wall clock decided: time-outs and the searches `clock_stopped` marks.
    Neither reproduces on a machine of another speed (baselines leave them out; `harness run`
    notes them before mixing machines)."""
    return (runs["status"] == "timeout") | clock_stopped(runs)


def common_limit(runs: pd.DataFrame) -> float:
    """The smallest per-run wall-clock limit among the stored runs, s (inf: none had one).

    Every run of a campaign is judged under this one limit: a run stored under a larger
    limit (``--timeout 600`` beside a campaign run with ``--timeout 10``) that took longer
    would have been a time-out there, and solved counts compare like with like only if
    no solver got more time than another."""
    t = pd.to_numeric(runs["timeout_s"], errors="coerce") if "timeout_s" in runs else pd.Series(dtype=float)
    t = t[(t > 0) & np.isfinite(t)]
    return float(t.min()) if len(t) else math.inf


def judged_under(runs: pd.DataFrame, limit: float) -> pd.DataFrame:
    """The runs with every run longer than ``limit`` seconds turned into a time-out (no f,
    no violation: it neither counts as solved nor sets a reference value), marked in the
    boolean column ``over_limit``."""
    wall = pd.to_numeric(runs["wall_time_s"], errors="coerce")
    over = (wall > limit) & ~runs["status"].isin(["timeout", "not_applicable"])
    out = runs.assign(over_limit=over)
    if not over.any():
        return out
    out.loc[over, "message"] = [f"took {w:.1f} s, over the common wall-clock limit of {limit:g} s"
                                for w in wall[over]]
    out.loc[over, "status"] = "timeout"
    out.loc[over, ["f", "max_violation"]] = math.nan
    return out


def _outcome(r: pd.Series) -> str:
    """solved, or why not: infeasible, cap, failed (converged elsewhere), error, timeout, infrastructure."""
    if r["status"] == "not_applicable":
        return "not applicable"
    kind = failure_kind(str(r["status"]), str(r["message"]))
    if kind:
        return {"solver": "error", "timeout": "timeout", "infrastructure": "infrastructure"}[kind]
    viol = float(r["max_violation"])
    if not (viol <= FEAS_TOL):
        return "infeasible"
    if np.isfinite(r["ref"]) and abs(float(r["f"]) - r["ref"]) / (1 + abs(r["ref"])) <= SOLVED_ER:
        return "solved"
    return "cap" if r["status"] == "max_iter" else "other point"


def classify_runs(runs: pd.DataFrame, best_known: Mapping[str, float] | None = None) -> pd.DataFrame:
    """The runs with ``label``, ``ref``, ``ref_source``, ``er``, ``outcome`` and ``clock_stopped``
    columns, every run judged under the campaign's common wall-clock limit (`common_limit`);
    ``best_known``: the suite's stored best-known f per case (`reference_values`)."""
    runs = judged_under(runs, common_limit(runs))
    df = (runs.assign(label=solver_labels(runs), clock_stopped=clock_stopped(runs))
          .merge(reference_values(runs, best_known), on="case_id", how="left"))
    df["er"] = (df["f"] - df["ref"]).abs() / (1 + df["ref"].abs())
    df["outcome"] = [_outcome(r) for _, r in df.iterrows()]
    return df


def _summary(df: pd.DataFrame, order: list[str], defaults: bool = True) -> Table:
    ran = df[df["outcome"] != "not applicable"]
    solved = ran[ran["outcome"] == "solved"]
    # commonly solved: cases every solver that ran on them solved
    per_case = ran.groupby("case_id")["outcome"].agg(lambda s: bool((s == "solved").all()))
    common = set(per_case[per_case].index)
    rows = []
    for lab in order:
        mine = ran[ran["label"] == lab]
        if mine.empty:
            continue
        out = mine["outcome"].value_counts()
        counts = [count(v) for v in mine.loc[mine["case_id"].isin(common), "nfg"]]
        nfg_common = [v for v in counts if v is not None]
        rows.append({
            "solver": lab, "problems": len(mine), "solved": int(out.get("solved", 0)),
            "solved vs known optimum": int(((mine["outcome"] == "solved")
                                            & (mine["ref_source"] == "known optimum")).sum()),
            "other point": int(out.get("other point", 0)), "infeasible end": int(out.get("infeasible", 0)),
            "cap": int(out.get("cap", 0)), "error": int(out.get("error", 0)), "timeout": int(out.get("timeout", 0)),
            "infrastructure": int(out.get("infrastructure", 0)),
            "cut by the clock": int(mine["clock_stopped"].sum()),
            "commonly solved": len(nfg_common),
            "median N^fg (commonly solved)": float(np.median(nfg_common)) if nfg_common else math.nan,
            "median N^fg (solved)": float(solved.loc[solved["label"] == lab, "nfg"].astype(float).median()),
            "wall time [s]": round(float(mine["wall_time_s"].sum()), 1),
        })
    frame = pd.DataFrame(rows)
    refs = df.drop_duplicates("case_id")["ref_source"].value_counts()
    notes = [
        f"Solved: returned point feasible (violation <= {FEAS_TOL:g}) and E^r <= {SOLVED_ER:g} against the case's "
        "reference value (eq. 3.12); an infeasible end is never solved. "
        + ("Every solver ran with its defaults." if defaults else "Each solver ran with the suite's settings."),
        "Reference values: " + ", ".join(f"{v} case{'s' * (v != 1)} {k}" for k, v in refs.items())
        + " ('best found': the best feasible f any run reached, as in Moré-Wild data profiles; the suite keeps "
        "the point of every case's lowest end in reference.json, so a reference only ever goes down and a re-run "
        f"that ends higher moves no other solver's count; '{EARLIER}': no stored run is within the solved "
        "tolerance of that kept point's f).",
        f"Commonly solved: the {len(common)} cases that every solver which ran on them solved; medians of N^fg over "
        "them compare like with like.",
        "Outcomes: other point = feasible, converged elsewhere (a local minimum or a stop short of the reference); "
        "cap = iteration or evaluation cap; error = the solver or problem raised; infrastructure = the worker died.",
    ]
    cut = int(df["clock_stopped"].sum())
    if cut:
        notes.append(f"Cut by the clock: {cut} run{'s' * (cut != 1)} (multistart searches) stopped early with an "
                     "answer because the run's time limit was near; how many local runs fitted depends on the "
                     "machine's speed, so these rows can differ between re-runs (marked @ in the per-run table).")
    limit = common_limit(df)
    if math.isfinite(limit):
        late = int(df["over_limit"].sum())
        notes.append(f"Time limit: every run is judged under {limit:g} s of wall-clock time, the smallest limit any "
                     f"stored run had" + (f"; {late} finished runs that took longer count as time-outs."
                                          if late else "."))
    return Table(name="campaign_summary", title="Per-solver summary of the campaign", frame=frame, notes=notes)


def _per_case(df: pd.DataFrame, order: list[str]) -> Table:
    marks = {"solved": "", "other point": "*", "infeasible": "!", "cap": "$", "error": "~", "timeout": "t",
             "infrastructure": "x", "not applicable": "n/a"}
    rows = []
    for case, g in df.groupby("case_id", sort=True):
        first = g.iloc[0]
        row = {"case": case, "n": int(first["n"]), "f_ref": first["ref"], "ref": first["ref_source"]}
        by = {r["label"]: r for _, r in g.iterrows()}
        for lab in order:
            r = by.get(lab)
            if r is None:
                row[lab] = ""
            elif r["outcome"] == "not applicable":
                row[lab] = "n/a"
            else:
                nfg = count(r["nfg"])
                row[lab] = f"{'' if nfg is None else nfg}{marks[r['outcome']]}{'@' * bool(r['clock_stopped'])}"
        rows.append(row)
    notes = ["Cells: N^fg of the run, then its outcome: (none) solved, * feasible elsewhere, ! infeasible end, "
             "$ cap, ~ error, t timeout, x infrastructure failure; n/a the solver does not handle the problem; "
             "@ cut by the clock (stopped early with an answer: depends on the machine's speed)."]
    return Table(name="campaign_runs", title="N^fg and outcome of every run", frame=pd.DataFrame(rows), notes=notes)


def campaign_tables(runs: pd.DataFrame, solver_order: list[str] | None = None, prefix: str = "campaign",
                    suite: str = "", defaults: bool = True,
                    best_known: Mapping[str, float] | None = None) -> list[Table]:
    """The summary and per-run tables, named ``<prefix>_summary`` and ``<prefix>_runs``;
    ``defaults``: every solver ran at its defaults (the notes say so), as in cutest and hs-all;
    ``best_known``: the suite's stored best-known f per case (`reference_values`)."""
    df = classify_runs(runs, best_known)
    labels = list(dict.fromkeys(solver_order or [])) + sorted(set(df["label"]) - set(solver_order or []))
    labels = [lab for lab in labels if lab in set(df["label"])]
    out = [_summary(df, labels, defaults), _per_case(df, labels)]
    for t in out:
        t.name = t.name.replace("campaign", prefix)
        t.title = f"{suite}: {t.title}" if suite else t.title
    return out
