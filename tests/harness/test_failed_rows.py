"""Rows without counts (time-outs, worker deaths) are failures in every output, never crashes.

The stored runs of the committed suites are copied, one run per solver is turned into a
time-out or an error row (counts missing, as the harness stores them), and tables, the
report and ``compare`` are built from them.
"""

from __future__ import annotations

import pathlib
import shutil

import pandas as pd
import pytest

from harness._compare import compare_runs, format_changes
from harness._store import Store
from harness.cli import main
from harness.tables._render import build_tables

ROOT = pathlib.Path(__file__).resolve().parents[2]
COUNTS = ["nfg", "nf", "ng", "nc", "nj", "nh", "nit"]
FAST_SUITES = ["hs", "appendix-a", "tdpm", "rpr2", "rpr2-spread"]  # rpr3's tables take ~20 s: covered by CLI test


def _with_failures(runs: pd.DataFrame) -> pd.DataFrame:
    """Turn the first run of every solver into a failure without counts (alternately timeout/error)."""
    runs = runs.copy()
    firsts = runs.groupby("solver").head(1).index
    for k, i in enumerate(firsts):
        for c in COUNTS:
            if c in runs:
                runs.loc[i, c] = pd.NA
        runs.loc[i, ["status", "success"]] = ["timeout" if k % 2 == 0 else "error", False]
        runs.loc[i, "message"] = "injected by the test"
    return runs


@pytest.fixture(scope="module")
def failed_store(tmp_path_factory):
    out = tmp_path_factory.mktemp("failed")
    for s in FAST_SUITES:
        shutil.copytree(ROOT / "results" / s, out / s, ignore=shutil.ignore_patterns("*.png", "*.svg", "runs"))
        st = Store(out, s)
        _with_failures(st.load()).to_parquet(st.parquet, index=False)
    return out


@pytest.mark.parametrize("suite", FAST_SUITES)
def test_tables_show_failed_rows(failed_store, suite):
    runs = Store(failed_store, suite).load()
    assert runs["nfg"].isna().any()
    tables = build_tables(suite, runs)
    assert tables
    text = "\n".join(t.frame.to_string() for t in tables)
    assert "<NA>" not in text


def test_table_and_report_cli(failed_store, capsys):
    assert main(["table", "--suite", "hs", "--out", str(failed_store)]) == 0
    out = capsys.readouterr().out
    assert "timeout" in out or "error" in out
    assert main(["report", "--out", str(failed_store)]) == 0
    html = (failed_store / "report" / "index.html").read_text()
    assert "plug-in failed" not in html


def test_compare_with_rows_without_counts(failed_store):
    old = Store(ROOT / "results", "hs").load()
    new = Store(failed_store, "hs").load()
    res = compare_runs(old, new)
    failed = res.changes[res.changes["nfg_new"].isna()]
    assert len(failed) == new["nfg"].isna().sum()
    # a run solved before and failing now is a regression; one unsolved before is a change
    assert set(failed["verdict"]) <= {"changed"} | {v for v in failed["verdict"] if v.startswith("REGRESSION")}
    assert "—" in format_changes(res)
    back = compare_runs(new, old)  # and the other way round
    assert len(back.changes) == len(res.changes)


def test_compare_summarizes_unmatched_runs_in_short_lines():
    old = Store(ROOT / "results", "hs").load()
    text = format_changes(compare_runs(old.iloc[:0], old))  # every run "only in new"
    assert f"only in new: {len(old)} runs" in text
    assert max(len(line) for line in text.splitlines()) <= 120
    assert "more (--all lists every run)" in text


def test_history_plots_report_progress(tmp_path):
    import io

    from harness._plots import plot

    runs = Store(ROOT / "results", "hs").load()
    runs = runs[runs["problem"].isin(["hs010", "hs014", "hs022"])]
    buf = io.StringIO()
    paths = plot("hs", "history", out=tmp_path, runs=runs, progress=buf)
    assert len(paths) == 6 and "plot history: [3/3]" in buf.getvalue()
