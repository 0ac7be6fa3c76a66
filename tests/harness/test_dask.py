"""Dask LocalCluster results equal the local executor's (counts and f of every run)."""

import pytest

import harness

distributed = pytest.importorskip("distributed")

COLS = ["nfg", "nf", "ng", "nit", "f", "status", "success", "settings_hash", "run_key"]


def test_dask_localcluster_equals_local(tiny_file, tmp_path):
    local = tmp_path / "local"
    harness.run_suite(suite_file=tiny_file, out=local, jobs=2, progress=None, timeout=60)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=True,
                                  dashboard_address=None) as cluster:
        s = harness.run_suite(suite_file=tiny_file, out=tmp_path / "dask", executor="dask",
                              scheduler=cluster.scheduler_address, progress=None, timeout=60)
        # the per-run time limit holds on Dask too
        mod = str(tiny_file).replace("tiny_suite.py", "bad_solvers.py")
        t = harness.run_suite(suite_file=tiny_file, out=tmp_path / "dask2", executor="dask", problems=["q2"],
                              solvers=["mod-sleeps", "mod-raises"], modules=[mod],
                              scheduler=cluster.scheduler_address, progress=None, timeout=1.0)
        assert t.failed == 2
        st = harness.load_results("tiny", tmp_path / "dask2").set_index("solver").status.to_dict()
        assert st == {"mod-sleeps": "timeout", "mod-raises": "error"}
    assert s.executed == 5
    a = harness.load_results("tiny", local).set_index("case_id").sort_index()[COLS]
    b = harness.load_results("tiny", tmp_path / "dask").set_index("case_id").sort_index()[COLS]
    assert a.equals(b), (a, b)


def test_dask_needs_scheduler(tiny_file, tmp_path):
    with pytest.raises(harness.HarnessArgumentError, match="scheduler"):
        harness.run_suite(suite_file=tiny_file, out=tmp_path, executor="dask", progress=None)
