"""Retry policy of a resumed run (docs/harness.md, "Retry policy"): stored failures of the
infrastructure are run again, time-outs when the limit grows, everything with --retry-failed;
solver errors stay stored as results."""

import pathlib

import pytest

import harness
from harness._store import Store, failure_kind

HERE = pathlib.Path(__file__).parent
BAD = str(HERE / "bad_solvers.py")
TINY = str(HERE / "tiny_suite.py")


def _run(out, solvers, **kw):
    return harness.run_suite(suite_file=TINY, solvers=solvers, problems=["q2"], out=out, jobs=1, progress=None,
                             modules=[BAD], **kw)


def _rows(out):
    return Store(out, "tiny").load()


def test_failure_kinds():
    assert failure_kind("error", "worker process died (exit code -9)") == "infrastructure"
    assert failure_kind("error", "dask task failed: KilledWorker: ...") == "infrastructure"
    assert failure_kind("error", "MemoryError: (at lfop.py:10)") == "infrastructure"
    assert failure_kind("error", "RuntimeError: solver exploded") == "solver"
    assert failure_kind("timeout", "wall-clock limit of 1 s exceeded") == "timeout"
    assert failure_kind("converged", "") == ""



def test_a_run_that_exits_or_crashes_by_itself_is_its_own_result_not_retried():
    # exit(3) from the problem, a segmentation fault in a C solver: deterministic, so stored as results
    assert failure_kind("error", "worker process died (exit code 3)") == "solver"
    assert failure_kind("error", "worker process died (exit code -11)") == "solver"
    assert failure_kind("error", "worker process died while starting") == "infrastructure"
    # only a message that *is* a MemoryError counts, not one that mentions it
    assert failure_kind("error", "ValueError: not a MemoryError") == "solver"


def test_killed_worker_is_rerun(tmp_path):
    spec = f"mod-dies-once[marker={tmp_path / 'killed'}]"
    _run(tmp_path, [spec])
    first = _rows(tmp_path)
    assert list(first["status"]) == ["error"] and "worker process died" in first["message"].iloc[0]
    s = _run(tmp_path, [spec])
    assert s.executed == 1 and s.retried == 1
    again = _rows(tmp_path)
    assert len(again) == 1 and again["status"].iloc[0] == "converged"
    assert _run(tmp_path, [spec]).executed == 0  # a result is not run again


def test_solver_error_stays_unless_retry_failed(tmp_path):
    _run(tmp_path, ["mod-raises"])
    assert _run(tmp_path, ["mod-raises"]).executed == 0
    s = _run(tmp_path, ["mod-raises"], retry_failed=True)
    assert s.executed == 1 and s.retried == 1
    assert len(_rows(tmp_path)) == 1  # replaced, not duplicated


def test_timeout_rerun_only_with_a_larger_limit(tmp_path):
    _run(tmp_path, ["mod-slow[delay=2]"], timeout=0.5)
    rows = _rows(tmp_path)
    assert rows["status"].iloc[0] == "timeout" and rows["timeout_s"].iloc[0] == 0.5
    assert _run(tmp_path, ["mod-slow[delay=2]"], timeout=0.5).executed == 0
    assert _run(tmp_path, ["mod-slow[delay=2]"], timeout=0.4).executed == 0
    s = _run(tmp_path, ["mod-slow[delay=2]"], timeout=30)
    assert s.executed == 1 and s.retried == 1
    rows = _rows(tmp_path)
    assert len(rows) == 1 and rows["status"].iloc[0] == "converged" and rows["timeout_s"].iloc[0] == 30


@pytest.mark.parametrize("bad", [-5.0, float("nan")])
def test_bad_timeout_is_an_argument_error(tmp_path, bad):
    with pytest.raises(harness.HarnessArgumentError, match="--timeout"):
        _run(tmp_path, ["sqsd"], timeout=bad)
