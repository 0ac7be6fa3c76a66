"""Dask LocalCluster results equal the local executor's (counts and f of every run)."""

import json
import os

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


def test_dask_workers_without_the_blas_pin_give_local_counts(tmp_path, monkeypatch):
    """Workers started without the harness's kernel pin (here: forced to the native AVX-512
    kernels where the CPU has them) still run every case under the harness's environment:
    SQSD on Wood's function needs 514 evaluations with the pinned kernels, 970 without."""
    local = tmp_path / "local"
    cases = ["a11/n=4/x0", "a10/n=2/x0"]
    harness.run_suite("appendix-a", solvers=["sqsd", "scipy-bfgs"], problems=cases, out=local, jobs=1,
                      progress=None)
    pinned = dict(os.environ)
    monkeypatch.setenv("OPENBLAS_CORETYPE", "SkylakeX")  # what an unpinned worker on this CPU would load
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "2")
    monkeypatch.setenv("NPY_DISABLE_CPU_FEATURES", "")  # and NumPy's native loops
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        for k in ("OPENBLAS_CORETYPE", "OPENBLAS_NUM_THREADS", "NPY_DISABLE_CPU_FEATURES"):  # the harness is pinned
            monkeypatch.setenv(k, pinned[k]) if k in pinned else monkeypatch.delenv(k)
        harness.run_suite("appendix-a", solvers=["sqsd", "scipy-bfgs"], problems=cases, out=tmp_path / "dask",
                          executor="dask", scheduler=cluster.scheduler_address, progress=None)
    a = harness.load_results("appendix-a", local).set_index(["case_id", "solver"]).sort_index()
    b = harness.load_results("appendix-a", tmp_path / "dask").set_index(["case_id", "solver"]).sort_index()
    assert a[["nfg", "nf", "ng", "nit", "status"]].equals(b[["nfg", "nf", "ng", "nit", "status"]]), (a.nfg, b.nfg)
    assert (a["f"].to_numpy() == b["f"].to_numpy()).all()  # bitwise
    manifest = json.loads((tmp_path / "dask" / "appendix-a" / "manifest.json").read_text())
    workers = manifest["latest"]["dask_workers"]
    assert workers and all(w["OPENBLAS_CORETYPE"] == pinned.get("OPENBLAS_CORETYPE") for w in workers.values())
    assert all(w["NPY_DISABLE_CPU_FEATURES"] == pinned.get("NPY_DISABLE_CPU_FEATURES") for w in workers.values())


def test_new_slot_keeps_the_daemon_flag_off_for_every_thread(monkeypatch):
    """Two threads of one daemonic Dask worker start their children at once: each child must see
    the daemon flag off while it starts (the flag is process-wide; a race once restored it under
    another thread's start), and the flag is back on afterwards."""
    import multiprocessing as mp
    import threading
    import time

    from harness import _dask

    proc = mp.current_process()
    seen: list[object] = []

    class FakeSlot:  # stands in for the spawned child: Slot.__init__ is where multiprocessing checks
        def __init__(self, ctx, die_with_parent):
            time.sleep(0.05)  # widen the window in which another thread could flip the flag back
            seen.append(proc._config.get("daemon"))

    monkeypatch.setattr(_dask, "Slot", FakeSlot)
    monkeypatch.setitem(proc._config, "daemon", True)
    threads = [threading.Thread(target=_dask._new_slot, args=(_dask.numeric_env(),)) for _ in range(3)]
    for t in threads:
        t.start()
        time.sleep(0.01)
    for t in threads:
        t.join()
    assert seen == [False, False, False]
    assert proc._config["daemon"] is True
