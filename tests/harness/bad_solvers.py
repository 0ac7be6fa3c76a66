"""Misbehaving solvers for the fault-isolation tests (imported by path with --solver-module)."""

import dataclasses
import time

import numpy as np

from solvers import AbstractSolver, SolverOutput, Status, option, register


@dataclasses.dataclass(frozen=True)
class Raises(AbstractSolver):
    name = "mod-raises"
    summary = "raises after one evaluation"
    delay: float = option(0.0, "seconds to wait first")

    def minimize(self, oracle):
        oracle.f(oracle.x0)
        raise RuntimeError("solver exploded")


@dataclasses.dataclass(frozen=True)
class Sleeps(AbstractSolver):
    name = "mod-sleeps"
    summary = "never returns"

    def minimize(self, oracle):
        while True:
            time.sleep(1.0)


@dataclasses.dataclass(frozen=True)
class NaN(AbstractSolver):
    name = "mod-nan"
    summary = "returns a NaN point"

    def minimize(self, oracle):
        oracle.f(oracle.x0)
        return SolverOutput(np.full(oracle.n, np.nan), Status.CONVERGED, "claims success")


@dataclasses.dataclass(frozen=True)
class DiesOnce(AbstractSolver):
    """Its worker is killed by a signal (as by the OOM killer) the first time, per marker file."""

    name = "mod-dies-once"
    summary = "SIGKILLs its worker on the first call, then stops at x0"
    marker: str = option("", "file created when the worker has been killed once")

    def minimize(self, oracle):
        import os
        import pathlib
        import signal

        oracle.f(oracle.x0)
        if self.marker and not pathlib.Path(self.marker).exists():
            pathlib.Path(self.marker).touch()
            os.kill(os.getpid(), signal.SIGKILL)
        return SolverOutput(np.asarray(oracle.x0, dtype=float), Status.CONVERGED, "stopped at x0")


@dataclasses.dataclass(frozen=True)
class Slow(AbstractSolver):
    name = "mod-slow"
    summary = "waits, then stops at x0"
    delay: float = option(1.0, "seconds to wait")

    def minimize(self, oracle):
        time.sleep(self.delay)
        oracle.f(oracle.x0)
        return SolverOutput(np.asarray(oracle.x0, dtype=float), Status.CONVERGED, "stopped at x0")


for cls in (Raises, Sleeps, NaN, DiesOnce, Slow):
    register(cls)
