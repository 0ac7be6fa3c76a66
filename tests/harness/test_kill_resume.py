"""kill -9 in the middle of a run loses only the runs in flight; a re-run completes the
store with no run missing or duplicated (docs/harness.md, "Durability")."""

import os
import signal
import subprocess
import sys
import textwrap
import time

import harness

SUITE = textwrap.dedent('''
    import dataclasses, time
    import numpy as np
    from problems import Problem
    from solvers import AbstractSolver, SolverOutput, Status, option, register, solver_names

    NAME = "napping"
    SOLVERS = ["nap"]
    PROBLEMS = [Problem(name=f"p{i:02d}", x0=np.full(2, float(i)), objective=lambda x: float(x @ x),
                        gradient=lambda x: 2 * x, f_ref=0.0) for i in range(16)]

    @dataclasses.dataclass(frozen=True)
    class Nap(AbstractSolver):
        name = "nap"
        summary = "sleeps, then one gradient step to the minimum"
        seconds: float = option(0.15, "nap length")

        def minimize(self, oracle):
            time.sleep(self.seconds)
            x = oracle.x0 - 0.5 * oracle.grad(oracle.x0)
            oracle.f(x)
            return SolverOutput(x, Status.CONVERGED, "done", nit=1)

    if "nap" not in solver_names():
        register(Nap)
''')


def test_kill_9_then_resume(tmp_path):
    suite = tmp_path / "napping.py"
    suite.write_text(SUITE)
    out = tmp_path / "res"
    cmd = [sys.executable, "-m", "harness", "run", "--suite-file", str(suite), "--out", str(out), "--jobs", "2"]
    proc = subprocess.Popen(cmd, cwd=os.path.dirname(harness.__path__[0]), start_new_session=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    pending = out / "napping" / "runs"
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        if pending.is_dir() and len(list(pending.glob("*.json"))) >= 4:
            break
        time.sleep(0.02)
    os.kill(proc.pid, signal.SIGKILL)  # the harness itself, mid-suite
    proc.wait()
    # its workers die with it (no orphan goes on computing runs nobody will store)
    for _ in range(200):
        try:
            os.killpg(proc.pid, 0)
        except ProcessLookupError:
            break
        time.sleep(0.05)
    else:
        os.killpg(proc.pid, signal.SIGKILL)
        raise AssertionError("worker processes outlived the killed harness")
    before = harness.load_results("napping", out)
    assert 4 <= len(before) < 16, len(before)
    s = harness.run_suite(suite_file=suite, out=out, jobs=2, progress=None)
    assert s.skipped == len(before) and s.executed == 16 - len(before)
    after = harness.load_results("napping", out)
    assert len(after) == 16 and after.problem.is_unique and after.run_key.is_unique
    assert set(after.problem) == {f"p{i:02d}" for i in range(16)}
    assert (after.status == "converged").all()
    # rows stored before the kill are the same rows afterwards (not re-run)
    kept = after.set_index("run_key").loc[before.run_key, "finished_at"]
    assert list(kept) == list(before.finished_at)


def test_sigterm_consolidates_and_exits_130(tmp_path):
    suite = tmp_path / "napping.py"
    suite.write_text(SUITE)
    out = tmp_path / "res"
    cmd = [sys.executable, "-m", "harness", "run", "--suite-file", str(suite), "--out", str(out), "--jobs", "2"]
    proc = subprocess.Popen(cmd, cwd=os.path.dirname(harness.__path__[0]), start_new_session=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    pending = out / "napping" / "runs"
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and not (pending.is_dir() and len(list(pending.glob("*.json"))) >= 2):
        time.sleep(0.02)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 130 and "resume" in err
    assert (out / "napping" / "runs.parquet").exists() and not list(pending.glob("*.json"))
    assert 2 <= len(harness.load_results("napping", out)) < 16



def test_worker_killed_by_sigterm_is_an_interrupt_not_an_error_row(tmp_path):
    """A batch system may SIGTERM every process of the group: a worker killed that way
    stops the campaign (nothing stored for its run) instead of recording a solver error."""
    import multiprocessing as mp

    import pytest

    from harness._plan import plan_runs
    from harness._pool import Slot
    from harness._suites import ref_for

    suite = tmp_path / "napping.py"
    suite.write_text(SUITE)
    ref = ref_for(file=suite)
    spec = plan_runs(ref, ref.load(), ["nap[seconds=30]"], ["p01"], timeout=60)[0]
    slot = Slot(mp.get_context("fork"))
    try:
        assert slot.conn.poll(30) and slot.receive() is None  # READY
        slot.submit(spec)
        time.sleep(0.2)
        os.kill(slot.proc.pid, signal.SIGTERM)
        assert slot.conn.poll(30)
        with pytest.raises(KeyboardInterrupt):
            slot.receive()
    finally:
        slot.kill()
