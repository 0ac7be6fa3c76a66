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


def test_every_run_is_judged_under_the_smallest_stored_limit():
    """A run stored under a larger wall-clock limit that took longer than another run's limit is a
    time-out in the tables: it neither counts as solved nor sets the best-found reference."""
    runs = _runs()
    runs["timeout_s"] = 600.0
    runs.loc[runs["solver"] == "s1", "timeout_s"] = 10.0  # s1 ran under the campaign's 10 s
    slow = (runs["case_id"] == "C/n=2/x0") & (runs["solver"] == "s2")
    runs.loc[slow, "wall_time_s"] = 58.0  # s2 solved C, but in 58 s
    df = classify_runs(runs).set_index(["case_id", "solver"])
    assert df.loc[("C/n=2/x0", "s2"), "outcome"] == "timeout"
    assert np.isnan(df.loc[("C/n=2/x0", "s2"), "ref"])  # no feasible end left to be the reference
    assert df.loc[("A/n=2/x0", "s1"), "outcome"] == "solved"  # runs within the limit are unchanged
    notes = " ".join(campaign_tables(runs, ["s1", "s2"])[0].notes)
    assert "judged under 10 s" in notes and "1 finished runs that took longer" in notes
    runs.loc[slow, "wall_time_s"] = 9.0  # within every limit: solved again
    assert classify_runs(runs).set_index(["case_id", "solver"]).loc[("C/n=2/x0", "s2"), "outcome"] == "solved"


def test_campaigns_default_to_their_10_s_limit():
    from harness._runner import DEFAULT_TIMEOUT, default_timeout

    assert default_timeout("cutest") == default_timeout("hs-all") == 10.0
    assert default_timeout("hs") == DEFAULT_TIMEOUT == 600.0
    assert default_timeout("spatial") == 1800.0  # a guard well above its slowest run (436 s on the EPYC)
    assert default_timeout("rpr3") == default_timeout("rpr3-spread") == 1800.0  # D P1: up to 454 s
    assert default_timeout(None, "my_suite.py") == DEFAULT_TIMEOUT  # a user's file: no campaign protocol


def test_log_ratio_profile(tmp_path):
    runs = _runs().replace({"s1": "dynamic-q", "s2": "ipopt"})
    paths = plot("cutest", "log-ratio", out=tmp_path, runs=runs)
    assert any(p.name == "log_ratio_dynamic-q_vs_ipopt.png" for p in paths)


def test_campaign_parts_profile_each_solver_on_the_cases_it_handles(tmp_path):
    """A solver that handles only part of a library gets profiles over that part, beside everyone
    who handles all of it; the full-library profile is drawn as before."""
    from harness._plots import MIN_SUBSET, campaign_parts

    base = {"suite": "cutest", "settings": "{}", "settings_hash": "h", "overrides": "", "n": 2,
            "history": "[[1,3.0,0.0],[2,1.0,0.0]]", "wall_time_s": 0.1, "message": "", "nit": 1, "nf": 2, "ng": 2,
            "f": 1.0, "f_ref": 1.0, "max_violation": 0.0, "nfg": 2, "x": [0.0, 0.0]}
    rows = []
    for i in range(20):
        for solver in ("general", "unconstrained-only"):
            na = solver == "unconstrained-only" and i >= MIN_SUBSET + 2  # handles the first 12 cases only
            rows.append({**base, "case_id": f"P{i}/n=2/x0", "problem": f"P{i}", "solver": solver,
                         "status": "not_applicable" if na else "converged", "success": not na})
    runs = pd.DataFrame(rows)
    parts = campaign_parts(runs)
    assert [p[0] for p in parts] == ["_cases_of_unconstrained-only"]
    _, note, sub = parts[0]
    assert sub["case_id"].nunique() == MIN_SUBSET + 2 and set(sub["solver"]) == {"general", "unconstrained-only"}
    assert "12 cases unconstrained-only handle" in note
    names = {p.name for p in plot("cutest", "profile", out=tmp_path, runs=runs)}
    assert {"profile_nfg.png", "profile_nfg_cases_of_unconstrained-only.png"} <= names
    few = runs[(runs["solver"] == "general") | runs["case_id"].isin([f"P{i}/n=2/x0" for i in range(3)])]
    few = few[~((few["solver"] == "unconstrained-only") & (few["status"] == "not_applicable"))]
    assert campaign_parts(few) == []  # a part of 3 cases is below MIN_SUBSET: no separate profile
