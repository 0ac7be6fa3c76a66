"""Profiles, plots, report, compare and baseline from stored runs (no solver re-runs)."""

import json

import numpy as np
import pandas as pd
import pytest

import harness
from harness._compare import compare_runs, load_counts, save_baseline
from harness._profiles import data_profile, performance_profile
from harness.cli import main


@pytest.fixture(scope="module")
def stored(tmp_path_factory, request):
    tiny = str(request.path.with_name("tiny_suite.py"))
    out = tmp_path_factory.mktemp("res")
    harness.run_suite(suite_file=tiny, solvers=["sqsd", "sqsd[rho=0.1]"], out=out, jobs=2, progress=None)
    return tiny, out


def _runs(rows):
    base = {"suite": "s", "settings": "{}", "settings_hash": "h", "status": "converged", "n": 2, "f_ref": 0.0,
            "history": "[]", "wall_time_s": 1.0}
    return pd.DataFrame([{**base, **r} for r in rows])


def test_performance_profile_by_hand():
    runs = _runs([
        {"case_id": "p1", "solver": "a", "nfg": 10, "success": True},
        {"case_id": "p1", "solver": "b", "nfg": 20, "success": True},
        {"case_id": "p2", "solver": "a", "nfg": 40, "success": True},
        {"case_id": "p2", "solver": "b", "nfg": 10, "success": False},  # unsolved: infinite ratio
    ])
    grid, rho = performance_profile(runs, "nfg")
    at = lambda tau: rho.iloc[np.searchsorted(grid, tau, side="right") - 1]
    assert at(0.0)["a"] == 1.0 and at(0.0)["b"] == 0.0
    assert at(1.0)["b"] == 0.5 and at(grid[-1])["b"] == 0.5


def test_data_profile_by_hand():
    h = lambda pts: json.dumps([[i + 1, f, 0.0] for i, f in enumerate(pts)])
    runs = _runs([
        {"case_id": "p1", "solver": "a", "nfg": 3, "success": True, "history": h([10.0, 1.0, 0.0])},
        {"case_id": "p1", "solver": "b", "nfg": 6, "success": True, "history": h([10.0, 9, 8, 7, 6, 0.5])},
    ])
    grid, d = data_profile(runs, tau=0.1)  # f_L = 0, target 1.0: a at 2 evals, b at 6 evals; n + 1 = 3
    assert d["a"].iloc[np.searchsorted(grid, 2 / 3, side="right") - 1] == 1.0
    assert d["b"].iloc[np.searchsorted(grid, 5.9 / 3, side="right") - 1] == 0.0
    assert d["b"].iloc[-1] == 1.0


def test_plot_kinds_and_report(stored, capsys):
    tiny, out = stored
    for kind in ("profile", "data-profile"):
        assert main(["plot", "--suite-file", tiny, "--kind", kind, "--out", str(out)]) == 0
    assert main(["plot", "--suite-file", tiny, "--kind", "history", "--problem", "rosen", "--out", str(out)]) == 0
    figs = out / "tiny" / "figures"
    for stem in ("profile_nfg", "profile_wall_time", "data_profile", "history_rosen_n=2_x1"):
        assert (figs / f"{stem}.png").stat().st_size > 1000 and (figs / f"{stem}.svg").exists()
    assert main(["plot", "--suite-file", tiny, "--kind", "history", "--problem", "zz", "--out", str(out)]) == 2
    assert main(["plot", "--suite-file", tiny, "--kind", "thesis", "--out", str(out)]) == 2  # no plug-in: bad input
    capsys.readouterr()
    assert main(["report", "--out", str(out)]) == 0
    page = (out / "report" / "index.html").read_text()
    assert "Tiny: N^fg per case" in page and "../tiny/figures/profile_nfg.png" in page
    assert "sqsd[rho=0.1]" in page and "not applicable" in page


def test_compare_and_baseline(stored, tmp_path, capsys):
    tiny, out = stored
    base = tmp_path / "baseline"
    save_baseline("tiny", out, base)
    assert main(["compare", str(base), str(out)]) == 0
    assert "0 regressions" in capsys.readouterr().out
    csv = base / "tiny" / "counts.csv"
    frame = pd.read_csv(csv, keep_default_na=False, na_values=[""])
    first = frame.index[frame.success][0]
    frame.loc[first, "nfg"] = frame.loc[first, "nfg"] // 2  # the baseline was cheaper: NEW regressed
    frame.to_csv(csv, index=False)
    assert main(["compare", str(base), str(out)]) == 1
    assert "REGRESSION: N^fg" in capsys.readouterr().out
    assert main(["compare", str(base), str(out), "--nfg-tol", "5"]) == 0
    capsys.readouterr()
    save_baseline("tiny", out, base)  # restore
    old = load_counts(base, "tiny")
    new = harness.load_results("tiny", out)
    solved = new.index[new.success][:2]
    worse = new.copy()
    worse.loc[solved[0], "nfg"] = int(worse.loc[solved[0], "nfg"] * 1.2) + 1
    worse.loc[solved[1], ["success", "status"]] = [False, "max_iter"]
    c = compare_runs(old, worse)
    assert len(c.regressions) == 2
    assert {v.split(":")[1].strip()[:4] for v in c.regressions.verdict} == {"N^fg", "solv"}
    assert len(compare_runs(old, worse, nfg_tol=10.0).regressions) == 1  # thresholds configurable
    # a changed settings hash still pairs the run (settings changed, same case and solver)
    moved = new.copy()
    moved.loc[moved.settings_hash == moved.settings_hash.iloc[0], "settings_hash"] = "changed"
    c = compare_runs(old, moved)
    assert len(c.changes) == len(old) and len(c.regressions) == 0


