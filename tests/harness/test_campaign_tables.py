"""Campaign tables (cutest, hs-all): reference values, outcomes, never an infeasible 'solved'."""

import numpy as np
import pandas as pd

from harness._plots import plot
from harness.tables._campaign import campaign_tables, classify_runs


def _runs():
    base = {"suite": "cutest", "settings": "{}", "settings_hash": "h", "overrides": "", "n": 2, "history": "[]",
            "wall_time_s": 0.1, "message": "", "nit": 1, "nf": 1, "ng": 1}
    rows = [
        # known optimum 1.0
        {
            "case_id": "A/n=2/x0",
            "solver": "s1",
            "f": 1.0 + 1e-9,
            "f_ref": 1.0,
            "max_violation": 0.0,
            "status": "converged",
            "nfg": 10,
        },
        {
            "case_id": "A/n=2/x0",
            "solver": "s2",
            "f": 0.5,
            "f_ref": 1.0,
            "max_violation": 1e-3,
            "status": "converged",
            "nfg": 5,
        },
        # no known optimum: the best feasible f found (2.0) is the reference; s2's lower f is infeasible
        {
            "case_id": "B/n=2/x0",
            "solver": "s1",
            "f": 2.0,
            "f_ref": np.nan,
            "max_violation": 0.0,
            "status": "converged",
            "nfg": 7,
        },
        {
            "case_id": "B/n=2/x0",
            "solver": "s2",
            "f": 1.0,
            "f_ref": np.nan,
            "max_violation": 0.5,
            "status": "converged",
            "nfg": 3,
        },
        {
            "case_id": "C/n=2/x0",
            "solver": "s1",
            "f": np.nan,
            "f_ref": np.nan,
            "max_violation": np.nan,
            "status": "timeout",
            "nfg": pd.NA,
            "message": "wall-clock limit of 10 s exceeded",
        },
        {
            "case_id": "C/n=2/x0",
            "solver": "s2",
            "f": 3.0,
            "f_ref": np.nan,
            "max_violation": 0.0,
            "status": "max_iter",
            "nfg": 9,
        },
    ]
    df = pd.DataFrame([{**base, **r} for r in rows])
    df["nfg"] = df["nfg"].astype("Int64")
    df["success"] = df["status"].eq("converged") & (df["max_violation"] <= 1e-6)
    return df


def test_outcomes_and_references():
    df = classify_runs(_runs()).set_index(["case_id", "solver"])
    assert df.loc[("A/n=2/x0", "s1"), "outcome"] == "solved"
    assert df.loc[("A/n=2/x0", "s2"), "outcome"] == "infeasible"
    assert df.loc[("B/n=2/x0", "s1"), "ref"] == 2.0 and df.loc[("B/n=2/x0", "s1"), "ref_source"] == "best found"
    assert df.loc[("B/n=2/x0", "s2"), "outcome"] == "infeasible"  # lower f, but infeasible: never solved
    assert df.loc[("C/n=2/x0", "s1"), "outcome"] == "timeout"
    assert df.loc[("C/n=2/x0", "s2"), "outcome"] == "solved"  # the only feasible end is the best found


def test_summary_counts_failures_by_kind():
    summary = campaign_tables(_runs(), ["s1", "s2"])[0].frame.set_index("solver")
    assert summary.loc["s1", "solved"] == 2 and summary.loc["s1", "timeout"] == 1
    assert summary.loc["s2", "infeasible end"] == 2 and summary.loc["s2", "solved"] == 1
    assert summary.loc["s1", "solved vs known optimum"] == 1


def test_log_ratio_profile(tmp_path):
    runs = _runs().replace({"s1": "dynamic-q", "s2": "ipopt"})
    paths = plot("cutest", "log-ratio", out=tmp_path, runs=runs)
    assert any(p.name == "log_ratio_dynamic-q_vs_ipopt.png" for p in paths)
