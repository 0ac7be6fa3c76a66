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


for cls in (Raises, Sleeps, NaN):
    register(cls)
