"""A solver that raises, returns NaN or never returns yields error/timeout rows within the
time limit while every other run finishes; the harness itself exits 0."""

import dataclasses
import time

import numpy as np
import pytest

import harness
import solvers
from harness.cli import main
from solvers import AbstractSolver, SolverOutput, Status


@dataclasses.dataclass(frozen=True)
class _Raises(AbstractSolver):
    name = "test-raises"
    summary = "raises"

    def minimize(self, oracle):
        oracle.f(oracle.x0)
        raise RuntimeError("solver exploded")


@dataclasses.dataclass(frozen=True)
class _NaN(AbstractSolver):
    name = "test-nan"
    summary = "NaN point"

    def minimize(self, oracle):
        oracle.f(oracle.x0)
        return SolverOutput(np.full(oracle.n, np.nan), Status.CONVERGED, "claims success")


@dataclasses.dataclass(frozen=True)
class _Sleeps(AbstractSolver):
    name = "test-sleeps"
    summary = "never returns"

    def minimize(self, oracle):
        while True:
            time.sleep(1.0)


@dataclasses.dataclass(frozen=True)
class _Dies(AbstractSolver):
    name = "test-dies"
    summary = "kills its own process"

    def minimize(self, oracle):
        import os

        os._exit(3)


@pytest.fixture
def bad_solvers():
    classes = (_Raises, _NaN, _Sleeps, _Dies)
    for c in classes:
        solvers.register(c)
    yield [c.name for c in classes]
    for c in classes:
        solvers.unregister(c.name)


def test_errors_and_timeouts_are_rows(bad_solvers, tiny_file, tmp_path):
    t0 = time.perf_counter()
    s = harness.run_suite(suite_file=tiny_file, solvers=["sqsd", *bad_solvers], problems=["q2", "q20"],
                          out=tmp_path, jobs=2, timeout=1.5, progress=None)
    elapsed = time.perf_counter() - t0
    assert s.executed == 10
    df = harness.load_results("tiny", tmp_path).set_index(["problem", "solver"])
    for p in ("q2", "q20"):
        assert df.loc[(p, "sqsd"), "status"] == "converged"
        r = df.loc[(p, "test-raises")]
        assert r.status == "error" and "solver exploded" in r.message and r.nfg == 1 and not r.success
        r = df.loc[(p, "test-nan")]
        assert r.status == "error" and "non-finite" in r.message and not r.success
        r = df.loc[(p, "test-sleeps")]
        assert r.status == "timeout" and "1.5 s" in r.message and r.nfg is pd_na() and 1.4 < r.wall_time_s < 30
        r = df.loc[(p, "test-dies")]
        assert r.status == "error" and "worker process died (exit code 3)" in r.message

    assert elapsed < 60  # generous: the machine may be busy; "forever" would hang here


def pd_na():
    import pandas as pd

    return pd.NA


def test_solver_module_in_spawned_workers(tiny_file, tmp_path, capsys):
    """--solver-module: workers that do not inherit the parent (spawn) import it themselves."""
    mod = str(tiny_file).replace("tiny_suite.py", "bad_solvers.py")
    s = harness.run_suite(suite_file=tiny_file, solvers=["mod-raises", "mod-nan", "mod-sleeps"], problems=["q2"],
                          out=tmp_path, jobs=2, timeout=1.5, modules=[mod], start_method="spawn", progress=None)
    assert s.executed == 3 and s.failed == 3
    st = harness.load_results("tiny", tmp_path).set_index("solver").status.to_dict()
    assert st == {"mod-raises": "error", "mod-nan": "error", "mod-sleeps": "timeout"}
    # the CLI exits 0 whatever the solvers did
    assert main(["run", "--suite-file", tiny_file, "--solvers", "mod-raises", "--problems", "q20",
                 "--solver-module", mod, "--out", str(tmp_path), "--jobs", "1", "--quiet"]) == 0
