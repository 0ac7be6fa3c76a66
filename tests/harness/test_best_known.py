"""Best-known points of the campaigns (harness/_best_known.py): kept, only lowered, verifiable."""

from __future__ import annotations

import json
import pathlib

import numpy as np
import pandas as pd
import pytest

from harness import _best_known
from harness._reference import load_reference, reference_path, update_reference
from harness.cli import main
from harness.tables._campaign import EARLIER, campaign_tables, classify_runs

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _runs(rows):
    base = {"suite": "cutest", "settings": "{}", "settings_hash": "h", "overrides": "", "n": 2, "history": "[]",
            "wall_time_s": 0.1, "timeout_s": 10.0, "message": "", "nit": 1, "nf": 1, "ng": 1, "nfg": 5,
            "f_ref": np.nan, "max_violation": 0.0, "status": "converged", "x": [1.0, 2.0], "extra": "{}",
            "code_version": "c", "finished_at": "2026-11-29", "run_key": "k"}
    return pd.DataFrame([{**base, **r} for r in rows])


def test_the_lowest_feasible_end_within_the_limit_is_kept():
    runs = _runs([
        {"case_id": "A", "solver": "s1", "f": 2.0},
        {"case_id": "A", "solver": "s2", "f": 1.0, "max_violation": 1e-3},  # lower, infeasible: never
        {"case_id": "A", "solver": "s3", "f": 0.5, "wall_time_s": 12.0},  # lower, over the 10 s limit: never
        {"case_id": "B", "solver": "s1", "f": 3.0, "x": [0.5, 0.25]},
        {"case_id": "C", "solver": "s1", "f": np.nan, "status": "timeout", "max_violation": np.nan},
    ])
    data = _best_known.reference(runs, None)["best_known"]
    assert set(data) == {"A", "B"}
    assert data["A"]["f"] == 2.0 and data["A"]["solver"] == "s1"
    assert data["B"]["x"] == [0.5, 0.25]


def test_a_reference_only_goes_down():
    stored = _best_known.reference(_runs([{"case_id": "A", "solver": "s1", "f": 1.0, "x": [0.0, 0.0]}]))
    higher = _best_known.reference(_runs([{"case_id": "A", "solver": "s2", "f": 1.5}]), stored)
    assert higher["best_known"]["A"]["f"] == 1.0 and higher["best_known"]["A"]["x"] == [0.0, 0.0]
    tie = _best_known.reference(_runs([{"case_id": "A", "solver": "s2", "f": 1.0}]), stored)
    assert tie["best_known"]["A"]["solver"] == "s1"  # a tie keeps the stored entry: re-runs change nothing
    lower = _best_known.reference(_runs([{"case_id": "A", "solver": "s2", "f": 0.5}]), stored)
    assert lower["best_known"]["A"]["f"] == 0.5 and lower["best_known"]["A"]["solver"] == "s2"


def test_an_earlier_lower_end_is_the_reference_and_is_named():
    runs = _runs([{"case_id": "A", "solver": "s1", "f": 2.0}, {"case_id": "A", "solver": "s2", "f": 2.0 + 1e-9},
                  {"case_id": "B", "solver": "s1", "f": 3.0}])
    plain = classify_runs(runs).set_index(["case_id", "solver"])
    assert (plain["outcome"] == "solved").all() and (plain["ref_source"] == "best found").all()
    df = classify_runs(runs, {"A": 1.0, "B": 4.0}).set_index(["case_id", "solver"])
    assert df.loc[("A", "s1"), "ref"] == 1.0 and df.loc[("A", "s1"), "ref_source"] == EARLIER
    assert df.loc[("A", "s1"), "outcome"] == "other point"
    # a stored value above the runs' best is not a reference: the runs' best is
    assert df.loc[("B", "s1"), "ref"] == 3.0 and df.loc[("B", "s1"), "ref_source"] == "best found"
    near = classify_runs(runs, {"A": 2.0 - 1e-9}).set_index(["case_id", "solver"])
    assert near.loc[("A", "s1"), "ref"] == 2.0 - 1e-9 and near.loc[("A", "s1"), "ref_source"] == "best found"
    assert near.loc[("A", "s1"), "outcome"] == "solved"  # within the solved tolerance of the stored point
    notes = " ".join(campaign_tables(runs, ["s1", "s2"], best_known={"A": 1.0})[0].notes)
    assert f"1 case {EARLIER}" in notes


