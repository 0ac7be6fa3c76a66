"""The OptiProfiler export: histories expanded per evaluation, read back by OptiProfiler's own loader."""

import json

import numpy as np
import pandas as pd
import pytest

from harness._optiprofiler import export_optiprofiler, to_optiprofiler
from harness._plan import HarnessArgumentError


def _runs() -> pd.DataFrame:
    hist = [[1, 10.0, 0.5], [3, 4.0, 0.0], [5, 1.0, 0.0]]
    return pd.DataFrame([
        {"case_id": "p1", "solver": "a", "n": 2, "nfg": 5, "f": 1.0, "max_violation": 0.0, "wall_time_s": 0.1,
         "history": json.dumps(hist)},
        {"case_id": "p1", "solver": "b", "n": 2, "nfg": 2, "f": 7.0, "max_violation": 0.2, "wall_time_s": 0.2,
         "history": json.dumps([[1, 10.0, 0.5], [2, 7.0, 0.2]])},
    ])


def test_histories_are_per_evaluation_and_held():
    r = to_optiprofiler(_runs())
    assert r["solver_names"] == ["a", "b"]
    assert r["fun_histories"].shape == (1, 2, 1, 5)
    np.testing.assert_array_equal(r["fun_histories"][0, 0, 0], [10.0, 10.0, 4.0, 4.0, 1.0])
    np.testing.assert_array_equal(r["maxcv_histories"][0, 1, 0], [0.5, 0.2, 0.2, 0.2, 0.2])
    assert r["fun_inits"][0] == 10.0 and r["maxcv_inits"][0] == 0.5
    np.testing.assert_array_equal(r["n_evals"][0, :, 0], [5, 2])


def test_round_trip_through_optiprofilers_loader(tmp_path):
    loader = pytest.importorskip("optiprofiler.loader")
    path = export_optiprofiler(_runs(), tmp_path / "c.h5", plib="demo")
    back = loader.load_results_from_h5(path)[0]
    assert back["plib"] == "demo" and list(back["problem_names"]) == ["p1"]
    np.testing.assert_array_equal(back["fun_outs"][0, :, 0], [1.0, 7.0])


def test_a_failed_run_without_counts_has_no_evaluations():
    runs = pd.concat([_runs(), pd.DataFrame([{"case_id": "p2", "solver": "a", "n": 3, "nfg": pd.NA, "f": None,
                                              "max_violation": None, "wall_time_s": None, "history": None}])])
    r = to_optiprofiler(runs)
    assert r["n_evals"][1, 0, 0] == 0 and np.isnan(r["fun_histories"][1, 0, 0]).all()


def test_no_runs_is_an_error():
    with pytest.raises(HarnessArgumentError, match="no runs"):
        to_optiprofiler(_runs().iloc[:0])


def test_experiment_directory_loads_through_optiprofilers_benchmark_load_path(tmp_path, monkeypatch):
    """The directory layout is what `optiprofiler.benchmark(load="latest", benchmark_id=...)`
    reads: its own `load_results` finds the experiment, selects solvers and problems and
    keeps every field (drawing itself is left to OptiProfiler)."""
    loader = pytest.importorskip("optiprofiler.loader")
    runs = _runs().assign(problem=["HS71", "HS71"], success=[True, False])
    monkeypatch.chdir(tmp_path)
    export_optiprofiler(runs, "campaign", plib="demo")
    export_optiprofiler(runs, "campaign", plib="demo")  # re-export: still one experiment
    assert len(list((tmp_path / "campaign" / "demo" / "test_log").glob("time_stamp_*.txt"))) == 1
    results, opts = loader.load_results({}, {"load": "latest", "benchmark_id": "campaign"})
    r = results[0]
    assert opts["solver_names"] == ["a", "b"] and r["problem_names"] == ["p1"]
    assert r["problem_types"] == ["n"] and r["problem_mnlcons"][0] == 2  # HS71 from the S2MPJ catalogue
    np.testing.assert_array_equal(r["solvers_successes"][0, :, 0], [True, False])
    assert r["merit_outs"][0, 0, 0] == 1.0  # feasible end: the merit is f
    assert r["merit_histories"].shape == r["fun_histories"].shape
