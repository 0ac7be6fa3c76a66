"""CI performance tracking: re-run the cheap runs of the committed baseline
(results/baseline/<suite>/counts.csv) and fail on a regression (N^fg +10%, or a solved
run now unsolved).  Refresh the baseline after a deliberate change:
``python -m harness baseline --suite appendix-a --out results --to results/baseline``."""

import pathlib

import pandas as pd
import pytest

import harness
from harness._compare import compare_runs, format_changes, load_counts

BASELINE = pathlib.Path(__file__).resolve().parents[2] / "results" / "baseline"
SUITES = sorted(p.parent.name for p in BASELINE.glob("*/counts.csv"))
BUDGET = 2e4  # N^fg x n: about 100 runs, a few seconds of solver time


@pytest.mark.parametrize("suite", SUITES)
def test_no_regression_against_baseline(suite, tmp_path):
    base = load_counts(BASELINE, suite)
    cheap = base[base["success"].astype(bool) & (base["nfg"].astype(float) * base["n"].astype(float) <= BUDGET)]
    assert len(cheap) >= 10, "baseline has too few cheap solved runs to track"
    for solver, grp in cheap.groupby("solver"):
        harness.run_suite(suite, solvers=[solver], problems=sorted(grp["case_id"]), out=tmp_path,
                          jobs=2, timeout=120, progress=None)
    new = harness.load_results(suite, tmp_path)
    c = compare_runs(cheap, new)
    assert len(c.changes) == len(cheap), format_changes(c)
    assert c.regressions.empty, format_changes(c)


def test_baseline_checker_catches_a_regression(tmp_path):
    """The check above can fail: a baseline claiming fewer evaluations flags a regression."""
    if not SUITES:
        pytest.skip("no committed baseline")
    base = load_counts(BASELINE, SUITES[0])
    row = base[base["success"].astype(bool)].head(1).copy()
    better = row.assign(nfg=(row["nfg"].astype(float) / 2).astype(int))
    assert len(compare_runs(better, row).regressions) == 1
    assert len(compare_runs(row, pd.concat([row.assign(success=False, status="max_iter")])).regressions) == 1