def test_a_known_optimum_outranks_a_stored_point():
    runs = _runs([{"case_id": "A", "solver": "s1", "f": 1.0, "f_ref": 1.0}])
    df = classify_runs(runs, {"A": 0.5})
    assert df["ref"].iloc[0] == 1.0 and df["outcome"].iloc[0] == "solved"


def test_runs_cut_by_the_clock_are_counted_and_marked():
    cut = json.dumps({"stopped_by": "deadline"})
    runs = _runs([{"case_id": "A", "solver": "multistart", "f": 1.0, "status": "max_iter", "extra": cut},
                  {"case_id": "A", "solver": "s1", "f": 2.0, "extra": json.dumps({"stopped_by": "confidence"})},
                  {"case_id": "B", "solver": "multistart", "f": 1.0, "extra": "not json"}])
    summary, per_run = campaign_tables(runs, ["multistart", "s1"])
    counts = summary.frame.set_index("solver")["cut by the clock"]
    assert counts["multistart"] == 1 and counts["s1"] == 0
    cells = per_run.frame.set_index("case")
    assert cells.loc["A", "multistart"] == "5@" and cells.loc["A", "s1"] == "5*"
    assert cells.loc["B", "multistart"] == "5"
    assert any("Cut by the clock: 1 run" in n for n in summary.notes)


def test_stored_points_outlive_code_changes_but_not_fresh(tmp_path):
    runs = _runs([{"case_id": "A", "solver": "s1", "f": 1.0}])
    path = update_reference(tmp_path, "cutest", runs)
    doc = json.loads(path.read_text())
    doc["code_version"] = "an older version"
    path.write_text(json.dumps(doc))
    update_reference(tmp_path, "cutest", _runs([{"case_id": "A", "solver": "s1", "f": 3.0}]))
    assert load_reference(tmp_path, "cutest")["best_known"]["A"]["f"] == 1.0  # kept across the code change
    update_reference(tmp_path, "cutest", _runs([{"case_id": "A", "solver": "s1", "f": 3.0}]), fresh=True)
    assert load_reference(tmp_path, "cutest")["best_known"]["A"]["f"] == 3.0  # fresh: the stored runs alone


@pytest.mark.parametrize("name", ["hs-all", "cutest"])
def test_the_committed_points_verify_and_a_tampered_one_does_not(name):
    from problems import get_suite

    stored = load_reference(ROOT / "results", name)
    assert len(stored["best_known"]) > 100
    suite = get_suite(name)
    every = sorted(stored["best_known"])
    some = every[:: len(every) // 8][:8]  # spread over the alphabet
    report = _best_known.verify(suite, stored, some)
    assert report["ok"].all(), report.loc[~report["ok"], "why"].tolist()
    bad = json.loads(json.dumps(stored))
    bad["best_known"][some[0]]["f"] -= 1e-3 * max(1.0, abs(bad["best_known"][some[0]]["f"]))
    bad["best_known"][some[1]]["x"] = [0.0]
    report = _best_known.verify(suite, bad, some[:3] + ["NO-SUCH-CASE"]).set_index("case_id")
    assert not report.loc[some[0], "ok"] and "stored" in report.loc[some[0], "why"]
    assert not report.loc[some[1], "ok"] and "1 entries" in report.loc[some[1], "why"]
    assert report.loc[some[2], "ok"]
    assert report.loc["NO-SUCH-CASE", "why"] == "no stored entry"


def test_verify_command(tmp_path, capsys):
    (tmp_path / "hs-all").mkdir()
    doc = json.loads(reference_path(ROOT / "results", "hs-all").read_text())
    first = sorted(doc["data"]["best_known"])[0]
    doc["data"]["best_known"] = {first: doc["data"]["best_known"][first]}
    reference_path(tmp_path, "hs-all").write_text(json.dumps(doc))
    assert main(["reference", "--suite", "hs-all", "--out", str(tmp_path), "--verify"]) == 0
    assert "1 of 1 stored best-known points verified" in capsys.readouterr().out
    doc["data"]["best_known"][first]["f"] += 1.0
    reference_path(tmp_path, "hs-all").write_text(json.dumps(doc))
    assert main(["reference", "--suite", "hs-all", "--out", str(tmp_path), "--verify"]) == 1
    assert f"{first}: f at the stored point" in capsys.readouterr().out


@pytest.mark.parametrize("suite", ["rpr2", "hs"])
def test_verify_is_for_best_known_points_only(suite, capsys):
    assert main(["reference", "--suite", suite, "--verify"]) == 2
    err = capsys.readouterr().err
    assert "best-known points" in err or "has no stored reference" in err