def test_compare_a_finished_time_out_is_a_matter_of_time_not_an_improvement():
    old = _runs([{"case_id": "p1", "solver": "a", "nfg": np.nan, "success": False, "status": "timeout",
                  "rel_error": np.nan, "f": np.nan},
                 {"case_id": "p2", "solver": "a", "nfg": 12, "success": True, "rel_error": 0.0, "f": 0.0}])
    new = _runs([{"case_id": "p1", "solver": "a", "nfg": 40, "success": True, "rel_error": 0.0, "f": 0.0},
                 {"case_id": "p2", "solver": "a", "nfg": np.nan, "success": False, "status": "timeout",
                  "rel_error": np.nan, "f": np.nan}])
    v = compare_runs(old, new).changes.set_index("case_id").verdict
    assert v["p1"] == "finished in time: timeout -> converged (solved)"
    assert v["p2"].startswith("REGRESSION: solved -> unsolved (timeout)")  # a new time-out still counts


def _search(case: str, nfg: int, solved: bool, stopped_by: str, **more):
    """A multistart row: solved at f = 0, or not at f = 1; ``stopped_by`` as its ``extra`` says."""
    return {"case_id": case, "solver": "m", "nfg": nfg, "success": solved, "rel_error": 0.0 if solved else 1.0,
            "f": 0.0 if solved else 1.0, "extra": json.dumps({"stopped_by": stopped_by}), **more}


def test_compare_a_run_cut_by_the_clock_is_never_a_regression():
    """A multistart search that its deadline ended fits more or fewer local runs on another
    machine: a difference there is "cut by the clock" on either side, not a regression."""
    old = _runs([_search("p1", 50, True, "confidence"), _search("p2", 80, True, "deadline"),
                 _search("p3", 90, False, "deadline"), _search("p4", 10, True, "confidence")])
    new = _runs([_search("p1", 30, False, "deadline", status="max_iter"), _search("p2", 200, True, "deadline"),
                 _search("p3", 90, False, "deadline"), _search("p4", 30, True, "confidence")])
    c = compare_runs(old, new)
    v = c.changes.set_index("case_id").verdict
    assert v["p1"] == "cut by the clock: solved -> unsolved"
    assert v["p2"] == "cut by the clock: changed" and v["p3"] == "same"
    assert v["p4"].startswith("REGRESSION: N^fg")  # not cut by the clock: judged as before
    assert list(c.regressions["case_id"]) == ["p4"]


def test_a_baseline_leaves_out_runs_cut_by_the_clock(tmp_path, monkeypatch):
    import harness._compare as cmp

    runs = _runs([_search("p1", 50, True, "deadline"), _search("p2", 10, True, "confidence")])
    runs = runs.assign(**{c: "" for c in cmp.BASELINE_COLUMNS if c not in runs})
    monkeypatch.setattr(cmp, "load_results", lambda suite, out: runs)
    save_baseline("s", tmp_path, tmp_path / "base")
    assert list(load_counts(tmp_path / "base", "s")["case_id"]) == ["p2"]


def test_baseline_of_some_solvers_keeps_the_other_rows(stored, tmp_path, capsys):
    """`baseline --solvers`: a deliberate change of one solver refreshes that solver's rows only."""
    tiny, out = stored
    base = tmp_path / "baseline"
    save_baseline("tiny", out, base)
    csv = base / "tiny" / "counts.csv"
    stored_rows = pd.read_csv(csv, keep_default_na=False, na_values=[""])
    edited = stored_rows.assign(nfg=stored_rows["nfg"] + 1000)  # every row of the baseline edited
    other = edited.head(1).assign(solver="other-solver")  # a solver without stored runs here
    pd.concat([edited, other]).to_csv(csv, index=False)
    assert main(["baseline", "--suite", "tiny", "--out", str(out), "--to", str(base), "--solvers", "sqsd"]) == 0
    after = pd.read_csv(csv, keep_default_na=False, na_values=[""])
    assert len(after) == len(stored_rows) + 1
    assert sorted(after[after.solver == "sqsd"].nfg) == sorted(stored_rows.nfg)  # refreshed from the runs
    assert list(after[after.solver == "other-solver"].nfg) == list(other.nfg)  # kept as it was
    assert main(["baseline", "--suite", "tiny", "--out", str(out), "--to", str(base), "--solvers", "nosuch"]) == 2
    assert "nosuch" in capsys.readouterr().err
