"""Tables of a campaign over a problem library (suites ``cutest``, ``hs-all``; docs/cutest.md).

Reference value of a case: its known optimum (``f_ref``: the verified Hock–Schittkowski
values) where there is one, otherwise the best feasible f that any stored run reached, as
in Moré & Wild's data profiles and OptiProfiler.  A run *solves* a case when its returned
point is feasible (violation <= `FEAS_TOL`) and E^r = |f - f_ref| / (1 + |f_ref|) <=
`SOLVED_ER` (eq. 3.12), the rule of the thesis's Table 3.1.  An infeasible end is never
solved, whatever its f.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .._profiles import solver_labels
from .._store import failure_kind
from ._base import Table, count

__all__ = ["reference_values", "classify_runs", "campaign_tables", "common_limit", "judged_under", "SOLVED_ER",
           "FEAS_TOL"]

SOLVED_ER = 1e-5
FEAS_TOL = 1e-6


def reference_values(runs: pd.DataFrame) -> pd.DataFrame:
    """Per case: ``f_ref`` and its source ("known optimum" or "best found"); NaN when none."""
    out = []
    for case, g in runs.groupby("case_id", sort=True):
        known = pd.to_numeric(g["f_ref"], errors="coerce")
        if np.isfinite(known).any():
            ref = float(known[np.isfinite(known)].iloc[0])
            out.append({"case_id": case, "ref": ref, "ref_source": "known optimum"})
            continue
        feas = g[(pd.to_numeric(g["max_violation"], errors="coerce") <= FEAS_TOL) & np.isfinite(g["f"])]
        out.append({"case_id": case, "ref": float(feas["f"].min()) if len(feas) else math.nan,
                    "ref_source": "best found" if len(feas) else "none feasible"})
    return pd.DataFrame(out, columns=["case_id", "ref", "ref_source"])


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


def classify_runs(runs: pd.DataFrame) -> pd.DataFrame:
    """The runs with ``label``, ``ref``, ``ref_source``, ``er`` and ``outcome`` columns, every
    run judged under the campaign's common wall-clock limit (`common_limit`)."""
    runs = judged_under(runs, common_limit(runs))
    df = runs.assign(label=solver_labels(runs)).merge(reference_values(runs), on="case_id", how="left")
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
        + " ('best found': the best feasible f any stored run reached, as in Moré-Wild data profiles).",
        f"Commonly solved: the {len(common)} cases that every solver which ran on them solved; medians of N^fg over "
        "them compare like with like.",
        "Outcomes: other point = feasible, converged elsewhere (a local minimum or a stop short of the reference); "
        "cap = iteration or evaluation cap; error = the solver or problem raised; infrastructure = the worker died.",
    ]
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
                row[lab] = f"{'' if nfg is None else nfg}{marks[r['outcome']]}"
        rows.append(row)
    notes = ["Cells: N^fg of the run, then its outcome: (none) solved, * feasible elsewhere, ! infeasible end, "
             "$ cap, ~ error, t timeout, x infrastructure failure; n/a the solver does not handle the problem."]
    return Table(name="campaign_runs", title="N^fg and outcome of every run", frame=pd.DataFrame(rows), notes=notes)


def campaign_tables(runs: pd.DataFrame, solver_order: list[str] | None = None, prefix: str = "campaign",
                    suite: str = "", defaults: bool = True) -> list[Table]:
    """The summary and per-run tables, named ``<prefix>_summary`` and ``<prefix>_runs``;
    ``defaults``: every solver ran at its defaults (the notes say so), as in cutest and hs-all."""
    df = classify_runs(runs)
    labels = list(dict.fromkeys(solver_order or [])) + sorted(set(df["label"]) - set(solver_order or []))
    labels = [lab for lab in labels if lab in set(df["label"])]
    out = [_summary(df, labels, defaults), _per_case(df, labels)]
    for t in out:
        t.name = t.name.replace("campaign", prefix)
        t.title = f"{suite}: {t.title}" if suite else t.title
    return out
